#pragma once
#include "core/Rgb.h"
#include "core/Vec3.h"

namespace raycache {

enum class LightType { Point, Directional, Spot };

// Lights have no distance falloff (classic Whitted). A spot light is a point
// light restricted to a cone: full intensity inside coneAngle - falloffAngle,
// fading smoothly to zero at coneAngle (both half-angles in degrees).
struct Light {
    LightType type = LightType::Point;
    Vec3 position{0.0f, 10.0f, 0.0f};  // point and spot
    Vec3 direction{0.0f, -1.0f, 0.0f};  // directional and spot: where the light travels (unit)
    Rgb intensity{1.0f};
    float coneAngleDeg = 30.0f;
    float falloffAngleDeg = 5.0f;
};

}  // namespace raycache
