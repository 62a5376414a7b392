#pragma once
// Whether a surface's colour changes with the eye, so that a reprojected
// sample of it must be shaded again from the new eye (the Render Cache's
// reshading): mirror and refracted rays, a Blinn-Phong highlight, or the
// metallic-roughness BRDF, whose GGX lobe and Fresnel depend on the view
// direction at every roughness (its `specular` field stays black).
#include "scene/Material.h"

namespace raycache {

inline bool dependsOnView(const Material& m) {
    return m.reflects() || m.refracts() || !m.specular.isBlack() || m.model == ShadingModel::MetallicRoughness;
}

}  // namespace raycache
