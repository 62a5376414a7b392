#pragma once
// The workload of `raycache bench grids` and of benchmarks/grids_speed: a
// model (a procedural torus on a floor, or an animated built-in scene), the
// camera rays of a frame in 16x16 tiles, the shadow rays of their hits, and
// timed passes that trace them tile by tile, in parallel, through the grids
// (TraceScene::intersectPrimary, occludedPrimaryShadows) or through
// Embree's 16-wide coherent packets.
#include <optional>
#include <string>
#include <vector>

#include "core/Parallel.h"
#include "core/Ray.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "trace/TraceHit.h"
#include "trace/TraceScene.h"

namespace raycache {

struct GridsModel {
    std::string name;
    Scene scene;
    bool animated = false;
};

// A torus of about `triangles` triangles on a floor under one point light,
// the camera orbiting it; named "torus <thousands>k".
GridsModel gridsTorusModel(int triangles);

// One frame's rays by tile: the camera rays, and the shadow rays of their
// hits (with the light each goes to).
struct GridsFrameRays {
    std::vector<TileRange> tiles;
    std::vector<std::vector<Ray>> primary;  // per tile
    std::vector<std::vector<Ray>> shadow;   // per tile
    std::vector<std::vector<int>> lights;
};

// The camera rays of a side x side image, in 16x16 tiles.
GridsFrameRays cameraRaysByTile(const Camera& camera, int side);
// The shadow rays of `hits` (per tile, for rays.primary) toward every light of `scene`.
void addShadowRays(const Scene& scene, const std::vector<std::vector<TraceHit>>& hits, GridsFrameRays& rays);

// Wall milliseconds to make Embree's rebuilt-every-frame opponent ready for
// `still` (a scene without animation): made in `kept` the first time, and
// afterwards every hierarchy built again from nothing in the memory it holds
// (TraceScene::rebuild), as a renderer keeps one scene. Made anew each
// frame, its build times grew long tails (fresh pages).
double rebuildOpponent(std::optional<TraceScene>& kept, const Scene& still, const TraceOptions& options);

// Wall milliseconds to trace every tile's camera rays (grids: through the
// tracer's grids; otherwise Embree's packets); `keepHits`, if set, gets the hits.
double tracePrimary(const TraceScene& tracer, const GridsFrameRays& rays, const Parallel& parallel, bool grids,
                    std::vector<std::vector<TraceHit>>* keepHits);
// The same for every tile's shadow rays.
double traceShadows(const TraceScene& tracer, const GridsFrameRays& rays, const Parallel& parallel, bool grids);

}  // namespace raycache
