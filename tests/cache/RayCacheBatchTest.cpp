// RayCache::lookupBatch against one lookup() per query (the oracle): the
// same answers, the same counters, and store texels that fill exactly the
// texels a plain store() would.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cache/RayCache.h"

using namespace raycache;

namespace {

Scene mirrors(CacheTechnique technique) {
    Scene s;
    Material mirror;
    mirror.reflectivity = 0.8f;
    mirror.cache = {technique, 16};
    for (int i = 0; i < 2; ++i) {
        const Vec3 c{static_cast<float>(4 * i), 0, 0};
        s.objects.push_back(SceneObject{"m" + std::to_string(i), Sphere{c, 1}, mirror, c});
    }
    return s;
}

std::vector<RayCache::Query> queries(int count, int frame) {
    std::vector<RayCache::Query> q;
    for (int i = 0; i < count; ++i) {
        const float a = 0.61f * static_cast<float>(i) + 0.2f * static_cast<float>(frame);
        const Vec3 d = normalize(Vec3{std::cos(a), std::sin(1.3f * a), std::cos(0.7f * a)});
        const int object = i % 2;
        q.push_back({object, Vec3{static_cast<float>(4 * object), 0, 0} + d * 1.001f, d});
    }
    return q;
}

struct Answers {
    std::vector<unsigned char> found;
    std::vector<Rgb> colors;
    FrameCacheStats stats;
    std::vector<std::uint32_t> texels;  // both cubes after the frame
    std::vector<std::int8_t> levels;    // Lookups::BatchedWithLevels: the answering level of each query
};

enum class Lookups { Single, Batched, BatchedWithLevels };

// Three frames; in each, every unanswered query stores a colour of its own.
std::vector<Answers> run(CacheTechnique technique, Lookups lookups) {
    const bool batched = lookups != Lookups::Single;
    RayCache cache(mirrors(technique), {});
    auto workers = cache.makeWorkers(1);
    std::vector<Answers> frames;
    for (int frame = 0; frame < 3; ++frame) {
        const auto q = queries(300, frame);
        Answers a;
        a.found.assign(q.size(), 0);
        a.colors.assign(q.size(), Rgb{});
        std::vector<int> storeTexels(q.size(), -1);
        cache.beginFrame(workers);
        workers[0].beginBatch(0);
        if (lookups == Lookups::BatchedWithLevels) {
            a.levels.assign(q.size(), 99);
            cache.lookupBatch(q, a.colors, a.found, storeTexels, workers[0], {}, a.levels);
        } else if (batched) {
            cache.lookupBatch(q, a.colors, a.found, storeTexels, workers[0]);
        } else {
            for (std::size_t i = 0; i < q.size(); ++i)
                if (const auto c = cache.lookup(q[i].objectId, q[i].origin, q[i].direction, workers[0])) {
                    a.found[i] = 1;
                    a.colors[i] = *c;
                }
        }
        for (std::size_t i = 0; i < q.size(); ++i)
            if (!a.found[i])
                cache.store(q[i].objectId, q[i].origin, q[i].direction,
                            Rgb{static_cast<float>(i) / 300.0f, 0.5f, static_cast<float>(frame)}, 2.0f, workers[0],
                            storeTexels[i]);
        a.stats = cache.endFrame(workers);
        for (int o = 0; o < 2; ++o)
            for (std::uint32_t w : cache.cube(o).texels()) a.texels.push_back(w);
        frames.push_back(std::move(a));
    }
    return frames;
}

}  // namespace

TEST(RayCacheBatch, AnswersCountersAndStoresEqualOneLookupPerQuery) {
    for (CacheTechnique technique : {CacheTechnique::Cct, CacheTechnique::CdctParity}) {
        const auto single = run(technique, Lookups::Single);
        for (const Lookups lookups : {Lookups::Batched, Lookups::BatchedWithLevels}) {
            const auto batched = run(technique, lookups);
            for (std::size_t f = 0; f < single.size(); ++f) {
                EXPECT_EQ(batched[f].found, single[f].found) << "frame " << f;
                EXPECT_EQ(batched[f].colors == single[f].colors, true) << "frame " << f;
                EXPECT_EQ(batched[f].stats.lookups(), single[f].stats.lookups());
                EXPECT_EQ(batched[f].stats.hits(), single[f].stats.hits());
                EXPECT_EQ(batched[f].stats.stores(), single[f].stats.stores());
                EXPECT_EQ(batched[f].texels, single[f].texels) << "frame " << f;
            }
        }
        // The levels asked for: the finest (single-level cubes) for every
        // answered query, -1 for the others.
        for (const Answers& a : run(technique, Lookups::BatchedWithLevels))
            for (std::size_t i = 0; i < a.found.size(); ++i) EXPECT_EQ(a.levels[i], a.found[i] ? 0 : -1) << i;
        if (technique == CacheTechnique::Cct) {
            // The queries repeat directions across frames, so later frames answer some.
            EXPECT_GT(single[2].stats.hits(), 0u);
            EXPECT_LT(single[2].stats.hits(), single[2].stats.lookups());
        }
    }
}

TEST(RayCacheBatch, IdealModeAnswersEveryMissWithBlackAndStoresNothing) {
    for (CacheTechnique technique : {CacheTechnique::Cct, CacheTechnique::CdctParity})
        for (const bool withLevels : {false, true}) {
            RayCacheSettings settings;
            settings.ideal = true;
            RayCache cache(mirrors(technique), settings);
            auto workers = cache.makeWorkers(1);
            const auto q = queries(50, 0);
            std::vector<Rgb> colors(q.size(), Rgb{1.0f});
            std::vector<unsigned char> found(q.size(), 0);
            std::vector<int> storeTexels(q.size(), 7);
            std::vector<std::int8_t> levels(withLevels ? q.size() : 0, 99);
            cache.beginFrame(workers);
            cache.lookupBatch(q, colors, found, storeTexels, workers[0], {}, levels);
            const FrameCacheStats stats = cache.endFrame(workers);
            for (std::size_t i = 0; i < q.size(); ++i) {
                EXPECT_EQ(found[i], 1);
                EXPECT_EQ(colors[i], Rgb{});
                EXPECT_EQ(storeTexels[i], -1);
                // Black stands in for the trace: no level answered.
                if (withLevels) {
                    EXPECT_EQ(levels[i], -1);
                }
            }
            EXPECT_EQ(stats.misses(), q.size());
        }
}
