#pragma once
#include "core/Vec3.h"

namespace raycache {

// Pinhole camera. The image plane's vertical extent is set by verticalFovDeg;
// the horizontal extent follows the image aspect ratio.
struct Camera {
    Vec3 position{0.0f, 0.0f, 5.0f};
    Vec3 lookAt{0.0f, 0.0f, 0.0f};
    Vec3 up{0.0f, 1.0f, 0.0f};
    float verticalFovDeg = 45.0f;

    bool operator==(const Camera&) const = default;
};

}  // namespace raycache
