#pragma once
// Predictive sampling of the enhanced Render Cache (Walter et al. 2002): the
// camera of the next frame, guessed from the last two, so rays can be sent
// where holes will open before they do.
#include "scene/Camera.h"

namespace raycache {

// `current` moved on by the step from `previous` to `current` (eye and
// look-at alike); up and field of view as in `current`.
Camera predictNextCamera(const Camera& previous, const Camera& current);

}  // namespace raycache
