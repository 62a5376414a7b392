// Memory stays flat over a long camera path with caches on: once the caching
// cubes are as full as the path makes them, a frame must give back everything
// it takes. A few hundred frames at 64x64 pixels and 16x16 cube faces (the
// smallest allowed, so the cubes fill early); the 10 000-frame run is
// benchmarks/soak.cpp.
// Sizes only, never times.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "cache/RayCache.h"
#include "core/Parallel.h"
#include "core/ProcessMemory.h"
#include "render/FramePipeline.h"
#include "scene/BuiltinScenes.h"
#include "session/PipelineFactory.h"
#include "trace/TraceScene.h"

using namespace raycache;

namespace {

constexpr int kFrames = 300;
// A leak of one 64x64 float film per frame (48 KiB) would add 7 MiB over the
// second half; these bounds leave room only for allocator and page noise.
constexpr std::size_t kMaxHeapGrowth = 256 * 1024;
constexpr std::size_t kMaxResidentGrowth = 4 * 1024 * 1024;

struct MemorySample {
    int frame;
    std::size_t heap;
    std::size_t resident;
};

class MemorySoak : public ::testing::TestWithParam<CacheTechnique> {};

}  // namespace

// The two measures must see an allocation, or the soak test could not fail.
TEST(ProcessMemory, SeesAOneMebibyteAllocation) {
    const std::size_t heapBefore = heapBytesInUse(), residentBefore = residentBytes();
    std::vector<char> block(1 << 20, 1);
    const std::size_t heapAfter = heapBytesInUse(), residentAfter = residentBytes();
    EXPECT_GE(heapAfter, heapBefore + block.size());
    if (residentBytesAreMeaningful()) {
        EXPECT_GE(residentAfter, residentBefore + block.size() - 64 * 1024);
    }
    EXPECT_EQ(block[12345], 1);
}

TEST_P(MemorySoak, FlatAfterTheCachesFillOnAnOrbit) {
    const Scene scene = *makeBuiltinScene("room");  // orbiting camera, a mirror ball with a cube
    RenderSettings settings;
    settings.width = settings.height = 64;
    settings.threads = 2;
    settings.cache.techniqueOverride = GetParam();
    settings.cache.resolutionOverride = 16;
    const TraceScene tracer(scene);
    const Parallel parallel(settings.threads);
    RayCache cache(scene, settings.cache);
    const auto pipeline = makeFramePipeline(scene, tracer, settings, parallel, &cache);

    std::vector<MemorySample> samples;
    double invalidAtHalf = 0.0, invalidAtEnd = 0.0;
    std::uint64_t hitsInLastFrame = 0;
    for (int f = 0; f < kFrames; ++f) {
        Image film;  // a new film every frame, as the render command does
        const FrameStats stats = pipeline->render(scene.cameraPath.cameraAt(scene.camera, f), film);
        ASSERT_TRUE(stats.cache.has_value());
        if (f == kFrames / 2 - 1) invalidAtHalf = stats.cache->invalidPercentBefore();
        if (f == kFrames - 1) {
            invalidAtEnd = stats.cache->invalidPercentBefore();
            hitsInLastFrame = stats.cache->hits();
        }
        if ((f + 1) % 50 == 0) samples.push_back({f + 1, heapBytesInUse(), residentBytes()});
    }
    for (const MemorySample& s : samples)
        std::printf("[ memory   ] frame %3d: heap %8.1f KiB, resident %8.1f KiB\n", s.frame,
                    static_cast<double>(s.heap) / 1024.0, static_cast<double>(s.resident) / 1024.0);
    std::printf(
        "[ memory   ] cube invalid before frame %d: %.2f %%, before frame %d: %.2f %%; hits in the last "
        "frame %llu\n",
        kFrames / 2, invalidAtHalf, kFrames, invalidAtEnd, static_cast<unsigned long long>(hitsInLastFrame));

    // The cache is in use and no longer filling: the second half measures a
    // steady state, not the cubes' first writes.
    EXPECT_GT(hitsInLastFrame, 0u);
    EXPECT_NEAR(invalidAtEnd, invalidAtHalf, 1.0);
    const MemorySample& half = samples[samples.size() / 2 - 1];  // frame 150
    const MemorySample& end = samples.back();                    // frame 300
    ASSERT_EQ(half.frame, kFrames / 2);
    const auto growth = [](std::size_t from, std::size_t to) { return to > from ? to - from : 0; };
    EXPECT_LT(growth(half.heap, end.heap), kMaxHeapGrowth)
        << "live heap grew from frame " << half.frame << " to " << end.frame;
    if (residentBytesAreMeaningful()) {
        EXPECT_LT(growth(half.resident, end.resident), kMaxResidentGrowth)
            << "resident memory grew from frame " << half.frame << " to " << end.frame;
    }
}

INSTANTIATE_TEST_SUITE_P(Techniques, MemorySoak, ::testing::Values(CacheTechnique::Cct, CacheTechnique::Cdct),
                         [](const ::testing::TestParamInfo<CacheTechnique>& p) {
                             return std::string(p.param == CacheTechnique::Cct ? "Cct" : "Cdct");
                         });
