#pragma once
// What the tile kernel (render/TileKernel.h) keeps of the rays of one tile:
// the tree of nodes their colours add up in, the wave of packets being shaded,
// and the secondary rays waiting to be the next wave. Every call of the kernel
// uses these; the other parts of TileScratch serve one feature each.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/Ray.h"
#include "core/Rgb.h"
#include "render/HitLanes.h"
#include "render/RayCone.h"
#include "trace/RayPacket.h"

namespace raycache {

struct TileWave {
    enum class Kind : unsigned char { Reflection, Refraction };
    struct PendingRay {  // a secondary ray waiting to be traced
        Ray ray;
        int node;
        float pathWeight;
        int depth;
        Kind kind;
        RayCone cone{};
    };
    // What one ray brings back: the light at its hit (or the background, or
    // the cache's answer) plus its reflected and refracted rays' colours times
    // their weights (tests/render/SecondaryRayWeights.h), gathered from its child
    // nodes once the tile is done; the same sums, in the same order, as the
    // recursive form. A node's own colour is unweighted: that is what a
    // cube stores for a leaving ray, its weight applying at the parent.
    struct Node {
        Rgb direct;
        Rgb secondary;
        int parent = -1;            // -1: a pixel or texel of the caller's
        Rgb weightInParent;         // per channel
        // A ray leaving a caching object whose cache missed it: its store
        // record (an index into TileCacheBookkeeping::stores), stored when
        // done; -1 for every other node. Apart, so that the node every ray
        // gets stays small (GCC filled the 84-byte node with a `rep stos` per ray).
        int store = -1;
        // TileCacheBookkeeping::trackTrees: a ray leaving a caching object, or
        // below one (its bounds matter); 0 or 1. Four bytes, not a bool: with
        // a one-byte field last, GCC 12 filled each tile's nodes with
        // overlapping unaligned stores, several times slower than aligned ones.
        std::uint32_t tracked = 0;
        // With a cache: rays traced for this node's tree (its own ray, the
        // shadow rays at its hit, its children's trees), what a store of it
        // tells the cache policy a hit spares (cache/CachePolicy.h).
        std::uint32_t tracedRays = 0;
        Rgb color() const { return direct + secondary; }
    };
    // Sixteen rays of a wave and their hits in lanes, from the tracer's
    // packet to their direct light and secondary rays (render/TileKernelWaves.cpp).
    struct HitPacket {
        RayHitLanes16 rays;
        PacketLanes hits;  // -1 where the ray hit something
        alignas(64) int objectId[16];
        SurfaceLanes16 surface;
        alignas(64) float directR[16], directG[16], directB[16];
        alignas(64) int node[16];          // the node each ray's colour adds to
        // Product of the weights since the camera, each its largest channel:
        // for the minimum-weight rule.
        alignas(64) float pathWeight[16];
        alignas(64) int depth[16];         // rays on its path so far, the primary ray being 1
        // The pixel's cone along the ray (zero where no pixel stands behind it).
        alignas(64) float coneWidth[16], coneSpread[16];
        int count = 0;  // lanes in use; the rest are not traced
    };

    // The tile's nodes, its roots (the caller's pixels or texels) first.
    std::vector<Node> nodes;
    // The wave: its packets, packet p's view of light l at p * lights + l,
    // packet p's secondary rays at p (TileKernel::packetSpawnLanes), and one
    // packet's triangles. `filledLanes` counts the lanes addFirstHit filled.
    std::vector<HitPacket> packets;
    std::vector<LightLanes16> packetLights;
    std::vector<SecondaryRayLanes16> spawnLanes;
    MeshHitLanes meshLanes;
    std::size_t filledLanes = 0;
    // The secondary rays to trace as the next wave, in spawn order.
    std::vector<PendingRay> pending;
};

}  // namespace raycache
