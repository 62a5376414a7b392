#include "render/WhittedIntegrator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/Errors.h"
#include "core/Optics.h"

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

WhittedIntegrator::WhittedIntegrator(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                                     const RayCache* cache)
    : scene_(scene), tracer_(tracer), settings_(settings), cache_(cache && !cache->empty() ? cache : nullptr) {
    if (scene.lights.size() > kMaxLights)
        throw InputError("scene has " + std::to_string(scene.lights.size()) + " lights; at most " +
                         std::to_string(kMaxLights) + " are supported");
}

int WhittedIntegrator::shadowQueries(const SurfacePoint& sp, ShadowQuery* out) const {
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
            if (light.type == LightType::Spot)
                strength = smoothstep(cosDegrees(light.coneAngleDeg),
                                      cosDegrees(light.coneAngleDeg - light.falloffAngleDeg),
                                      dot(-toLight, light.direction));
        }
        // Lights below the geometric surface would leak through interpolated normals.
        if (strength <= 0.0f || dot(sp.normal, toLight) <= 0.0f || dot(sp.geometricNormal, toLight) <= 0.0f)
            continue;
        out[count++] = ShadowQuery{Ray{origin, toLight, 0.0f, distance}, static_cast<int>(i), strength};
    }
    return count;
}

Rgb WhittedIntegrator::directLight(const Material& material, const SurfacePoint& sp, const Vec3& toViewer,
                                   std::span<const ShadowQuery> queries,
                                   std::span<const unsigned char> visible) const {
    return directLight(material, material.albedo(sp.u, sp.v), sp, toViewer, queries, visible);
}

Rgb WhittedIntegrator::directLight(const Material& material, const Rgb& albedo, const SurfacePoint& sp,
                                   const Vec3& toViewer, std::span<const ShadowQuery> queries,
                                   std::span<const unsigned char> visible) const {
    Rgb color = material.ambient * albedo;
    for (std::size_t q = 0; q < queries.size(); ++q) {
        if (!visible[q]) continue;
        const ShadowQuery& query = queries[q];
        const Vec3& toLight = query.ray.direction;
        Rgb lit = albedo * dot(sp.normal, toLight);
        if (!material.specular.isBlack()) {
            const float nDotH = std::max(0.0f, dot(sp.normal, normalize(toLight + toViewer)));
            lit += material.specular * std::pow(nDotH, material.shininess);
        }
        color += lit * scene_.lights[static_cast<std::size_t>(query.lightIndex)].intensity * query.strength;
    }
    return color;
}

Rgb WhittedIntegrator::secondaryLight(const Ray& ray, const SurfacePoint& sp, int objectId, int depth, float weight,
                                      PathContext& path) const {
    Rgb color;
    if (depth >= settings_.maxDepth) return color;
    const Material& material = scene_.objects[static_cast<std::size_t>(objectId)].material;
    const float offset = surfaceOffset(sp.position);
    float reflectWeight = material.reflectivity;
    if (material.refracts()) {
        // Entering: air -> material; leaving: material -> air (objects do not nest).
        const float eta = sp.frontFace ? 1.0f / material.ior : material.ior;
        if (const auto refracted = refract(ray.direction, sp.normal, eta)) {
            const float w = weight * material.transmissivity;
            if (w >= settings_.minWeight) {
                const Ray r{sp.position - sp.geometricNormal * offset, normalize(*refracted)};
                // A refracted ray that exits the object leaves it for the scene;
                // one that enters still has the inside to cross.
                const Rgb seen = sp.frontFace ? trace(r, SecondaryKind::Refraction, depth + 1, w, path)
                                              : leavingRay(objectId, r, SecondaryKind::Refraction, depth + 1, w, path);
                color += seen * material.transmissivity;
            }
        } else {
            // Total internal reflection: the transmitted share is reflected.
            reflectWeight += material.transmissivity;
        }
    }
    if (reflectWeight > 0.0f) {
        const float w = weight * reflectWeight;
        if (w >= settings_.minWeight) {
            const Ray r{sp.position + sp.geometricNormal * offset, normalize(reflect(ray.direction, sp.normal))};
            // Reflection off the outside leaves the object; inside, it stays in.
            const Rgb seen = sp.frontFace ? leavingRay(objectId, r, SecondaryKind::Reflection, depth + 1, w, path)
                                          : trace(r, SecondaryKind::Reflection, depth + 1, w, path);
            color += seen * reflectWeight;
        }
    }
    return color;
}

Rgb WhittedIntegrator::leavingRay(int objectId, const Ray& ray, SecondaryKind kind, int depth, float weight,
                                  PathContext& path) const {
    if (!cache_ || !path.cache || !cache_->cachesObject(objectId)) return trace(ray, kind, depth, weight, path);
    if (const auto cached = cache_->lookup(objectId, ray.origin, ray.direction, *path.cache)) return *cached;
    float hitDistance = 0.0f;
    const Rgb color = trace(ray, kind, depth, weight, path, &hitDistance);
    cache_->store(objectId, ray.origin, ray.direction, color, hitDistance, *path.cache);
    return color;
}

Rgb WhittedIntegrator::shade(const Ray& ray, const TraceHit& hit, int depth, float weight,
                             PathContext& path) const {
    const SceneObject& object = scene_.objects[static_cast<std::size_t>(hit.objectId)];
    const SurfacePoint sp = surfacePointAt(object, ray, hit, object.material.diffuseTexture.has_value());

    std::array<ShadowQuery, kMaxLights> queries;
    std::array<unsigned char, kMaxLights> visible;
    const int count = shadowQueries(sp, queries.data());
    for (int i = 0; i < count; ++i) visible[i] = tracer_.occluded(queries[i].ray) ? 0 : 1;
    path.counts.shadow += static_cast<std::uint64_t>(count);
    const auto n = static_cast<std::size_t>(count);
    return directLight(object.material, sp, -ray.direction, {queries.data(), n}, {visible.data(), n}) +
           secondaryLight(ray, sp, hit.objectId, depth, weight, path);
}

Rgb WhittedIntegrator::trace(const Ray& ray, SecondaryKind kind, int depth, float weight, PathContext& path,
                             float* hitDistance) const {
    if (kind == SecondaryKind::Reflection) ++path.counts.reflection;
    else ++path.counts.refraction;
    const TraceHit hit = tracer_.intersect(ray);
    if (hitDistance) *hitDistance = hit.hit() ? hit.t : std::numeric_limits<float>::infinity();
    return hit.hit() ? shade(ray, hit, depth, weight, path) : background(ray);
}

Rgb WhittedIntegrator::traceFromInside(int objectId, const Ray& ray, int depth, PathContext& path,
                                       float& hitDistance) const {
    // Enough for any closed mesh a cube centre sits in; past this the ray
    // counts as seeing the environment.
    constexpr int kMaxOwnSurfaces = 64;
    ++path.counts.prefill;
    Ray r = ray;
    for (int i = 0; i < kMaxOwnSurfaces; ++i) {
        const TraceHit hit = tracer_.intersect(r);
        if (!hit.hit()) break;
        if (hit.objectId != objectId) {
            hitDistance = hit.t;
            return shade(r, hit, depth, 1.0f, path);
        }
        r.tNear = hit.t + surfaceOffset(r.origin + r.direction * hit.t);
    }
    hitDistance = std::numeric_limits<float>::infinity();
    return background(ray);
}

}  // namespace raycache
