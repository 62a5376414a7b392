#pragma once
// Rays the tile kernel (render/TileKernel.h) hands the tracer in one batch
// call rather than packet by packet: the camera rays of a set of pixels or
// of a tile the grids answer, and the shadow rays of camera hits, which the
// tracer may answer per light with its light grids
// (TraceScene::occludedPrimaryShadows). Kept together because each batch
// is packed, traced and read back within one stage.
#include <vector>

#include "core/Ray.h"
#include "trace/RayPacket.h"
#include "trace/TraceHit.h"

namespace raycache {

struct TileTraceBatch {
    // The rays, and what came back: hits of camera rays, or for shadow rays
    // whether each is occluded, each with its light for the light grids.
    std::vector<Ray> rays;
    std::vector<TraceHit> hits;
    std::vector<unsigned char> occluded;
    std::vector<int> shadowLights;
    // The shadow rays of camera hits in lanes, before they are packed:
    // packet p's toward light l at p * lights + l.
    std::vector<RayLanes16> shadowLanes;
    std::vector<PacketLanes> shadowTraced;
};

}  // namespace raycache
