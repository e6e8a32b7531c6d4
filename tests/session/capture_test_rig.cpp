#include "capture_test_rig.hpp"

#include <cstdlib>
#include <filesystem>

#include "telear/core/robot_loader.hpp"
#include "telear/sim/marker_observations.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/observations_file.hpp"
#include "telear/vision/registered_camera_file.hpp"
#include "telear/vision/registration.hpp"

namespace telear::test {

Result<PumaCaptureRig> load_puma_capture_rig() {
  auto model = core::load_robot("puma560");
  if (!model) return Error{"robot: " + model.error().message};
  auto rig = sim::load_stereo_rig(sim::default_rig_file("puma560"));
  if (!rig) return Error{"rig: " + rig.error().message};
  auto marker = core::marker_mount_for(**model);
  if (!marker) return Error{"marker: " + marker.error().message};
  return PumaCaptureRig{*model, std::move(*rig), *marker};
}

void CaptureRigTest::SetUp() {
  auto loaded = load_puma_capture_rig();
  ASSERT_TRUE(loaded) << loaded.error().message;
  model = loaded->model;
  rig = std::move(loaded->rig);
  marker = loaded->marker;
  dir = temp_dir.path();
  auto written = write_true_calibration(rig, dir);
  ASSERT_TRUE(written) << written.error().message;
  calibration = *written;
}

void CaptureRigTest::TearDown() {
  const char* keep = std::getenv("TELEAR_CAPTURE_TEST_KEEP");
  if (keep == nullptr || dir.empty()) return;
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path to = std::filesystem::path(keep) / test->name();
  std::error_code error;
  std::filesystem::remove_all(to, error);
  std::filesystem::create_directories(to, error);
  std::filesystem::copy(dir, to, std::filesystem::copy_options::recursive, error);
  if (error) ADD_FAILURE() << "TELEAR_CAPTURE_TEST_KEEP: " << to << ": " << error.message();
}

Result<Eigen::VectorXd> marker_visible_start() {
  vision::RegistrationObservations observations;
  if (std::filesystem::exists(TELEAR_TEST_MARKER_START_FILE)) {
    auto loaded = vision::load_observations_file(TELEAR_TEST_MARKER_START_FILE);
    if (!loaded) return loaded.error();
    observations = std::move(*loaded);
  } else {
    sim::MarkerObservationsOptions find;
    find.rig_file = sim::default_rig_file("puma560");
    find.configurations = 4;
    find.seed = 2;
    auto found = sim::simulate_marker_observations(find);
    if (!found) return found.error();
    observations = std::move(found->observations);
  }
  for (const auto& c : observations.configurations) {
    if (!c.left_pixels.empty() && !c.right_pixels.empty()) return c.q;
  }
  return Error{"the marker was not detected in both eyes anywhere"};
}

Result<std::string> write_true_calibration(const sim::StereoRig& rig,
                                           const std::filesystem::path& dir) {
  const std::string calibration = (dir / "calibration.yaml").string();
  const Status written = vision::write_files_atomically(
      {{calibration, vision::registered_camera_yaml(
                         rig.cameras, vision::right_from_left(rig.cameras.left.T_cam_base,
                                                              rig.cameras.right.T_cam_base))}});
  if (!written) return written.error();
  return calibration;
}

}  // namespace telear::test
