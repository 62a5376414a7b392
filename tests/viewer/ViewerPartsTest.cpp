// The viewer's small parts: frame-time history, cube inspector picture,
// difference heat map, frame handoff between threads, technique table.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "cache/CubeCross.h"
#include "scene/BuiltinScenes.h"
#include "viewer/CubeInspectorImage.h"
#include "viewer/DifferenceHeatMap.h"
#include "viewer/FrameHandoff.h"
#include "viewer/FrameTimeHistory.h"
#include "viewer/TechniqueChoice.h"
#include "viewer/ViewerRenderConfig.h"

using namespace raycache;

TEST(FrameTimeHistory, KeepsTheLastTimesInOrderWithTheirMedian) {
    FrameTimeHistory h(4);
    EXPECT_EQ(h.fps(), 0.0);
    for (double t : {10.0, 20.0, 30.0, 40.0, 50.0}) h.add(t);
    EXPECT_EQ(h.size(), 4u);
    EXPECT_EQ(h.chronological(), (std::vector<float>{20, 30, 40, 50}));
    EXPECT_DOUBLE_EQ(h.medianMs(), 35.0);
    EXPECT_DOUBLE_EQ(h.maxMs(), 50.0);
    EXPECT_DOUBLE_EQ(h.fps(), 1000.0 / 35.0);
    h.add(5.0);
    EXPECT_DOUBLE_EQ(h.medianMs(), 35.0);  // {30, 40, 50, 5}
    h.clear();
    EXPECT_EQ(h.size(), 0u);
}

namespace {

CachingCube partlyFilledCube(int size) {
    CachingCube cube({0, 0, 0}, size);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                if ((x + y + f) % 3 == 0) continue;  // left invalid
                const Rgb c{0.125f * static_cast<float>(f + 1), static_cast<float>(x) / 64.0f,
                            static_cast<float>(y) / 64.0f};
                cube.writeIfInvalid(cubeTexelIndex({static_cast<CubeFace>(f), x, y}, size),
                                    CachingCube::encodeTexel(c));
            }
    return cube;
}

}  // namespace

TEST(CubeInspectorImage, AtFullSizeEqualsTheCubeCross) {
    const CachingCube cube = partlyFilledCube(16);
    const Image full = unfoldCubeCross(cube);
    const Image inspector = cubeInspectorImage(cube, 64);  // larger than the cube: full size
    ASSERT_EQ(inspector.width(), full.width());
    ASSERT_EQ(inspector.height(), full.height());
    EXPECT_EQ(inspector.pixels(), full.pixels());
}

TEST(CubeInspectorImage, SmallerPicturesSubsampleTheTexels) {
    const CachingCube cube = partlyFilledCube(16);
    const Image full = unfoldCubeCross(cube);
    const Image small = cubeInspectorImage(cube, 4);  // every 4th texel
    ASSERT_EQ(small.width(), 16);
    ASSERT_EQ(small.height(), 12);
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 16; ++x) {
            const int cellX = x / 4, cellY = y / 4;
            EXPECT_EQ(small.at(x, y), full.at(cellX * 16 + (x % 4) * 4, cellY * 16 + (y % 4) * 4)) << x << "," << y;
        }
}

TEST(CubeInspectorImage, DroppedTexelsAreMagentaUntilFilledAgain) {
    const int n = 16;
    const CachingCube cube = partlyFilledCube(n);
    const Image plain = cubeInspectorImage(cube, n);
    std::vector<std::uint64_t> dropped((cube.texelCount() + 63) / 64, 0);
    const int filledTexel = cubeTexelIndex({CubeFace::PosZ, 0, 0}, n);  // (0 + 0 + 4) % 3 != 0: filled
    const int emptyTexel = cubeTexelIndex({CubeFace::PosZ, 1, 1}, n);    // (1 + 1 + 4) % 3 == 0: invalid
    ASSERT_TRUE(cube.isValid(filledTexel));
    ASSERT_FALSE(cube.isValid(emptyTexel));
    for (const int t : {filledTexel, emptyTexel})
        dropped[static_cast<std::size_t>(t) >> 6] |= std::uint64_t{1} << (static_cast<std::size_t>(t) & 63);
    const Image marked = cubeInspectorImage(cube, n, dropped);
    const CubeCrossCell cell = cubeCrossCell(CubeFace::PosZ);
    const auto at = [&](const Image& image, int x, int y) { return image.at(cell.column * n + x, cell.row * n + y); };
    EXPECT_EQ(at(marked, 1, 1), kDroppedMagenta);                                    // dropped, still empty
    EXPECT_EQ(at(marked, 0, 0), (at(plain, 0, 0) + kDroppedMagenta) * 0.5f);        // dropped, filled again
    EXPECT_EQ(at(marked, 2, 0), at(plain, 2, 0));                                    // not dropped
}

TEST(DifferenceHeatMap, BlueWhereEqualRedWhereOpposite) {
    const std::vector<std::uint8_t> a = {0, 0, 0, 255, 10, 20, 30, 255, 0, 0, 0, 255};
    const std::vector<std::uint8_t> b = {255, 255, 255, 255, 10, 20, 30, 255, 0, 0, 51, 255};
    std::vector<std::uint8_t> out(12);
    const double sum = differenceHeatMap(a, b, 1.0f, out);
    EXPECT_NEAR(sum, 1.0 + 0.0 + 51.0 / (3.0 * 255.0), 1e-6);  // per-pixel values are floats
    EXPECT_EQ((std::vector<std::uint8_t>(out.begin(), out.begin() + 4)), (std::vector<std::uint8_t>{255, 0, 0, 255}));
    EXPECT_EQ((std::vector<std::uint8_t>(out.begin() + 4, out.begin() + 8)),
              (std::vector<std::uint8_t>{0, 0, 255, 255}));
    // 1/15 of the way with gain 1; with gain 15 it reaches the top: red.
    differenceHeatMap(a, b, 15.0f, out);
    EXPECT_EQ((std::vector<std::uint8_t>(out.begin() + 8, out.begin() + 12)),
              (std::vector<std::uint8_t>{255, 0, 0, 255}));
    std::uint8_t mid[3];
    heatMapColor(0.5f, mid);
    EXPECT_EQ((std::vector<std::uint8_t>{mid[0], mid[1], mid[2]}), (std::vector<std::uint8_t>{0, 255, 0}));
}

TEST(FrameHandoff, TheNewestFrameWinsAndBuffersCirculate) {
    FrameHandoff handoff;
    DisplayFrame produced, shown;
    EXPECT_FALSE(handoff.take(shown));
    produced.serial = 1;
    ASSERT_TRUE(handoff.publish(produced, false));
    produced.serial = 2;
    ASSERT_TRUE(handoff.publish(produced, false));  // replaces frame 1, never shown
    ASSERT_TRUE(handoff.take(shown));
    EXPECT_EQ(shown.serial, 2u);
    EXPECT_FALSE(handoff.take(shown));
    EXPECT_EQ(shown.serial, 2u);
}

TEST(FrameHandoff, LosslessPublishWaitsUntilTakenAndCloseReleasesIt) {
    FrameHandoff handoff;
    constexpr int kFrames = 200;
    std::thread producer([&] {
        DisplayFrame f;
        for (int i = 1; i <= kFrames; ++i) {
            f.serial = static_cast<std::uint64_t>(i);
            f.rgba.assign(16, static_cast<std::uint8_t>(i));
            if (!handoff.publish(f, true)) return;
        }
    });
    DisplayFrame shown;
    std::uint64_t expected = 1;
    while (expected <= kFrames) {
        if (!handoff.take(shown)) {
            std::this_thread::yield();
            continue;
        }
        ASSERT_EQ(shown.serial, expected);  // every frame, in order
        ASSERT_EQ(shown.rgba[0], static_cast<std::uint8_t>(expected));
        ++expected;
    }
    producer.join();

    // A publisher blocked on an untaken frame is released by close().
    DisplayFrame f;
    ASSERT_TRUE(handoff.publish(f, true));
    std::atomic<bool> returned{false}, result{true};
    std::thread blocked([&] {
        result = handoff.publish(f, true);
        returned = true;
    });
    handoff.close();
    blocked.join();
    EXPECT_TRUE(returned);
    EXPECT_FALSE(result);
}

TEST(TechniqueChoice, EveryTechniqueHasAChoiceLabelledWithItsName) {
    EXPECT_EQ(techniqueChoiceIndex(std::nullopt), 0);
    EXPECT_FALSE(kTechniqueChoices[0].technique.has_value());
    EXPECT_STREQ(kTechniqueChoices[0].label, "scene");
    for (const CacheTechniqueInfo& info : kCacheTechniques) {
        const TechniqueChoice& choice =
            kTechniqueChoices[static_cast<std::size_t>(techniqueChoiceIndex(info.technique))];
        EXPECT_EQ(choice.technique, info.technique);
        EXPECT_EQ(choice.label, info.name);
    }
}

TEST(ViewerRenderConfig, AppliesChoicesAndRejectsInvalidOnes) {
    const Scene scene = *makeBuiltinScene("room");
    RenderSettings base;
    base.width = 77;
    ViewerRenderConfig config;
    config.technique = techniqueChoiceIndex(CacheTechnique::Cdct);
    config.cacheResolution = 64;
    config.cdctStep = 0.2f;
    config.cdctEpsilon = 0.02f;
    config.maxDepth = 3;
    EXPECT_EQ(viewerRenderConfigError(scene, base, config), "");
    const RenderSettings s = applyViewerRenderConfig(base, config);
    EXPECT_EQ(s.width, 77);
    EXPECT_EQ(s.maxDepth, 3);
    EXPECT_EQ(s.cache.techniqueOverride, CacheTechnique::Cdct);
    EXPECT_EQ(s.cache.resolutionOverride, 64);
    EXPECT_EQ(s.cache.cdctStepOverride, 0.2f);
    EXPECT_EQ(s.cache.cdctEpsilonOverride, 0.02f);

    config.cdctEpsilon = 0.5f;  // not below the step
    EXPECT_NE(viewerRenderConfigError(scene, base, config).find("epsilon"), std::string::npos);
    config.cdctEpsilon = 0.02f;
    config.cacheResolution = 8;
    EXPECT_FALSE(viewerRenderConfigError(scene, base, config).empty());
    config.cacheResolution = 64;
    config.maxDepth = 0;
    EXPECT_FALSE(viewerRenderConfigError(scene, base, config).empty());
}
