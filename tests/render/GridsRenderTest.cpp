// Frames rendered with --accel grids against --accel embree (docs/grids.md):
// the same pixels except where the two tracers' triangle tests round the hit
// distance or barycentrics differently, and bit-identical for any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"

using namespace raycache;

namespace {

Image renderWith(const Scene& scene, Accelerator accelerator, int threads, float time, FrameStats* stats = nullptr) {
    RenderSettings settings;
    settings.width = settings.height = 64;
    settings.threads = threads;
    settings.trace.accelerator = accelerator;
    RenderSession session(scene, settings);
    session.setTime(time);
    Image film;
    const FrameStats s = session.render(scene.camera, film);
    if (stats) *stats = s;
    return film;
}

struct ImageDifference {
    int pixels = 0;
    float maxAbs = 0.0f;
};

ImageDifference difference(const Image& a, const Image& b) {
    ImageDifference d;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const Rgb& p = a.at(x, y);
            const Rgb& q = b.at(x, y);
            const float m = std::max({std::fabs(p.r - q.r), std::fabs(p.g - q.g), std::fabs(p.b - q.b)});
            if (m > 0.0f) ++d.pixels;
            d.maxAbs = std::max(d.maxAbs, m);
        }
    return d;
}

}  // namespace

TEST(GridsRender, FramesMatchEmbreeOnBuiltinScenes) {
    for (const char* name : {"room", "grid-32", "glass", "shapes", "cloth", "light-sweep", "room-moving"}) {
        const std::optional<Scene> scene = makeBuiltinScene(name);
        ASSERT_TRUE(scene) << name;
        FrameStats stats;
        const Image grids = renderWith(*scene, Accelerator::Grids, 2, 1.0f, &stats);
        const Image embree = renderWith(*scene, Accelerator::Embree, 2, 1.0f);
        const ImageDifference d = difference(grids, embree);
        ASSERT_TRUE(stats.trace) << name;
        std::cout << "[grids render] " << name << ": " << d.pixels << " of 4096 pixels differ, max abs "
                  << d.maxAbs << "; grids answered " << stats.trace->primaryAnswered << " primary and "
                  << stats.trace->shadowAnswered << " shadow rays, refused " << stats.trace->primaryRefused << " and "
                  << stats.trace->shadowRefused << "\n";
        // The grids really answered the frame's rays.
        EXPECT_EQ(stats.trace->primaryAnswered, 4096u) << name;
        EXPECT_GT(stats.trace->shadowAnswered, 0u) << name;
        // Hits are the same primitives; only the last bits of t, u, v differ.
        EXPECT_LT(d.maxAbs, 1e-4f) << name;
    }
}

TEST(GridsRender, BitIdenticalForAnyThreadCount) {
    for (const char* name : {"room", "cloth"}) {
        const std::optional<Scene> scene = makeBuiltinScene(name);
        ASSERT_TRUE(scene) << name;
        const Image one = renderWith(*scene, Accelerator::Grids, 1, 0.5f);
        const Image two = renderWith(*scene, Accelerator::Grids, 2, 0.5f);
        const ImageDifference d = difference(one, two);
        EXPECT_EQ(d.pixels, 0) << name;
    }
}
