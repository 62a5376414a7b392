#pragma once
// How scene-linear light becomes what a display shows (`--view-transform`):
// a curve from scene-linear Rec. 709 RGB to display-linear RGB in [0, 1],
// which linearToSrgb8 (core/ColorSpace.h) then encodes. docs/usage.md
// describes each and where it comes from.
#include <array>
#include <string_view>

#include "core/Rgb.h"

namespace raycache {

enum class ViewTransform {
    Standard,           // the values as they are; the encoding clamps to [0, 1] (Blender's "Standard")
    Filmic,             // Blender 3.x's Filmic, base contrast (a fit of its curve; desaturation not reproduced)
    Agx,                // Blender 4's AgX, by the "minimal AgX" polynomial fit
    KhronosPbrNeutral,  // the Khronos PBR Neutral tone mapper, exactly as published
};
inline constexpr std::array kViewTransforms{ViewTransform::Standard, ViewTransform::Filmic, ViewTransform::Agx,
                                            ViewTransform::KhronosPbrNeutral};

// "standard", "filmic", "agx", "khronos-pbr-neutral".
constexpr const char* viewTransformName(ViewTransform transform) {
    switch (transform) {
        case ViewTransform::Standard: return "standard";
        case ViewTransform::Filmic: return "filmic";
        case ViewTransform::Agx: return "agx";
        case ViewTransform::KhronosPbrNeutral: return "khronos-pbr-neutral";
    }
    return "?";
}

// The display-linear colour of a scene-linear one, in [0, 1] for every
// transform but Standard (which returns its input: the 8-bit encoding clamps).
// Negative and NaN components count as 0.
Rgb applyViewTransform(ViewTransform transform, const Rgb& sceneLinear);

}  // namespace raycache
