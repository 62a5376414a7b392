// The cache's threading contract exercised with plain std::threads, so that
// ThreadSanitizer sees every synchronization (oneTBB and Embree are not built
// with TSan, so renders through them cannot be checked this way): during a
// frame many workers look up and queue stores on one RayCache; endFrame
// merges on one thread. The result must equal a single-threaded run.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "cache/RayCache.h"

using namespace raycache;

namespace {

Scene threeMirrors() {
    Scene s;
    Material mirror;
    mirror.reflectivity = 0.8f;
    mirror.cache = {CacheTechnique::Cct, 32};
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

// Renders `frames` fake frames of `pixels` pixels split over `threads` threads.
std::vector<std::vector<std::uint32_t>> run(int threads, int frames, int pixels) {
    RayCache cache(threeMirrors(), {});
    auto workers = cache.makeWorkers(threads);
    for (int frame = 0; frame < frames; ++frame) {
        cache.beginFrame(workers);
        std::vector<std::thread> pool;
        for (int t = 0; t < threads; ++t)
            pool.emplace_back([&, t] {
                CacheWorker& worker = workers[static_cast<std::size_t>(t)];
                for (int p = t; p < pixels; p += threads) {
                    worker.beginPixel(static_cast<std::uint32_t>(p));
                    for (int bounce = 0; bounce < 2; ++bounce) {
                        const int object = (p + bounce) % 3;
                        const Vec3 d = directionFor(p * 2 + bounce, frame);
                        if (!cache.lookup(object, {0, 0, 0}, d, worker)) {
                            // The "traced" color depends on the pixel, so the first writer matters.
                            const Rgb color{static_cast<float>(p % 97) / 97.0f, 0.5f, static_cast<float>(bounce)};
                            cache.store(object, {0, 0, 0}, d, color, 1.0f, worker);
                        }
                    }
                }
            });
        for (std::thread& th : pool) th.join();
        cache.endFrame(workers);
    }
    std::vector<std::vector<std::uint32_t>> texels;
    for (int o = 0; o < 3; ++o) {
        const auto words = cache.cube(o).texels();
        texels.emplace_back(words.begin(), words.end());
    }
    return texels;
}

}  // namespace

TEST(RayCacheConcurrency, ManyThreadsGiveTheSingleThreadedCaches) {
    const auto reference = run(1, 3, 4000);
    for (int threads : {2, 4, 7}) EXPECT_EQ(run(threads, 3, 4000), reference) << threads << " threads";
}
