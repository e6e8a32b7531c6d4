#pragma once
// The frame code (telear/vision/frame_code.hpp) read back from what the operator's view has
// just drawn: the last step of glass-to-glass latency, capture -> shown (docs/latency.md).
//
// Only the code's strip is read (272 x 32 px of the eye: one small glReadPixels, not the whole
// image). The strip's pixels land where the source wrote them only when the video is drawn
// unscaled and unwarped: the AR view in raw overlay mode (render::OverlayMode::kRaw; the
// undistorted mode remaps the picture) with its eye at the video's size, which is how
// render::ArView draws a frame that fits its cameras. Otherwise -- undistorted video, a scaled
// stream, no video (VR), a ghost drawn over the corner -- the code reads as absent: the
// figure is "not measurable", never a wrong time.
//
// "Shown" is when the read returns: glReadPixels waits until the drawing into the eye has
// finished, so the frame is in the frame buffer the window presents next. A display adds its
// own delay on top (the next refresh, up to one period, and the panel's response), which only
// a camera filming the screen measures.

#include <cstdint>
#include <optional>

#include "telear/render/offscreen_target.hpp"
#include "telear/vision/frame_code.hpp"

namespace telear::render {

struct ShownFrameCode {
  std::optional<vision::FrameCode> code;  // nullopt: no readable code in the target
  std::int64_t shown_ns = 0;              // monotonic_ns when the read-back returned
};

// Reads and decodes the code's strip of `target` (an eye the video was drawn into). A target
// with no room for the code (under 304 x 64) reads nothing and gives no code. Needs the
// target's context current.
ShownFrameCode read_shown_frame_code(const OffscreenTarget& target);

}  // namespace telear::render
