#pragma once
// The grids of one frame (Guntury and Narayanan 2010, docs/grids.md): a perspective grid over
// the camera's frustum for primary rays, and one light-space grid per light
// for the shadow rays of primary hits, all rebuilt from the posed scene by
// buildFrame. Queries answer exactly or refuse (a ray outside what the grids
// cover); TraceScene sends refused rays to Embree and counts them.
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/Parallel.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "trace/grids/FrustumGrid.h"
#include "trace/grids/GridPrimitives.h"

namespace raycache {

struct GridSettings {
    int pixelsPerColumn = 8;         // camera grid: one column per this many pixels squared
    int maxSlices = 64;              // depth slices of any grid, at most
    double cellsPerPrimitive = 2.0;  // how many slices: about this many cells per primitive
    // Light grids start with the camera grid's columns and get finer ones
    // where they would need more slices than this (FrustumGridSpec): a
    // shadow ray crosses every slice between its origin and the light.
    int lightRefineAboveSlices = 16;
    // A point light's single grid may cover points up to this far from its
    // axis; beyond, the light gets six grids, one per axis face.
    double maxLightHalfAngleDeg = 80.0;
};

// What building the grids of one frame cost and made; and what the queries
// of that frame answered (counted as they run).
struct GridFrameStats {
    double primaryBuildMs = 0.0;  // primitives listed, camera grid built
    double shadowBuildMs = 0.0;   // every light's grid
    std::uint64_t primitives = 0;
    std::uint64_t primaryPairs = 0, shadowPairs = 0;
    std::uint64_t primaryNearZone = 0;
    int lightGrids = 0;          // grids built for lights (a six-face light counts its non-empty faces)
    int lightsWithSixFaces = 0;  // point lights among the geometry
};

class GridAccelerator {
public:
    explicit GridAccelerator(const GridSettings& settings) : settings_(settings) {}

    // Rebuilds every grid for `scene` (which must stay unchanged while this
    // frame is traced) seen by `camera` at width x height.
    GridFrameStats buildFrame(const Scene& scene, const Camera& camera, int width, int height,
                              const Parallel& parallel);
    bool built() const { return primitives_ != nullptr; }

    // False when the camera grid does not cover the ray.
    bool intersectPrimary(const Ray& ray, TraceHit& hit) const { return camera_.intersect(ray, hit); }
    // The same for a batch, as packets (FrustumGrid::intersectBatch); refused[i] = 1: not covered.
    void intersectPrimaryBatch(std::span<const Ray> rays, std::span<TraceHit> hits,
                               std::span<unsigned char> refused) const {
        camera_.intersectBatch(rays, hits, refused);
    }
    // False when light `light` has no grid or its grid does not cover the ray.
    bool occludedShadow(const Ray& ray, int light, bool& blocked) const;
    // The same for a batch of rays toward light `light`, as packets
    // (FrustumGrid::occludedBatch); refused[i] = 1: not covered.
    void occludedShadowBatch(std::span<const Ray> rays, int light, std::span<unsigned char> blocked,
                             std::span<unsigned char> refused) const;

    const FrustumGrid& cameraGrid() const { return camera_; }

private:
    void buildLightGrid(const Light& light, std::size_t index, const std::vector<Vec3>& visible,
                        const Parallel& parallel, GridFrameStats& stats);

    GridSettings settings_;
    std::unique_ptr<GridPrimitives> primitives_;
    FrustumGrid camera_;
    // A light's grids: one (directional, spot, or a point light whose seen
    // region fits around one axis), or six axis faces (a point light among
    // the geometry). Null entries: no grid (nothing to cover).
    struct LightGrids {
        std::vector<std::unique_ptr<FrustumGrid>> grids;
        std::vector<std::unique_ptr<FrustumGrid>> spare;  // earlier frames' grids, to rebuild in place
        bool faces = false;
    };
    const FrustumGrid* lightGridFor(const Ray& ray, int light, int& face) const;

    std::vector<LightGrids> lights_;
    std::vector<Vec3> lightPositions_;
    // Per primitive, the face grids of the light being built that may meet it.
    std::vector<std::uint8_t> faceMasks_;
    double worldScale_ = 1.0;
};

}  // namespace raycache
