#include "render/LocalShading.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/Errors.h"
#include "render/HitLanes.h"

namespace raycache {

namespace {

float smoothstep(float edge0, float edge1, float x) {
    if (edge1 <= edge0) return x >= edge1 ? 1.0f : 0.0f;
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

float cosDegrees(float degrees) { return std::cos(degrees * std::numbers::pi_v<float> / 180.0f); }

}  // namespace

float surfaceOffset(const Vec3& p) {
    const float extent = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z), 1.0f});
    return 1e-4f * extent;
}

LocalShading::LocalShading(const Scene& scene) : scene_(scene) {
    if (scene.lights.size() > kMaxLights)
        throw InputError("scene has " + std::to_string(scene.lights.size()) + " lights; at most " +
                         std::to_string(kMaxLights) + " are supported");
    // The cone's cosines, once per light rather than once per shadow query.
    for (const Light& light : scene.lights) {
        SpotCone cone{cosDegrees(light.coneAngleDeg), cosDegrees(light.coneAngleDeg - light.falloffAngleDeg)};
        cone.angleScale = 1.0f / std::max(0.001f, cone.inner - cone.outer);
        cone.angleOffset = -cone.outer * cone.angleScale;
        spotCosines_.push_back(cone);
    }
}

int LocalShading::shadowQueries(const SurfacePoint& sp, ShadowQuery* out) const {
    const Vec3 origin = sp.position + sp.geometricNormal * surfaceOffset(sp.position);
    int count = 0;
    for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
        const Light& light = scene_.lights[i];
        Vec3 toLight;
        float distance;
        float strength = 1.0f;
        if (light.type == LightType::Directional) {
            toLight = -light.direction;
            distance = std::numeric_limits<float>::infinity();
        } else {
            const Vec3 d = light.position - sp.position;
            const float inverseDistance = 1.0f / std::sqrt(dot(d, d));
            distance = dot(d, d) * inverseDistance;
            toLight = d * inverseDistance;
            if (light.physical) {
                strength = physicalFalloff(light, dot(d, d), distance);
                if (light.type == LightType::Spot)
                    strength = physicalSpotFactor(spotCosines_[i], dot(-toLight, light.direction)) * strength;
            } else if (light.type == LightType::Spot) {
                strength = smoothstep(spotCosines_[i].outer, spotCosines_[i].inner,
                                      dot(-toLight, light.direction));
            }
        }
        // Lights below the geometric surface would leak through interpolated normals.
        if (strength <= 0.0f || dot(sp.normal, toLight) <= 0.0f || dot(sp.geometricNormal, toLight) <= 0.0f)
            continue;
        out[count++] = ShadowQuery{Ray{origin, toLight, 0.0f, distance}, static_cast<int>(i), strength};
    }
    return count;
}

}  // namespace raycache
