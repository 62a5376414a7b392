// The cache's threading contract exercised with plain std::threads, so that
// ThreadSanitizer sees every synchronization (oneTBB and Embree are not built
// with TSan, so renders through them cannot be checked this way): during a
// frame many workers look up (one by one and in batches) and queue stores on
// one RayCache; endFrame merges, on one thread or with its cube partitions
// on several. The result must equal a single-threaded run.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>
#include <thread>
#include <vector>

#include "cache/RayCache.h"

using namespace raycache;

namespace {

Scene threeMirrors(CacheTechnique technique) {
    Scene s;
    Material mirror;
    mirror.reflectivity = 0.8f;
    mirror.cache = {technique, 32};
    for (int i = 0; i < 3; ++i) {
        const Vec3 c{static_cast<float>(3 * i), 0, 0};
        s.objects.push_back(SceneObject{"m" + std::to_string(i), Sphere{c, 1}, mirror, c});
    }
    return s;
}

// A deterministic "pixel": which object and direction it asks about in a frame.
Vec3 directionFor(int pixel, int frame) {
    const float a = 0.37f * static_cast<float>(pixel) + 0.11f * static_cast<float>(frame);
    return {std::cos(a), std::sin(1.7f * a), std::cos(0.3f * a) - 0.2f};
}

// Renders `frames` fake frames of `pixels` pixels split over `threads`
// threads; returns the cubes' texels and every answer the cache gave.
// `viewSized`: cubes sized from the view (RayCacheSettings::resolutionFromView),
// the batch lookups wide enough to halve them after the first frame, so the
// resampling runs on endFrame's partition threads.
std::vector<std::vector<std::uint32_t>> run(int threads, int frames, int pixels,
                                            CacheTechnique technique = CacheTechnique::Cct, bool viewSized = false) {
    // endFrame's cube partitions, each on a thread of its own when threads > 1.
    const RayCache::PartitionRunner partitionsOnThreads = [&](int count, const std::function<void(int)>& body) {
        std::vector<std::thread> pool;
        for (int part = 0; part < count; ++part) pool.emplace_back([&body, part] { body(part); });
        for (std::thread& th : pool) th.join();
    };
    RayCacheSettings settings;
    settings.resolutionFromView = viewSized;
    RayCache cache(threeMirrors(technique), settings);
    auto workers = cache.makeWorkers(threads);
    std::vector<std::uint32_t> answers(static_cast<std::size_t>(frames * pixels * 2), 0u);
    for (int frame = 0; frame < frames; ++frame) {
        cache.beginFrame(workers);
        std::vector<std::thread> pool;
        for (int t = 0; t < threads; ++t)
            pool.emplace_back([&, t] {
                CacheWorker& worker = workers[static_cast<std::size_t>(t)];
                for (int p = t; p < pixels; p += threads) {
                    worker.beginBatch(static_cast<std::uint32_t>(p));
                    for (int bounce = 0; bounce < 2; ++bounce) {
                        const int object = (p + bounce) % 3;
                        const Vec3 d = directionFor(p * 2 + bounce, frame);
                        // Leaving the sphere's surface (CDCT searches from there).
                        const Vec3 origin = Vec3{static_cast<float>(3 * object), 0, 0} + normalize(d) * 1.001f;
                        // Odd pixels ask through the batch call, even ones one by one.
                        std::optional<Rgb> answer;
                        int storeTexel = -1;
                        if (p % 2 == 1) {
                            const RayCache::Query query{object, origin, d, viewSized ? 0.5f : 0.0f};
                            Rgb color;
                            unsigned char found = 0;
                            cache.lookupBatch({&query, 1}, {&color, 1}, {&found, 1}, {&storeTexel, 1}, worker);
                            if (found) answer = color;
                        } else {
                            answer = cache.lookup(object, origin, d, worker);
                        }
                        if (answer)
                            answers[static_cast<std::size_t>((frame * pixels + p) * 2 + bounce)] =
                                CachingCube::encodeTexel(*answer);
                        if (!answer) {
                            // The "traced" color depends on the pixel, so the first writer matters.
                            const Rgb color{static_cast<float>(p % 97) / 97.0f, 0.5f, static_cast<float>(bounce)};
                            cache.store(object, origin, d, color, 1.0f, worker, storeTexel);
                        }
                    }
                }
            });
        for (std::thread& th : pool) th.join();
        // Improved CDCT: the cubes asked for are filled between frames (a
        // surface 4 units out, colours telling texels apart).
        for (const int object : cache.objectsAwaitingPrefill(workers)) {
            std::vector<RayCache::PrefillTexel> texels(cache.cube(object).texelCount());
            for (std::size_t i = 0; i < texels.size(); ++i)
                texels[i] = {Rgb{static_cast<float>(i % 101), static_cast<float>(object), 1.0f}, 4.0f};
            cache.completePrefill(object, texels);
        }
        if (threads > 1) cache.endFrame(workers, partitionsOnThreads);
        else cache.endFrame(workers);
    }
    std::vector<std::vector<std::uint32_t>> texels;
    for (int o = 0; o < 3; ++o) {
        const auto words = cache.cube(o).texels();
        texels.emplace_back(words.begin(), words.end());
        const auto depths = cache.cube(o).depthWords();
        texels.emplace_back(depths.begin(), depths.end());
    }
    texels.push_back(std::move(answers));
    return texels;
}

}  // namespace

TEST(RayCacheConcurrency, ManyThreadsGiveTheSingleThreadedCaches) {
    const auto reference = run(1, 3, 4000);
    for (int threads : {2, 4, 7}) EXPECT_EQ(run(threads, 3, 4000), reference) << threads << " threads";
}

TEST(RayCacheConcurrency, CubesSizedFromTheViewResizeAlikeOnManyThreads) {
    const auto reference = run(1, 3, 4000, CacheTechnique::Cct, true);
    ASSERT_EQ(reference[0].size(), 6u * 16u * 16u);  // the cube was halved: the test could fail
    for (int threads : {2, 4}) EXPECT_EQ(run(threads, 3, 4000, CacheTechnique::Cct, true), reference) << threads << " threads";
}

TEST(RayCacheConcurrency, CdctParityAndImprovedSearchesFromManyThreads) {
    for (CacheTechnique technique : {CacheTechnique::CdctParity, CacheTechnique::Cdct}) {
        const auto reference = run(1, 3, 2000, technique);
        std::size_t answered = 0;
        for (std::uint32_t a : reference.back()) answered += a != 0u;
        EXPECT_GT(answered, 0u) << "the searches answer something";
        for (int threads : {2, 5})
            EXPECT_EQ(run(threads, 3, 2000, technique), reference) << threads << " threads";
    }
}
