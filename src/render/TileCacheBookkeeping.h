#pragma once
// What the tile kernel (render/TileKernel.h) keeps for the ray cache
// (cache/RayCache.h): the lookup batch of the rays leaving caching objects,
// the stores of the ones it missed, and, for the cache policy and animated
// scenes, the rays and bounds of each node's tree. Unused without a cache.
#include <cstdint>
#include <vector>

#include "cache/RayCache.h"
#include "cache/RayTreeBounds.h"
#include "core/Rgb.h"
#include "core/Vec3.h"
#include "render/RayCone.h"
#include "render/TileWave.h"

namespace raycache {

struct TileCacheBookkeeping {
    // A secondary ray leaving a caching object: the cache is asked first.
    // The ray itself and its object are its query (cacheQueries, same index),
    // written where the ray is spawned, so the lookup reads them in place.
    struct LeavingRay {
        int node;
        float pathWeight;
        int depth;
        TileWave::Kind kind;
        RayCone cone{};
    };
    // What a traced leaving ray stores once its tree is resolved.
    struct NodeStore {
        int objectId;               // the caching object it left
        int storeTexel;             // where, when the lookup already knows (RayCache::lookupBatch), else -1
        Vec3 origin, direction;     // the ray
        float hitDistance = 0.0f;   // distance to its first hit, infinity for a miss
        int depth;                  // its depth and path weight, for the store's RayTreeRecord
        float pathWeight;
    };

    // The lookup batch of a wave (RayCache::lookupBatch): the leaving rays
    // and their queries, and per query its answer, or where a miss stores.
    std::vector<LeavingRay> leaving;
    std::vector<RayCache::Query> cacheQueries;  // one per leaving ray
    std::vector<Rgb> cachedColors;
    std::vector<unsigned char> cacheFound;
    std::vector<int> storeTexels;
    std::vector<int> answerTexels;
    // The missed leaving rays that were traced (TileWave::Node::store).
    std::vector<NodeStore> stores;
    // When the cache tracks dependencies (animated scenes): per node, where
    // its ray tree reached (cache/RayTreeBounds.h), gathered up like colours.
    bool trackTrees = false;
    std::vector<RayTreeBounds> nodeBounds;
    // Whether this tile counts each node's traced rays (TileWave::Node::tracedRays):
    // only when the frame has cube workers, whose stores tell the cache
    // policy what a hit spares. In a frame where every cube stands aside
    // the count would go nowhere and still cost instructions.
    bool countTreeRays = false;
};

}  // namespace raycache
