#pragma once
// SyntheticSource: stereo pairs generated cheaply at any size and rate, for benchmarks and
// tests (`telear bench stream` measures the pipeline, not a renderer or a camera).
//
// A few distinct pairs are made once at construction (a seeded mix of gradients, a checker,
// a moving bar and per-pixel noise, so JPEG sizes are like a camera's, not like a flat
// image's) and cycled; each capture() copies one and stamps it with the capture time; with
// `frame_code` it also writes each eye's frame number and capture time into its pixels
// (telear/vision/frame_code.hpp: glass-to-glass latency, `telear bench latency`).

#include <cstdint>
#include <vector>

#include "telear/vision/stereo_source.hpp"

namespace telear::vision {

struct SyntheticSourceOptions {
  int width = 640, height = 480;  // 16..8192
  double fps = 30.0;              // > 0
  int distinct_frames = 8;        // 1..64 pre-made pairs, cycled
  double noise_sigma = 4.0;       // grey levels
  std::uint64_t seed = 1;
  bool frame_code = false;  // stamp each eye with its frame code (needs at least 304x64)
};

class SyntheticSource final : public StereoSource {
 public:
  static Result<std::unique_ptr<SyntheticSource>> create(const SyntheticSourceOptions& options);

  std::string name() const override { return "synthetic"; }
  int width() const override { return options_.width; }
  int height() const override { return options_.height; }
  double fps() const override { return options_.fps; }
  Result<StereoCapture> capture() override;

 private:
  explicit SyntheticSource(const SyntheticSourceOptions& options);
  SyntheticSourceOptions options_;
  std::vector<core::Image> left_, right_;
  FramePacer pacer_;
  std::uint64_t frame_ = 0;
};

}  // namespace telear::vision
