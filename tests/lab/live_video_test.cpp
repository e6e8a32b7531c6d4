// The demo's live video as the simulated rig renders it (lab::DemoOptions' anti-aliasing): the
// gripper's marker is found where the true camera projects its corners, to the accuracy the
// live registration check reports as overlay error (issue 26: point-sampled frames put the
// marker's edges on whole pixels, and the live residual read ~0.45 px while the overlay itself
// was off by ~0.1 px).

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <opencv2/core.hpp>

#include "telear/lab/demo_workflow.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/sim/marker_observations.hpp"
#include "telear/sim/rig_robot.hpp"
#include "telear/sim/scene_renderer.hpp"
#include "telear/sim/stereo_rig.hpp"
#include "telear/vision/marker_detection.hpp"

namespace telear::lab {
namespace {

struct CornerErrors {
  double rms_px = 0.0;
  int markers = 0;  // detected (eye, configuration) pairs
};

// The marker's corners detected in frames rendered with the live video's anti-aliasing, at
// the first `count` configurations where the simulator's observations saw it in both eyes,
// against their projections through the rig's true cameras.
CornerErrors live_corner_errors(int multisample, int count) {
  auto rig = sim::load_stereo_rig(sim::default_rig_file());
  EXPECT_TRUE(rig.ok()) << rig.error().message;
  auto robot = sim::load_rig_robot(*rig);
  EXPECT_TRUE(robot.ok()) << robot.error().message;
  sim::MarkerObservationsOptions observe;
  observe.rig_file = sim::default_rig_file();
  observe.configurations = 2 * count;
  observe.supersample = 1;
  auto observed = sim::simulate_marker_observations(observe);
  EXPECT_TRUE(observed.ok()) << observed.error().message;

  auto context = render::create_headless_context();
  EXPECT_TRUE(context.ok()) << context.error().message;
  sim::SceneOptions options;  // as sim::SimRigSource renders the live video
  options.supersample = 1;
  options.multisample = multisample;
  options.fast_noise = true;
  options.marker = robot->description.marker;
  auto scene = sim::SceneRenderer::create(*rig, *robot->model(), robot->body, options);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene.ok() || !observed.ok()) return {};

  CornerErrors errors;
  double sum_sq = 0.0;
  int corners = 0, used = 0;
  for (const auto& c : observed->observations.configurations) {
    if (c.left_pixels.empty() || c.right_pixels.empty() || used == count) continue;
    ++used;
    scene->set_configuration(c.q);
    const auto truth_base = scene->marker_corners_base();
    for (const sim::Eye eye : {sim::Eye::kLeft, sim::Eye::kRight}) {
      const core::Image image = scene->render(eye, static_cast<std::uint64_t>(used));
      const cv::Mat rgb(image.height, image.width, CV_8UC3,
                        const_cast<std::uint8_t*>(image.pixels.data()));
      const auto found = vision::detect_aruco_marker(rgb, scene->marker()->mount.id);
      if (found.size() != 4) continue;
      // The demo's views show the marker 18-26 px wide; below that its cells are under 3 px
      // and the edge fit is out of its range (the check then reports contour corners).
      if ((found[1] - found[0]).norm() < 18.0) continue;
      ++errors.markers;
      for (int k = 0; k < 4; ++k) {
        const auto truth = rig->camera(eye).project(truth_base[k]);
        EXPECT_TRUE(truth.has_value());
        if (!truth) continue;
        sum_sq += (found[k] - *truth).squaredNorm();
        ++corners;
      }
    }
  }
  errors.rms_px = corners > 0 ? std::sqrt(sum_sq / corners) : 0.0;
  return errors;
}

TEST(LiveVideo, TheDemosLiveFramesShowTheMarkerWhereTheTrueCameraPutsIt) {
  const DemoOptions demo;
  const CornerErrors live = live_corner_errors(demo.live_multisample, 8);
  std::cout << "marker corners vs truth, " << demo.live_multisample << " samples per pixel: RMS "
            << live.rms_px << " px over " << live.markers << " detections\n";
  ASSERT_GE(live.markers, 10);
  // The demo's live residual is held at <= 0.25 px (docs/demo.md); the detector's share of
  // it must be well under that.
  EXPECT_LT(live.rms_px, 0.15);
}

// Why: the same frames point-sampled put the edges on whole pixels.
TEST(LiveVideo, PointSampledFramesMoveTheMarkersCornersByTenthsOfAPixel) {
  const CornerErrors point_sampled = live_corner_errors(1, 8);
  std::cout << "marker corners vs truth, point-sampled: RMS " << point_sampled.rms_px << " px\n";
  ASSERT_GE(point_sampled.markers, 10);
  EXPECT_GT(point_sampled.rms_px, 0.2);
}

}  // namespace
}  // namespace telear::lab
