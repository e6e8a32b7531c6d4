#pragma once
// Reading the bound GL read framebuffer (an offscreen target's, or a window's back buffer)
// into image order: top row first, tightly packed RGB or RGBA. GL's rows run bottom-up, so
// the rows are flipped on the way; RGBA is read (the driver's fast path on llvmpipe) and
// packed to RGB on the CPU. Needs a current context; waits for rendering to finish.

#include <cstdint>
#include <vector>

#include "telear/core/image.hpp"

namespace telear::render {

// `pixels` holds width * height * channels bytes (channels 3 or 4); `scratch` is reused
// between calls to spare an allocation per frame.
void read_bound_framebuffer(int width, int height, int channels, std::uint8_t* pixels,
                            std::vector<std::uint8_t>& scratch);

// The rectangle whose bottom-left pixel is (x, y_bottom) in GL's convention (rows counted
// from the bottom), into image order likewise: what a small read-back (the frame code's strip,
// telear/render/frame_code_readback.hpp) asks for instead of the whole framebuffer.
void read_bound_framebuffer_region(int x, int y_bottom, int width, int height, int channels,
                                   std::uint8_t* pixels, std::vector<std::uint8_t>& scratch);

core::Image read_bound_framebuffer_rgb(int width, int height);

}  // namespace telear::render
