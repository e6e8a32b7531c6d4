// Google Benchmark program of the video's way from JPEG to texture (issue 23, item 5): per eye,
// TurboJPEG to RGB then the CPU's RGB -> RGBA pass and the upload (VideoBackground::upload), or
// TurboJPEG to the Y'CbCr planes (no colour conversion, no chroma upsampling) then the planes'
// upload and the GPU's conversion (VideoBackground::upload_planes), each to glFinish. The
// decode alone is timed too. On llvmpipe the "GPU" is the same CPU; on a GPU the conversion
// is free. The image: a textured test card encoded at the stream's quality (85, 4:2:0).
//   build/bench/video_upload_bench --benchmark_filter=1280

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "telear/net/jpeg_codec.hpp"
#include "telear/render/egl_context.hpp"
#include "telear/render/gl_objects.hpp"
#include "telear/render/video_background.hpp"

namespace {

using telear::core::Image;

// A test card with camera-like content: smooth colour gradients, edges and sensor noise (a
// flat image would decode unrealistically fast).
std::string test_card_jpeg(int width, int height) {
  Image rgb(width, height, 3);
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 4.0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool tile = ((x / 40) + (y / 40)) % 2 == 0;
      const double base[3] = {120 + 80 * std::sin(x * 0.01), 110 + 60 * std::cos(y * 0.013),
                              tile ? 180.0 : 60.0};
      for (int c = 0; c < 3; ++c) {
        rgb.at(x, y, c) =
            static_cast<std::uint8_t>(std::clamp(base[c] + noise(random), 0.0, 255.0));
      }
    }
  }
  telear::net::JpegEncoder encoder;
  return encoder.encode(rgb, 85).value();
}

void decode_rgb(benchmark::State& state) {
  const std::string jpeg =
      test_card_jpeg(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  telear::net::JpegDecoder decoder;
  for (auto _ : state) benchmark::DoNotOptimize(decoder.decode(jpeg));
}

void decode_planes(benchmark::State& state) {
  const std::string jpeg =
      test_card_jpeg(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  telear::net::JpegDecoder decoder;
  for (auto _ : state) benchmark::DoNotOptimize(decoder.decode_planes(jpeg));
}

// One eye's JPEG decoded and uploaded each iteration by `decode_and_upload(decoder, background)`.
template <typename DecodeAndUpload>
void run_upload(benchmark::State& state, DecodeAndUpload decode_and_upload) {
  const int width = static_cast<int>(state.range(0)), height = static_cast<int>(state.range(1));
  const std::string jpeg = test_card_jpeg(width, height);
  telear::net::JpegDecoder decoder;
  auto background = telear::render::VideoBackground::create(width, height);
  if (!background) {
    state.SkipWithError(background.error().message.c_str());
    return;
  }
  for (auto _ : state) {
    decode_and_upload(jpeg, decoder, *background);
    glFinish();
  }
}

void decode_rgb_and_upload(benchmark::State& state) {
  run_upload(state, [](const std::string& jpeg, telear::net::JpegDecoder& decoder,
                       telear::render::VideoBackground& background) {
    const Image rgb = decoder.decode(jpeg).value();
    background.upload(rgb.pixels.data(), telear::render::ChannelOrder::kRgb);
  });
}

void decode_planes_and_upload(benchmark::State& state) {
  run_upload(state, [](const std::string& jpeg, telear::net::JpegDecoder& decoder,
                       telear::render::VideoBackground& background) {
    background.upload_planes(decoder.decode_planes(jpeg).value());
  });
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Args({640, 480})->Args({1280, 720})->Unit(benchmark::kMillisecond)->MinTime(0.5);
}

BENCHMARK(decode_rgb)->Apply(sizes);
BENCHMARK(decode_planes)->Apply(sizes);
BENCHMARK(decode_rgb_and_upload)->Apply(sizes);
BENCHMARK(decode_planes_and_upload)->Apply(sizes);

}  // namespace

int main(int argc, char** argv) {
  auto context = telear::render::create_headless_context();
  if (!context) {
    std::fprintf(stderr, "video_upload_bench: %s\n", context.error().message.c_str());
    return 1;
  }
  std::printf("device: %s\n", (*context)->description().c_str());
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
