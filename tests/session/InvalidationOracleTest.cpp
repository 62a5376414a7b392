// Per-block cache invalidation on animated scenes, against an oracle: after
// each change of the scene, every texel that was valid is traced again from
// the ray it was stored for, in the new pose and without caches (the
// uncached render is the truth). A texel that survived the change must come
// out bit-identical (no stale texel, ever); a dropped texel that also comes
// out identical was dropped needlessly (counted and printed: the price of
// conservative bounds).
//
// RayCacheSettings::invalidationOracle makes every lookup miss, so each
// stored colour is exactly its ray's uncached colour and the re-trace can be
// compared bit for bit.
#include <gtest/gtest.h>

#include <cstdio>

#include "scene/BuiltinScenes.h"
#include "session/InvalidationOracle.h"

namespace raycache {
namespace {

RenderSettings oracleSettings() {
    RenderSettings s;
    s.width = 160;
    s.height = 120;
    s.threads = 2;
    s.cache.techniqueOverride = CacheTechnique::Cct;
    s.cache.resolutionOverride = 32;
    s.cache.invalidationOracle = true;
    return s;
}

// `resized`: how many cubes took another resolution over the run.
InvalidationCounts runOracle(const std::string& name, int changes, const RenderSettings& settings = oracleSettings(),
                             int* resized = nullptr) {
    const Scene scene = *makeBuiltinScene(name);
    RenderSession session(scene, settings);
    Image film;
    InvalidationCounts counts;
    // From a third into the animation, where things move at speed (eased
    // keys start at rest), as the dynamic experiment does.
    const float start = scene.animation.duration() / 3.0f;
    for (int frame = 0; frame < changes; ++frame) {
        session.setTime(start + static_cast<float>(frame) / scene.fps);
        const FrameStats stats = session.render(scene.camera, film);
        if (resized && stats.cache)
            for (const ObjectCacheStats& o : stats.cache->objects) *resized += o.resizedTo > 0 ? 1 : 0;
        InvalidationOracle oracle;
        oracle.take(session);
        session.setTime(start + static_cast<float>(frame + 1) / scene.fps);
        counts += oracle.check(session);
    }
    std::printf("[oracle] %s: %lld texels checked over %d changes: %lld kept (%lld stale), %lld dropped "
                "(%lld of them needlessly), %lld really changed\n",
                name.c_str(), static_cast<long long>(counts.checked), changes, static_cast<long long>(counts.kept),
                static_cast<long long>(counts.stale), static_cast<long long>(counts.dropped),
                static_cast<long long>(counts.needless), static_cast<long long>(counts.changed()));
    EXPECT_GT(counts.checked, 0) << name << ": no frame stored a texel";
    // The oracle reproduces the cache: in the pose it was filled in, every
    // texel's ray traced again gives the stored word.
    EXPECT_EQ(counts.differing, 0) << name;
    return counts;
}

TEST(InvalidationOracle, MovingObjectsLeaveNoStaleTexelAndKeepTheRest) {
    for (const char* name : {"room-moving", "orbit"}) {
        const InvalidationCounts c = runOracle(name, 3);
        EXPECT_EQ(c.stale, 0) << name;
        // Not everything is thrown away: the test could fail.
        EXPECT_GT(c.kept, 0) << name;
        EXPECT_GT(c.changed(), 0) << name;  // the change did alter texels
    }
}

// orbit's mirror spheres move: of their texels, those whose rays escaped to
// the sky and still do are kept (and, above, none of them is stale).
TEST(InvalidationOracle, MovingSpheresKeepTheirEscapedRays) {
    const InvalidationCounts c = runOracle("orbit", 3);
    EXPECT_GT(c.movedCube, 0);
    EXPECT_GT(c.movedCubeKept, 0);
    EXPECT_LT(c.movedCubeKept, c.movedCube);  // those that hit something go
    EXPECT_EQ(c.stale, 0);
}

TEST(InvalidationOracle, DeformingMeshLeavesNoStaleTexel) {
    const InvalidationCounts c = runOracle("cloth", 2);
    EXPECT_EQ(c.stale, 0);
    EXPECT_GT(c.changed(), 0);
}

// A moving light changes the light at every shaded point: only trees that
// shaded nothing (rays that escaped to the environment) may stay.
TEST(InvalidationOracle, MovingLightLeavesNoStaleTexel) {
    const InvalidationCounts c = runOracle("light-sweep", 2);
    EXPECT_EQ(c.stale, 0);
    EXPECT_GT(c.changed(), 0);
}

// Cubes resampled to the view's resolution (RayCacheSettings::
// resolutionFromView) keep exact invalidation: a resampled texel keeps the
// record of the ray whose colour it took, and its block the union of the
// blocks that colour came from.
TEST(InvalidationOracle, ResizedCubesLeaveNoStaleTexel) {
    RenderSettings settings = oracleSettings();
    settings.cache.resolutionOverride = 256;  // finer than room's ball needs at 160×120: shrinks to 128²
    settings.cache.resolutionFromView = true;
    int resized = 0;
    const InvalidationCounts c = runOracle("room-moving", 3, settings, &resized);
    EXPECT_GT(resized, 0);  // the test could fail
    EXPECT_EQ(c.stale, 0);
    EXPECT_GT(c.kept, 0);
    EXPECT_GT(c.changed(), 0);
}

}  // namespace
}  // namespace raycache
