#pragma once
// How CCT cubes are filled from the surfaces the camera sees
// (RayCacheSettings::visibleFill; render/VisibleSurfaceFill.h does the
// filling): the modes and the words the command line and the statistics
// name them by.
#include <array>

namespace raycache {

enum class VisibleFill : unsigned char {
    Off,
    Exact,        // from surfaces whose colour does not depend on the view (no highlight, mirror or glass)
    Approximate,  // also from surfaces with highlights (the camera's highlight is stored)
};

// Every mode, in the order messages list them.
inline constexpr std::array kVisibleFills{VisibleFill::Off, VisibleFill::Exact, VisibleFill::Approximate};

// "off", "exact", "approximate" (`--cache-fill`).
const char* visibleFillName(VisibleFill fill);

}  // namespace raycache
