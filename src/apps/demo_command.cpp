#include "apps/demo_command.hpp"

#include <chrono>
#include <sstream>

#include "telear/core/image_size.hpp"
#include "telear/core/number_format.hpp"
#include "telear/lab/demo_workflow.hpp"

namespace telear::cli {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kSteps = 7;

std::string seconds_text(double seconds) {
  return core::format_fixed(seconds, 1);
}

}  // namespace

int run_demo(const DemoOptions& options, std::ostream& out, std::ostream& err) {
  const auto demo_start = Clock::now();
  lab::DemoOptions demo;
  auto size = core::parse_image_size(options.resolution, {64, 48}, {1920, 1080});
  if (!size) {
    err << "telear demo: --resolution: " << size.error().message << "\n";
    return 2;
  }
  demo.width = size->width;
  demo.height = size->height;
  demo.robot = options.robot;
  demo.tip = options.tip;
  auto geometry = options.geometry_options();
  if (!geometry) {
    err << "telear demo: " << geometry.error().message << "\n";
    return 2;
  }
  demo.geometry = *geometry;
  demo.out_dir = options.out;
  demo.cache_dir = options.cache;
  demo.delay_ms = options.delay_ms;
  demo.seed = options.seed;
  demo.fps = options.fps;
  demo.camera_fps = options.camera_fps;
  demo.live_multisample = options.live_multisample;
  // Recorded by default, so that the report has its plots; --record names the file.
  if (!options.no_record) {
    demo.record_path = options.record.empty() ? options.out + "/session.mcap" : options.record;
  }
  demo.video = !options.no_video;
  if (Status s = demo.validate(); !s) {
    err << "telear demo: " << s.error().message << "\n";
    return 2;
  }

  lab::DemoProgress progress;
  progress.step = [&](int n, const std::string& what) {
    const double t = std::chrono::duration<double>(Clock::now() - demo_start).count();
    out << "[" << n << "/" << kSteps << "] " << what << " (" << seconds_text(t) << " s)"
        << std::endl;
  };
  progress.note = [&](const std::string& text) { out << "      " << text << "\n"; };
  auto outcome = lab::run_demo(demo, progress);
  if (!outcome) {
    err << "telear demo: " << outcome.error().message << "\n";
    return 2;
  }
  if (!outcome->video_warning.empty())
    err << "telear demo: warning: " << outcome->video_warning << "\n";
  out << "telear demo: wrote " << outcome->report_md << ", report.json, "
      << outcome->key_frames.size() << " key frames"
      << (outcome->video_path.empty() ? "" : ", " + outcome->video_path) << " in "
      << seconds_text(outcome->seconds) << " s\n";
  return outcome->execution_result == "completed" ? 0 : 1;
}

}  // namespace telear::cli
