#pragma once
// What turns a film (scene-linear light) into the colours an 8-bit image or
// the viewer shows: an exposure in stops, then a view transform
// (core/ViewTransform.h), then the sRGB encoding. EXR files get the film
// itself, neither exposed nor transformed.
#include <cmath>

#include "core/Rgb.h"
#include "core/ViewTransform.h"

namespace raycache {

// The widest exposure a scene file or option may ask for, in stops either way.
inline constexpr float kMaxExposureStops = 64.0f;

struct DisplaySettings {
    float exposure = 0.0f;  // stops (EV): the light is multiplied by 2^exposure
    ViewTransform view = ViewTransform::Standard;
};

class DisplayTransform {
public:
    DisplayTransform() = default;
    explicit DisplayTransform(const DisplaySettings& settings)
        : view_(settings.view), scale_(static_cast<float>(std::exp2(static_cast<double>(settings.exposure)))),
          exposed_(settings.exposure != 0.0f) {}

    // True when the display shows the film's values as they are (0 EV,
    // Standard): the 8-bit codes are then those of linearToSrgb8 alone.
    bool identity() const { return !exposed_ && view_ == ViewTransform::Standard; }

    // The display-linear colour of a film pixel, for linearToSrgb8. At 0 EV
    // the light is not multiplied at all (the same bits as without exposure).
    Rgb operator()(Rgb linear) const {
        if (exposed_) linear *= scale_;
        return applyViewTransform(view_, linear);
    }

private:
    ViewTransform view_ = ViewTransform::Standard;
    float scale_ = 1.0f;
    bool exposed_ = false;
};

}  // namespace raycache
