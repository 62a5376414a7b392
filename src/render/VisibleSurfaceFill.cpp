#include "render/VisibleSurfaceFill.h"

#include <algorithm>
#include <cmath>

#include "core/Box3.h"
#include "render/LocalShading.h"

namespace raycache {

namespace {

// Squared distance from `p` to the nearest point of `box`.
float squaredDistance(const Box3& box, const Vec3& p) {
    const auto axis = [](float v, float lo, float hi) { return v < lo ? lo - v : (v > hi ? v - hi : 0.0f); };
    const float dx = axis(p.x, box.lo.x, box.hi.x), dy = axis(p.y, box.lo.y, box.hi.y), dz = axis(p.z, box.lo.z, box.hi.z);
    return dx * dx + dy * dy + dz * dz;
}

}  // namespace

VisibleSurfaceFill::VisibleSurfaceFill(const Scene& scene, const TraceScene& tracer, const RayCache* cache)
    : tracer_(tracer), cache_(cache) {
    if (!cache_ || cache_->visibleFill() == VisibleFill::Off) return;
    mode_ = cache_->visibleFill();
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const int id = static_cast<int>(i);
        if (!cache_->cachesObject(id) || cache_->cube(id).hasDepth()) continue;  // CCT cubes only
        sources_.push_back({id, RayCache::boundingRadius(scene.objects[i]), scene.objects[i].material.reflects()});
    }
}

bool VisibleSurfaceFill::fills(const Material& material) const {
    if (material.reflects() || material.refracts()) return false;
    return mode_ == VisibleFill::Approximate || (mode_ == VisibleFill::Exact && material.specular.isBlack());
}

std::uint64_t VisibleSurfaceFill::fillTile(std::span<const VisiblePoint> points, const Vec3& eye,
                                           VisibleFillScratch& s, CacheWorker& worker) const {
    if (points.empty() || sources_.empty()) return 0;
    Box3 box;
    for (const VisiblePoint& p : points) box.add(p.position);
    s.candidates.clear();
    for (const Source& source : sources_) {
        const CachingCube& cube = cache_->cube(source.objectId);
        const Vec3 center = cube.center();
        const float reach = kReach * source.radius;
        if (squaredDistance(box, center) > reach * reach) continue;
        // Rays start on a sphere just outside the object, so they never meet
        // it; points inside that sphere cannot be seen from outside it.
        const float start = source.radius * 1.001f + surfaceOffset(center);
        const Vec3 toEye = normalize(eye - center);
        for (std::size_t i = 0; i < points.size(); ++i) {
            const Vec3 toPoint = points[i].position - center;
            const float squared = dot(toPoint, toPoint);
            if (!(squared <= reach * reach && squared > start * start)) continue;
            // Where the ray starts: where a mirror of that shape would reflect
            // the eye toward the point (the normal halfway between the
            // directions to the eye and to the point), so that it leaves from
            // about where the camera's reflected rays toward the point leave.
            // A point behind the object, as the eye sees it, is reached by
            // rays through the object: they leave on the far side, toward it.
            const Vec3 toPointUnit = toPoint / std::sqrt(squared);
            Vec3 normal = toPointUnit;
            if (source.reflects) {
                Vec3 halfway = toEye + toPointUnit;
                // A few fixed-point steps toward the sphere's mirror point for
                // near eyes and points (the directions seen from the point
                // itself, not from the centre): on room's ball 3 steps took
                // the filled answers from 33.5 to 34.5 dB against the
                // uncached render, 8 to 34.8.
                for (int k = 0; k < kMirrorPointSteps && dot(halfway, halfway) > 1e-6f; ++k) {
                    const Vec3 p = center + normalize(halfway) * start;
                    halfway = normalize(eye - p) + normalize(points[i].position - p);
                }
                if (dot(halfway, halfway) > 1e-6f) normal = normalize(halfway);
            }
            const Vec3 origin = center + normal * start;
            const Vec3 ray = points[i].position - origin;
            const float distance = length(ray);
            const Vec3 direction = ray / distance;
            if (!(dot(direction, normal) > 0.0f)) continue;  // would pass through the object
            const int texel = cube.texelIndexFor(direction);
            if (cube.isValid(texel)) continue;  // as the frame began: stores land at its end
            // Stops short of the point by the offset that lifts rays off surfaces.
            const float length = distance - surfaceOffset(points[i].position);
            if (!(length > 0.0f)) continue;
            s.candidates.push_back({source.objectId, texel, static_cast<int>(i), Ray{origin, direction, 0.0f, length}});
        }
    }
    // One ray per texel: the first candidate that addresses it.
    std::stable_sort(s.candidates.begin(), s.candidates.end(), [](const auto& a, const auto& b) {
        return a.objectId != b.objectId ? a.objectId < b.objectId : a.texel < b.texel;
    });
    s.candidates.erase(std::unique(s.candidates.begin(), s.candidates.end(),
                                   [](const auto& a, const auto& b) { return a.objectId == b.objectId && a.texel == b.texel; }),
                       s.candidates.end());
    const std::size_t n = s.candidates.size();
    s.rays.resize(n);
    s.occluded.resize(n);
    for (std::size_t k = 0; k < n; ++k) s.rays[k] = s.candidates[k].ray;
    tracer_.occludedIncoherent(std::span(s.rays.data(), n), std::span(s.occluded.data(), n));
    for (std::size_t k = 0; k < n; ++k) {
        if (s.occluded[k]) continue;
        const VisibleFillScratch::Candidate& c = s.candidates[k];
        const VisiblePoint& point = points[static_cast<std::size_t>(c.point)];
        const float hitDistance = length(point.position - c.ray.origin);
        if (cache_->tracksDependencies()) {
            // The point's colour depends on what lies on the ray, on the point's
            // object and on its light: every light and its shadow rays.
            RayTreeRecord tree{{}, c.ray.origin, c.ray.direction, 2, 1.0f};
            tree.bounds.addSegment(c.ray.origin, point.position);
            // Whether the point's shadow rays reached their lights is not kept
            // with its colour.
            tree.bounds.addShadowRaysOfUnknownAnswer(point.position);
            tree.bounds.shaded = true;
            cache_->store(c.objectId, c.ray.origin, c.ray.direction, point.color, hitDistance, worker, c.texel, &tree);
        } else {
            cache_->store(c.objectId, c.ray.origin, c.ray.direction, point.color, hitDistance, worker, c.texel);
        }
    }
    return n;
}

}  // namespace raycache
