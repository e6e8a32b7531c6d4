#pragma once
// What the operator's AR view draws for a session frame: the one mapping from the session's
// view (display decision, frame, ghost, reported state) to render::ArViewInput, shared by
// the console and the demo's recorder. Its own layer, above session and render, so that the
// console reaches it without the simulator (docs/architecture.md).

#include "telear/render/ar_view.hpp"
#include "telear/session/session.hpp"

namespace telear::view {

// The returned input points into `view.frame`: keep `view` alive while rendering it.
render::ArViewInput ar_view_input(const session::SessionView& view);

}  // namespace telear::view
