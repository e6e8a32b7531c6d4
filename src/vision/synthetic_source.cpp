#include "telear/vision/synthetic_source.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "telear/core/image_size.hpp"
#include "telear/vision/frame_code.hpp"

namespace telear::vision {
namespace {

// One eye's image k: gradients and a checker shifted by `disparity` (the right eye sees the
// scene shifted), a bar moving with k, and uniform-ish noise.
core::Image make_image(int width, int height, int k, int disparity, double sigma,
                       std::mt19937_64& rng) {
  core::Image image(width, height, 3);
  std::uniform_real_distribution<double> noise(-sigma * std::sqrt(3.0), sigma * std::sqrt(3.0));
  const int bar_x = (k * width / 16) % std::max(1, width);
  for (int y = 0; y < height; ++y) {
    std::uint8_t* row = image.row(y);
    for (int x = 0; x < width; ++x) {
      const int xs = x + disparity;
      const bool check = ((xs / 32) + (y / 32)) % 2 == 0;
      double r = 255.0 * xs / width, g = 255.0 * y / height, b = check ? 200.0 : 60.0;
      if (std::abs(x - bar_x) < width / 40 + 2) r = g = b = 240.0;
      const double values[3] = {r, g, b};
      for (int c = 0; c < 3; ++c) {
        row[x * 3 + c] =
            static_cast<std::uint8_t>(std::clamp(std::lround(values[c] + noise(rng)), 0L, 255L));
      }
    }
  }
  return image;
}

}  // namespace

Result<std::unique_ptr<SyntheticSource>> SyntheticSource::create(
    const SyntheticSourceOptions& options) {
  if (options.width < 16 || options.height < 16 || options.width > 8192 || options.height > 8192) {
    return Error{"synthetic source: size " +
                 core::to_string(core::ImageSize{options.width, options.height}) +
                 " is outside 16x16 .. 8192x8192"};
  }
  if (!(options.fps > 0.0 && options.fps <= 10000.0)) {
    return Error{"synthetic source: fps must be in (0, 10000]"};
  }
  if (options.distinct_frames < 1 || options.distinct_frames > 64) {
    return Error{"synthetic source: distinct_frames must be in 1..64"};
  }
  if (options.frame_code && !frame_code_rect(options.width, options.height)) {
    return Error{"synthetic source: the frame code needs at least 304x64 pixels, the size is " +
                 core::to_string(core::ImageSize{options.width, options.height})};
  }
  return std::unique_ptr<SyntheticSource>(new SyntheticSource(options));
}

SyntheticSource::SyntheticSource(const SyntheticSourceOptions& options)
    : options_(options), pacer_(options.fps) {
  std::mt19937_64 rng(options.seed);
  for (int k = 0; k < options.distinct_frames; ++k) {
    left_.push_back(make_image(options.width, options.height, k, 0, options.noise_sigma, rng));
    right_.push_back(
        make_image(options.width, options.height, k, options.width / 40, options.noise_sigma, rng));
  }
}

Result<StereoCapture> SyntheticSource::capture() {
  pacer_.wait();
  StereoCapture out;
  out.frame_number = ++frame_;
  const std::size_t k = (frame_ - 1) % left_.size();
  out.capture_ns_left = core::monotonic_ns();
  out.left = left_[k];
  out.capture_ns_right = core::monotonic_ns();
  out.right = right_[k];
  if (options_.frame_code) {
    const auto number = static_cast<std::uint32_t>(out.frame_number);
    write_frame_code(out.left, {number, out.capture_ns_left});
    write_frame_code(out.right, {number, out.capture_ns_right});
  }
  return out;
}

}  // namespace telear::vision
