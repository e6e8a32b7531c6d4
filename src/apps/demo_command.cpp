#include "apps/demo_command.hpp"

#include <chrono>
#include <cstdio>
#include <sstream>

#include "telear/session/demo_workflow.hpp"

namespace telear::cli {

namespace {

using Clock = std::chrono::steady_clock;

struct Failure {
  std::string message;
};

constexpr int kSteps = 7;

std::pair<int, int> parse_resolution(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || x != 'x' || !in.eof() || w < 64 || h < 48 || w > 1920 || h > 1080) {
    throw Failure{"--resolution '" + text + "' must be WIDTHxHEIGHT within 64x48 .. 1920x1080"};
  }
  return {w, h};
}

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", seconds);
  return text;
}

}  // namespace

int run_demo(const DemoOptions& options, std::ostream& out, std::ostream& err) {
  const auto demo_start = Clock::now();
  session::DemoOptions demo;
  try {
    std::tie(demo.width, demo.height) = parse_resolution(options.resolution);
  } catch (const Failure& f) {
    err << "telear demo: " << f.message << "\n";
    return 2;
  }
  demo.out_dir = options.out;
  demo.cache_dir = options.cache;
  demo.delay_ms = options.delay_ms;
  demo.seed = options.seed;
  demo.fps = options.fps;
  demo.camera_fps = options.camera_fps;
  demo.video = !options.no_video;
  if (Status s = demo.validate(); !s) {
    err << "telear demo: " << s.error().message << "\n";
    return 2;
  }

  session::DemoProgress progress;
  progress.step = [&](int n, const std::string& what) {
    const double t = std::chrono::duration<double>(Clock::now() - demo_start).count();
    out << "[" << n << "/" << kSteps << "] " << what << " (" << seconds_text(t) << " s)"
        << std::endl;
  };
  progress.note = [&](const std::string& text) { out << "      " << text << "\n"; };
  auto outcome = session::run_demo(demo, progress);
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
