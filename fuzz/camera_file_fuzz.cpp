// Door: camera and calibration files: telear's own YAML (vision::parse_camera_yaml), the
// observations of a registration (vision::parse_observations_yaml) and a capture folder's
// manifest (vision::parse_capture_manifest). The first byte picks which.

#include "fuzz_input.hpp"
#include "telear/vision/camera_file.hpp"
#include "telear/vision/capture_folder.hpp"
#include "telear/vision/observations_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace telear;
  const auto [door, text] = fuzz::door_input(data, size, 3);
  switch (door) {
    case 0:
      (void)vision::parse_camera_yaml(text, "fuzz_camera.yaml");
      break;
    case 1:
      (void)vision::parse_observations_yaml(text, "fuzz_observations.yaml");
      break;
    default:
      (void)vision::parse_capture_manifest(text, "fuzz_capture");
      break;
  }
  return 0;
}
