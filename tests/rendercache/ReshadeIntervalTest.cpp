// The Render Cache's reshading interval (RenderCacheSettings::reshadeInterval,
// `--rc-reshade-every`): against the same run reshading every sample every
// frame, an interval of 4 reshades about a quarter of the view-dependent
// samples per moving frame, leaves what is sampled unchanged, and on the
// first frame the camera stands still reshades the rest, so that the image
// is again the one every-frame reshading gives, but for the few samples that
// win their pixel only when the camera stops (every-frame reshading last
// shaded them from an older eye; the interval's catch-up from this one), and
// as close to the ray pipeline's; on one and two threads alike.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/ColorSpace.h"

#include "ImageCompare.h"
#include "rendercache/ReshadeSelection.h"
#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"

using namespace raycache;

namespace {

RenderSettings settingsWithInterval(int interval, int threads) {
    RenderSettings s;
    s.width = 64;
    s.height = 64;
    s.threads = threads;
    s.pipeline = PipelineKind::RenderCache;
    // Uncached: a reshaded colour then depends on the sample and the eye alone.
    s.cache.techniqueOverride = CacheTechnique::None;
    s.renderCache.reflections = ReprojectedReflections::Reshade;
    s.renderCache.budget = 0.1f;
    s.renderCache.reshadeInterval = interval;
    return s;
}

struct Frame {
    Image image;
    RenderCacheStats stats;
};

// Frames along room's path, then two with the camera still at the last one.
std::vector<Frame> renderMovingThenStill(const Scene& scene, const RenderSettings& settings, int moving) {
    RenderSession session(scene, settings);
    std::vector<Frame> frames;
    for (int frame = 0; frame < moving + 2; ++frame) {
        const Camera camera = scene.cameraPath.cameraAt(scene.camera, std::min(frame, moving - 1));
        Frame f;
        const FrameStats stats = session.render(camera, f.image);
        EXPECT_TRUE(stats.renderCache.has_value());
        if (stats.renderCache) f.stats = *stats.renderCache;
        frames.push_back(std::move(f));
    }
    return frames;
}

// Sum of squared differences of the displayed values.
double squaredError(const Image& a, const Image& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
        const Rgb &x = a.pixels()[i], &y = b.pixels()[i];
        for (const auto& [u, v] : {std::pair{x.r, y.r}, std::pair{x.g, y.g}, std::pair{x.b, y.b}}) {
            const double d = displayedValue(u) - displayedValue(v);
            sum += d * d;
        }
    }
    return sum;
}

}  // namespace

TEST(ReshadeSelection, EachPixelTakesItsTurnOnceInAnInterval) {
    for (int interval : {2, 3, 4, 16}) {
        for (int y = 0; y < 5; ++y) {
            for (int x = 0; x < 7; ++x) {
                int turns = 0;
                for (std::uint32_t round = 0; round < static_cast<std::uint32_t>(interval); ++round)
                    turns += ReshadeSelection{true, interval, round}.inTurn(x, y) ? 1 : 0;
                EXPECT_EQ(turns, 1) << "interval " << interval << " pixel " << x << "," << y;
            }
        }
    }
    SampleLook plain, mirror, stale;
    mirror.viewDependent = kViewDependent;
    stale.viewDependent = kViewDependent | kShadedFromAnOlderEye;
    const ReshadeSelection still{false, 4, 0}, moving{true, 1, 0};
    EXPECT_FALSE(still.chooses(plain, 0, 0));
    EXPECT_FALSE(still.chooses(mirror, 0, 0)) << "a still frame reshades only what an older eye shaded";
    EXPECT_TRUE(still.chooses(stale, 0, 0));
    EXPECT_FALSE(moving.chooses(plain, 0, 0));
    EXPECT_TRUE(moving.chooses(mirror, 5, 3));
    EXPECT_FALSE(ReshadeSelection({false, 1, 0}).any()) << "the default does nothing on a still frame";
}

TEST(ReshadeInterval, AQuarterPerMovingFrameThenTheRestWhenTheCameraStops) {
    const auto scene = makeBuiltinScene("room");
    ASSERT_TRUE(scene.has_value());
    constexpr int kMoving = 6;
    const std::vector<Frame> every = renderMovingThenStill(*scene, settingsWithInterval(1, 2), kMoving);
    const std::vector<Frame> quarter = renderMovingThenStill(*scene, settingsWithInterval(4, 2), kMoving);
    const std::vector<Frame> quarterOneThread = renderMovingThenStill(*scene, settingsWithInterval(4, 1), kMoving);
    ASSERT_EQ(every.size(), quarter.size());
    int framesThatDiffer = 0;
    for (std::size_t i = 0; i < every.size(); ++i) {
        const RenderCacheStats &a = every[i].stats, &b = quarter[i].stats;
        // What is traced and where samples land do not depend on reshading.
        EXPECT_EQ(a.fresh, b.fresh) << i;
        EXPECT_EQ(a.reprojected, b.reprojected) << i;
        EXPECT_EQ(a.holes, b.holes) << i;
        EXPECT_TRUE(identicalImages(quarter[i].image, quarterOneThread[i].image)) << "frame " << i;
        EXPECT_EQ(b.reshaded, quarterOneThread[i].stats.reshaded) << i;
        const bool moving = i >= 1 && i < static_cast<std::size_t>(kMoving);
        if (moving) {
            ASSERT_GT(a.reshaded, 500) << "room's mirrors and highlights, frame " << i;
            const double share = static_cast<double>(b.reshaded) / static_cast<double>(a.reshaded);
            EXPECT_GT(share, 0.2) << i;
            EXPECT_LT(share, 0.3) << i;
            framesThatDiffer += identicalImages(every[i].image, quarter[i].image) ? 0 : 1;
        }
    }
    EXPECT_GT(framesThatDiffer, 0) << "samples out of their turn show an older eye's colour while the camera moves";
    // The first still frame: every-frame reshading has nothing to do, the
    // interval reshades the samples an older eye shaded; the images agree
    // but for samples every-frame reshading left behind, and are as close
    // to the ray pipeline's image.
    const std::size_t firstStill = kMoving, secondStill = kMoving + 1;
    EXPECT_EQ(every[firstStill].stats.reshaded, 0);
    EXPECT_GT(quarter[firstStill].stats.reshaded, 0);
    EXPECT_EQ(quarter[secondStill].stats.reshaded, 0);
    RenderSettings ray = settingsWithInterval(1, 2);
    ray.pipeline = PipelineKind::Ray;
    Image full;
    RenderSession(*scene, ray).render(scene->cameraPath.cameraAt(scene->camera, kMoving - 1), full);
    for (const std::size_t still : {firstStill, secondStill}) {
        const Image &a = every[still].image, &b = quarter[still].image;
        int differing = 0;
        for (std::size_t p = 0; p < a.pixels().size(); ++p) differing += a.pixels()[p] == b.pixels()[p] ? 0 : 1;
        EXPECT_LE(differing, 64 * 64 / 200) << "still frame " << still;
        EXPECT_LE(squaredError(b, full), 1.01 * squaredError(a, full)) << "still frame " << still;
    }
}
