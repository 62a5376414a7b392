#pragma once
// The ray tracer's view of a scene: an Embree BVH over every object (spheres
// as analytic sphere primitives, meshes as triangles). This folder is the only
// code that includes Embree.
#include <memory>
#include <span>

#include "core/Ray.h"
#include "scene/Scene.h"
#include "trace/TraceHit.h"

namespace raycache {

// How a deforming mesh's hierarchy follows its vertices each frame.
enum class DeformingMeshUpdate {
    Refit,    // keep the tree, recompute its boxes: cheap, but the tree ages as the shape drifts
    Rebuild,  // a new tree (Embree's medium quality) every frame
};

struct TraceOptions {
    DeformingMeshUpdate deformingMeshes = DeformingMeshUpdate::Refit;  // chosen by measurement: docs/dynamic-scenes.md
};

class TraceScene {
public:
    // Builds the acceleration structure from a copy of the geometry; `scene`
    // may go away afterwards. Throws RuntimeError if Embree fails.
    explicit TraceScene(const Scene& scene, const TraceOptions& options = {});
    ~TraceScene();
    TraceScene(const TraceScene&) = delete;
    TraceScene& operator=(const TraceScene&) = delete;

    // Moves the tracer's objects `changed` (sorted object indices) to their
    // pose in `posed` (scene/ScenePose.h): animated spheres are updated in
    // place, rigidly moving meshes are instances whose transform changes,
    // deforming meshes refit their hierarchy. Not thread-safe: no ray may be
    // in flight. `posed` has the objects of the scene this tracer was built from.
    void update(const Scene& posed, std::span<const int> changed);

    // Nearest hit in [ray.tNear, ray.tFar]. Thread-safe.
    TraceHit intersect(const Ray& ray) const;
    // True if anything lies in [ray.tNear, ray.tFar]. Thread-safe.
    bool occluded(const Ray& ray) const;
    // Nearest hits for a batch of coherent rays (e.g. one tile's primary
    // rays), traced as packets. hits.size() must equal rays.size().
    void intersectCoherent(std::span<const Ray> rays, std::span<TraceHit> hits) const;

    // Occlusion for a batch of coherent rays (e.g. one tile's shadow rays
    // toward one light), as packets: occluded[i] = 1 if rays[i] is blocked.
    void occludedCoherent(std::span<const Ray> rays, std::span<unsigned char> occluded) const;

    // The same for batches of rays that go their own ways (e.g. shadow rays
    // of later bounces): traced one by one, which beats packets whose lanes
    // diverge.
    void intersectIncoherent(std::span<const Ray> rays, std::span<TraceHit> hits) const;
    void occludedIncoherent(std::span<const Ray> rays, std::span<unsigned char> occluded) const;

    // Escape hatch for code in src/trace/ that needs the raw RTCScene.
    void* embreeScene() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace raycache
