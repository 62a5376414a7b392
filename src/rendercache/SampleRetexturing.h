#pragma once
// Texture re-fetch of the Render Cache (issue 38 item 2): a reprojected
// sample sits up to half a pixel off its new pixel's centre, so on a
// texture it shows the texel of the wrong point, and a checkerboard's edges
// come out jagged and shifted. A textured sample keeps its colour taken
// apart (SampleTexturing: albedo * lighting + rest); its pixel's centre ray
// is met with the sample's own primitive (render/HitOnPrimitive), the
// albedo fetched there, and multiplied back. The lighting and the rest vary
// slowly over a surface and stay as traced (the rest is shaded again from
// the new eye anyway where reflections are reshaded).
#include "core/Ray.h"
#include "core/Rgb.h"
#include "rendercache/SamplePool.h"
#include "scene/SceneObject.h"

namespace raycache {

// Priority (rendercache/RequestMap.h: holes 1, samples 0.5 * age / max age)
// of a pixel whose centre ray misses its textured sample's primitive: the
// stored colour is shown, so it is worth a ray sooner than an old sample,
// but not sooner than a hole.
inline constexpr float kMissedPrimitivePriority = 0.75f;

// The colour a textured sample of `object` (index `objectId`), at distance
// `sampleDistance` from the eye, shows at the pixel whose centre ray is
// `centreRay`, written to `color`; false (and `color` untouched) where
// that ray misses the sample's primitive.
bool retexturedColor(const SceneObject& object, int objectId, const SampleTexturing& texturing, const Ray& centreRay,
                     float sampleDistance, Rgb& color);

}  // namespace raycache
