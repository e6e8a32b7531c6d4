#pragma once
// A decoded JPEG as its planes (JFIF Y'CbCr, full range, BT.601 coefficients), before the
// colour conversion: the luma plane at the image's size and two chroma planes at the
// subsampled size (4:2:0: half width and height, rounded up). Each plane is tightly packed,
// top row first. The renderer converts them on the GPU (render::VideoBackground::
// upload_planes); luma alone is the grey image marker detection wants; to_rgb() is the CPU
// conversion for the rare consumer that needs RGB (a registration capture).

#include <cstdint>
#include <vector>

#include "telear/core/image.hpp"

namespace telear::core {

struct YCbCrImage {
  int width = 0, height = 0;                // luma, the image's size
  int chroma_width = 0, chroma_height = 0;  // Cb and Cr
  std::vector<std::uint8_t> y, cb, cr;

  bool empty() const { return y.empty(); }
  // The luma plane as a grey image (a copy).
  Image luma() const;
};

// The subsampling factor along one axis: luma pixels per chroma pixel (2 for 4:2:0; an odd
// size's chroma plane rounds up, so the factor is ceil(luma / chroma)).
int chroma_factor(int luma_size, int chroma_size);

// RGB8 from the planes: chroma sampled at each pixel's centre, bilinear between chroma samples
// (libjpeg's "fancy" upsampling is the same triangle filter for 2:1; results agree within
// 1-2 levels), the JFIF conversion R = Y + 1.402 (Cr - 128), G = Y - 0.344136 (Cb - 128) -
// 0.714136 (Cr - 128), B = Y + 1.772 (Cb - 128), rounded and clamped. An empty image for
// planes whose sizes do not fit together.
Image to_rgb(const YCbCrImage& planes);

}  // namespace telear::core
