// Door: a pair of ROS camera_info messages, as the vision server's ROS 1 source receives them
// from any node on the ROS graph (drivers::ros1::calibration_from_camera_info: the lens model,
// D, K, R, P, binning and region of interest checked, a rectified pair's baseline recovered),
// and the stereo camera file it makes, read back as a client reads it (parse_camera_yaml).
// The input is the two messages' fields (fuzz::ByteReader's layout; fuzz/seeds/camera_info.py
// writes the seeds), then the two image topics' sizes.

#include "drivers/ros1/camera_info_calibration.hpp"
#include "fuzz_input.hpp"
#include "telear/vision/camera_file.hpp"

namespace {

using telear::drivers::ros1::CameraInfoFields;

CameraInfoFields read_camera_info(telear::fuzz::ByteReader& in) {
  CameraInfoFields info;
  info.topic = in.string();
  info.frame_id = in.string();
  info.width = in.take<std::int32_t>();
  info.height = in.take<std::int32_t>();
  info.distortion_model = in.string();
  info.D.resize(in.take<std::uint8_t>() % 16);
  for (double& d : info.D) d = in.take<double>();
  for (double& k : info.K) k = in.take<double>();
  for (double& r : info.R) r = in.take<double>();
  for (double& p : info.P) p = in.take<double>();
  info.binning_x = in.take<std::int32_t>();
  info.binning_y = in.take<std::int32_t>();
  info.roi_x_offset = in.take<std::int32_t>();
  info.roi_y_offset = in.take<std::int32_t>();
  info.roi_width = in.take<std::int32_t>();
  info.roi_height = in.take<std::int32_t>();
  return info;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace telear;
  fuzz::ByteReader in(data, size);
  const CameraInfoFields left = read_camera_info(in);
  const CameraInfoFields right = read_camera_info(in);
  drivers::ros1::TopicImageSize left_image{left.topic, in.take<std::int32_t>(),
                                           in.take<std::int32_t>()};
  drivers::ros1::TopicImageSize right_image{right.topic, in.take<std::int32_t>(),
                                            in.take<std::int32_t>()};
  auto calibration =
      drivers::ros1::calibration_from_camera_info(left, right, left_image, right_image);
  if (calibration && !calibration->yaml.empty()) {
    (void)vision::parse_camera_yaml(calibration->yaml, "fuzz camera_info");
  }
  return 0;
}
