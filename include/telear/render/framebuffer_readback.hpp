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

core::Image read_bound_framebuffer_rgb(int width, int height);

}  // namespace telear::render
