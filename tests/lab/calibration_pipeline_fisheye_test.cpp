// The calibrate -> register -> evaluate pipeline on the fisheye rig
// (data/rigs/puma560_fisheye_rig.yaml) at a small scale (8 views, 8 marker configurations, 2x
// supersampling): the calibration step uses the rig's lens model, so the stereo file carries
// equidistant cameras and the evaluation is close to the truth.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "telear/lab/calibration_pipeline.hpp"
#include "telear/vision/camera_file.hpp"
#include "test_util/temp_dir.hpp"
#include "test_util/test_util.hpp"

namespace telear::lab {
namespace {

namespace fs = std::filesystem;

TEST(CalibrationPipelineFisheye, CalibratesWithTheRigsLensModel) {
  test_files::TempDir tmp("pipeline_fisheye");
  const fs::path cache = tmp.file("cache");
  CalibrationPipelineOptions options;
  options.rig_file = test::data_path("rigs/puma560_fisheye_rig.yaml");
  options.cache_dir = cache.string();
  options.views = 8;
  options.configurations = 8;
  options.supersample = 2;

  auto result = run_calibration_pipeline(options);
  ASSERT_TRUE(result.ok()) << result.error().message;
  auto cameras = vision::load_camera_file((cache / "stereo.yaml").string());
  ASSERT_TRUE(cameras.ok()) << cameras.error().message;
  EXPECT_EQ(cameras->left.kc.model, vision::DistortionModel::equidistant);
  ASSERT_TRUE(cameras->right.has_value());
  EXPECT_EQ(cameras->right->kc.model, vision::DistortionModel::equidistant);
  const CalibrationEvaluation& e = result->evaluation;
  for (const EyeEvaluation* eye : {&e.left, &e.right}) {
    std::printf("fx %+.3f %%, cx %+.2f px, registration %.2f mm, overlay %.3f px RMS\n",
                eye->fx_error_percent, eye->cx_error_px, eye->registration_mm, eye->overlay_rms_px);
    EXPECT_LT(std::abs(eye->fx_error_percent), 0.5);
    EXPECT_LT(eye->registration_mm, 5.0);
    EXPECT_LT(eye->overlay_rms_px, 1.0);
  }
}

}  // namespace
}  // namespace telear::lab
