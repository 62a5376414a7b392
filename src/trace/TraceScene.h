#pragma once
// The ray tracer's view of a scene: an Embree BVH over every object (spheres
// as analytic sphere primitives, meshes as triangles). This folder is the only
// code that includes Embree.
#include <memory>
#include <span>

#include "core/Parallel.h"
#include "core/Ray.h"
#include "scene/Accelerator.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "trace/RayPacket.h"
#include "trace/TraceHit.h"
#include "trace/grids/GridAccelerator.h"

namespace raycache {

// How a deforming mesh's hierarchy follows its vertices each frame.
enum class DeformingMeshUpdate {
    Refit,    // keep the tree, recompute its boxes: cheap, but the tree ages as the shape drifts
    Rebuild,  // a new tree (Embree's medium quality) every frame
};

// Embree's build quality for a still scene's hierarchy: Low is its fastest
// build, Medium its default, High (spatial splits) the best tree.
enum class EmbreeBuildQuality { Low, Medium, High };

struct TraceOptions {
    EmbreeBuildQuality stillSceneQuality = EmbreeBuildQuality::High;
    DeformingMeshUpdate deformingMeshes = DeformingMeshUpdate::Refit;  // chosen by measurement: docs/dynamic-scenes.md
    // Primary rays and the shadow rays of primary hits: Embree or the grids.
    Accelerator accelerator = Accelerator::Embree;
    GridSettings grids;
    // Threads Embree builds its hierarchies on; 0: all. 1 builds on the
    // calling thread alone (Embree then starts no oneTBB worker, whose
    // hand-overs ThreadSanitizer cannot see: the tests run under it use 1).
    // Embree limits oneTBB process-wide while the device lives.
    int buildThreads = 0;
};

// What the tracer did for one frame beyond Embree's own work: the grids'
// build, and how many primary and shadow rays they answered or refused
// (refused rays are traced by Embree). All zero with Accelerator::Embree.
struct FrameTraceStats {
    GridFrameStats build;
    std::uint64_t primaryAnswered = 0, primaryRefused = 0;
    std::uint64_t shadowAnswered = 0, shadowRefused = 0;
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
    // Every object of a still scene's tracer set to `posed` (the same objects,
    // meshes with the same vertex counts) and every hierarchy built again
    // from nothing, in the memory the tracer already holds: the per-frame
    // rebuild of a renderer that keeps one Embree scene. Not thread-safe.
    void rebuild(const Scene& posed);

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

    // One packet of up to sixteen coherent rays, traced where lanes.valid is
    // -1, through Embree whatever the accelerator (the tile kernel uses it
    // only without grids). Sets tFar to each hit's distance and objectId[k]
    // to the object hit (-1: nothing, or a lane not traced); the hit's
    // primitive and barycentrics are in packet.hit.
    void intersectPacket(RayHitLanes16& packet, const PacketLanes& lanes, int* objectId) const;
    // Occlusion of the valid lanes of one packet: occluded[k] = 1 where lane
    // k is blocked (0 where it is clear or not traced).
    void occludedPacket(RayLanes16& packet, const PacketLanes& lanes, unsigned char* occluded) const;

    // The same for batches of rays that go their own ways (e.g. shadow rays
    // of later bounces): traced one by one, which beats packets whose lanes
    // diverge.
    void occludedIncoherent(std::span<const Ray> rays, std::span<unsigned char> occluded) const;

    // Gets the tracer ready for a frame of `camera` at width x height: with
    // the grids accelerator, rebuilds every grid from `posed` (the scene as
    // update() left it; it must outlive the frame). Does nothing with Embree.
    // Not thread-safe: no ray may be in flight. Const because sessions share
    // one tracer read-only; the grids are per-frame state, rebuilt by
    // whichever session renders next.
    void prepareFrame(const Scene& posed, const Camera& camera, int width, int height,
                      const Parallel& parallel) const;
    // Primary rays (from the camera of the last prepareFrame): the grids
    // when they are on, otherwise as intersectCoherent. Exact either way:
    // rays the grids do not cover go to Embree.
    void intersectPrimary(std::span<const Ray> rays, std::span<TraceHit> hits) const;
    // Shadow rays of primary hits; lights[i] is the index of the light
    // rays[i] heads for. The grids when they are on, otherwise as occludedCoherent.
    void occludedPrimaryShadows(std::span<const Ray> rays, std::span<const int> lights,
                                std::span<unsigned char> occluded) const;
    // The grids' build and answer counts since the last prepareFrame.
    FrameTraceStats frameStats() const;
    Accelerator accelerator() const;

    // Whether `ray` meets object `objectId`'s own surface anywhere in
    // [tNear, tFar], every other object ignored: a concave mirror that sees
    // itself. Spheres are solved analytically; any other object is traced
    // against a hierarchy of its own, which prepareOwnSurfaceTests must have
    // built (RuntimeError otherwise). Thread-safe.
    bool meetsObject(int objectId, const Ray& ray) const;
    // Builds the hierarchies meetsObject needs for `objects` (object
    // indices), those not built yet; each shares its object's geometry, so it
    // follows update(). Not thread-safe: no ray may be in flight. Const for
    // the reason prepareFrame is.
    void prepareOwnSurfaceTests(std::span<const int> objects) const;

    // Escape hatch for code in src/trace/ that needs the raw RTCScene.
    void* embreeScene() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace raycache
