#pragma once
// `telear bench latency`: glass to glass on one machine (docs/latency.md, docs/benchmarks.md
// "Latency: capture -> shown"). A VisionServer on 127.0.0.1:0 with the synthetic source
// (telear/vision/synthetic_source.hpp) paced at `fps` and stamping every eye with its frame
// code, one VisionClient, and a headless EGL AR view (render::ArView: the PUMA's ghost over the
// video, raw overlay mode, cameras of the stream's size) that draws each newly decoded frame
// and reads the code back from the left eye's frame buffer (telear/render/frame_code_readback.hpp).
//
// Per frame, cumulative from the capture, on the client's clock (server stamps converted with
// the clock offset): encoded (capture -> encode end), received, decoded (the stream's stages,
// telear/net/latency_stages.hpp) and shown (the frame code's capture time -> the read-back of
// the drawn eye). Reported: p50 / p99 of each, frames measured at the screen, source frames
// never shown (lost: the latest-wins pipeline skipped them), frames drawn without a readable
// code, and the goal (capture -> shown p50 <= 20 ms at 640x480).

#include <iosfwd>
#include <string>

namespace telear::cli {

struct LatencyBenchOptions {
  std::string resolution = "640x480";  // WxH per eye, at least 304x64 (the frame code's room)
  double seconds = 5.0;                // measured, after a 0.5 s warm-up
  double fps = 30.0;                   // the source's rate, like a camera
  int quality = 85;                    // JPEG quality 1..100
  std::string json;                    // also write the results as JSON to this file
};

int run_bench_latency(const LatencyBenchOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
