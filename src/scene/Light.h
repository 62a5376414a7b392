#pragma once
#include "core/Rgb.h"
#include "core/Vec3.h"

namespace raycache {

enum class LightType { Point, Directional, Spot };

// A classic light (physical false) has no distance falloff (Whitted's): a
// spot light is a point light restricted to a cone, full intensity inside
// coneAngle - falloffAngle, fading by smoothstep to zero at coneAngle (both
// half-angles in degrees).
//
// A physical light is KHR_lights_punctual's, in radiometric units: a point or
// spot light's intensity is a radiant intensity (W/sr), giving irradiance
// intensity / d^2 at distance d, windowed by clamp(1 - (d / range)^4, 0, 1)
// when range > 0; a spot fades between its inner cone (coneAngle -
// falloffAngle) and its outer cone (coneAngle) by the extension's smooth
// falloff (the cosine's linear ramp, squared); a directional light's
// intensity is an irradiance (W/m^2).
struct Light {
    LightType type = LightType::Point;
    Vec3 position{0.0f, 10.0f, 0.0f};  // point and spot
    Vec3 direction{0.0f, -1.0f, 0.0f};  // directional and spot: where the light travels (unit)
    Rgb intensity{1.0f};
    float coneAngleDeg = 30.0f;
    float falloffAngleDeg = 5.0f;
    bool physical = false;
    float range = 0.0f;  // physical point and spot lights: 0 for no range
};

}  // namespace raycache
