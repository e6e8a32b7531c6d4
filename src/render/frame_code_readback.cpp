#include "telear/render/frame_code_readback.hpp"

#include "telear/core/clock.hpp"

namespace telear::render {

ShownFrameCode read_shown_frame_code(const OffscreenTarget& target) {
  ShownFrameCode shown;
  const auto rect = vision::frame_code_rect(target.width(), target.height());
  if (!rect) {
    shown.shown_ns = core::monotonic_ns();
    return shown;
  }
  // RGBA: the driver's fast path, and the decoder reads four channels as well as three.
  core::Image strip(rect->width, rect->height, 4);
  target.read_region(rect->x, rect->y, rect->width, rect->height, 4, strip.pixels.data());
  shown.shown_ns = core::monotonic_ns();
  shown.code = vision::read_frame_code(strip, 0, 0);
  return shown;
}

}  // namespace telear::render
