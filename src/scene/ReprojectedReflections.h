#pragma once
// What a reprojected sample of the Render Cache (render/RenderCacheSettings.h)
// shows on a mirror, glass or glossy surface. Here, below the renderer,
// because the scene format names it too ("renderCache": {"reflections"}):
// the scene file and the command line read the names from here.
#include <array>

namespace raycache {

enum class ReprojectedReflections {
    Reproject,  // the colour seen when it was traced (the 2002 Render Cache: it smears as the eye moves)
    Reshade,    // highlights and reflected/refracted colour evaluated again from the new eye,
                // reflected/refracted rays answered by the object's caching cube when it has one
};
// Both, in the order messages list them.
inline constexpr std::array kReprojectedReflections{ReprojectedReflections::Reshade, ReprojectedReflections::Reproject};

// "reshade" / "reproject".
constexpr const char* reprojectedReflectionsName(ReprojectedReflections mode) {
    return mode == ReprojectedReflections::Reshade ? "reshade" : "reproject";
}

}  // namespace raycache
