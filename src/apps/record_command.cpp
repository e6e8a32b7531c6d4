#include "apps/record_command.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <thread>

#include "apps/command_failure.hpp"
#include "telear/core/clock.hpp"
#include "telear/net/token_file.hpp"
#include "telear/record/server_recorder.hpp"

namespace telear::cli {
namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_signal(int) {
  g_interrupted = true;
}

}  // namespace

int run_record(const RecordOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear record"};
  if (options.robot_server.empty()) return fail("--robot HOST:PORT is required");
  if (options.output.empty()) return fail("-o FILE.mcap is required");
  if (!(options.seconds >= 0.0)) return fail("--seconds must be 0 (until interrupted) or more");
  record::ServerRecorderOptions recording;
  if (!options.token_file.empty()) {
    auto t = net::load_token_file(options.token_file);
    if (!t) return fail("--token-file: " + t.error().message);
    recording.token = *t;
  }
  recording.robot_address = options.robot_server;
  recording.tls_ca_file = options.tls_ca_file;
  recording.vision_address = options.vision_server;
  recording.state_rate_hz = options.state_rate_hz;
  recording.recorder.path = options.output;
  recording.recorder.metadata["recorded_by"] = "telear record";
  auto recorder = record::ServerRecorder::start(recording);
  if (!recorder) return fail(recorder.error().message, kExitFailure);

  g_interrupted = false;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  out << "recording " << options.robot_server
      << (options.vision_server.empty() ? std::string() : " and " + options.vision_server) << " to "
      << options.output << (options.seconds > 0 ? "" : " (Ctrl-C stops)") << std::endl;
  const std::int64_t start = core::monotonic_ns();
  while (!g_interrupted &&
         (options.seconds <= 0 ||
          static_cast<double>(core::monotonic_ns() - start) * 1e-9 < options.seconds)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  auto counts = (*recorder)->stop();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!counts) return fail(counts.error().message, kExitFailure);
  std::uint64_t messages = 0, dropped = 0;
  for (const auto& [topic, n] : counts->written) messages += n;
  for (const auto& [topic, n] : counts->dropped) dropped += n;
  out << "wrote " << options.output << ": " << messages << " messages, " << counts->bytes
      << " bytes";
  if (dropped > 0) out << ", " << dropped << " dropped (the writer could not keep up)";
  out << "\n";
  for (const auto& [topic, n] : counts->written) out << "  " << topic << " " << n << "\n";
  return 0;
}

}  // namespace telear::cli
