#pragma once
// What the operator's AR view draws for a session frame: the one mapping from the session's
// view (display decision, frame, ghost, reported state) to render::ArViewInput, shared by
// the demo and the console.

#include "telear/render/ar_view.hpp"
#include "telear/session/session.hpp"

namespace telear::lab {

// The returned input points into `view.frame`: keep `view` alive while rendering it.
render::ArViewInput ar_view_input(const session::SessionView& view);

}  // namespace telear::lab
