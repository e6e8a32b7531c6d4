#pragma once
// `telear bench stream`: the robot and vision services measured end to end through the real
// servers on loopback (docs/benchmarks.md, "Stream"):
//
//   video   per stereo resolution: a VisionServer on 127.0.0.1:0 with the synthetic source
//           (telear/vision/synthetic_source.hpp) paced at source_fps, one VisionClient over gRPC;
//           sustained decoded fps, per-stage latency p50 / p99 (DecodedStereoFrame.latency:
//           capture -> encode start, encode, send queue, network, decode, total capture ->
//           decoded) and bytes per frame, against the targets;
//   baseline the same run's raw TurboJPEG encode + decode of one stereo pair at the same size
//           and quality, so the pipeline's latency reads as k x codec time across machines;
//   robot   a RobotServer (simulated driver) on 127.0.0.1:0, a RobotClient holding the lease:
//           round trip p50 / p99 of Ping and of SetGripper (an authenticated, lease-checked
//           command);
//   command plan-then-send vs streaming jog at 100 Hz for the same 10 s motion, in bytes
//           (telear/net/command_bytes.hpp).
//
// The source runs faster than the targets (default 120 fps), so the fps column is the
// pipeline's capacity on this machine and the latencies are measured under that load (a
// camera at 60 or 30 fps loads it less).

#include <iosfwd>
#include <string>

namespace telear::cli {

struct StreamBenchOptions {
  double seconds = 3.0;                          // measured per resolution (after a warm-up)
  std::string resolutions = "640x480,1280x720";  // WxH per eye, comma-separated
  double source_fps = 120.0;                     // the synthetic source's rate
  int quality = 85;                              // JPEG quality 1..100
  int rtt_calls = 500;                           // per robot command kind
  std::string json;                              // also write the results as JSON to this file
  bool sequential_decode = false;  // the client decodes the eyes in turn (the comparison)
  bool decode_planes = false;      // the client decodes to Y'CbCr planes (--planes)
};

int run_bench_stream(const StreamBenchOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
