// Improved CDCT on concave mirrors and on mirrors that see other mirrors,
// with the uncached render as ground truth: the `bowl` scene's mirrors see
// themselves (rays that meet their own object are traced), and `shapes`'
// mirrors see each other (texels that saw a mirror from the centre are
// traced), and the npm teapot made a mirror shows its body in its spout and
// handle. Each switch is measured on and off, against CCT.
#include <gtest/gtest.h>

#include <cstdio>

#include "PathRender.h"
#include "metrics/ImageMetrics.h"
#include "scene/BuiltinScenes.h"
#include "scene/MeshLoader.h"

using namespace raycache;

namespace {

constexpr int kFrames = 8;
constexpr int kSize = 160;
constexpr int kFaces = 64;  // small faces: CCT answers most of its lookups too

// Mean PSNR against `truth` over frames 2..kFrames (frame 1 traces everything).
double meanPsnr(const PathRender& run, const PathRender& truth) {
    double sum = 0.0;
    for (int f = 1; f < kFrames; ++f)
        sum += psnr(run.frames[static_cast<std::size_t>(f)], truth.frames[static_cast<std::size_t>(f)]);
    return sum / (kFrames - 1);
}

std::uint64_t total(const PathRender& run, std::uint64_t (FrameCacheStats::*count)() const) {
    std::uint64_t sum = 0;
    for (const FrameStats& s : run.stats) sum += ((*s.cache).*count)();
    return sum;
}

// A scene's camera path with improved CDCT with one of its switches off
// (`without`) and with all on, beside CCT; PSNRs against the uncached path.
struct SwitchComparison {
    PathRender without, with;
    double cctDb, withoutDb, withDb;
};

SwitchComparison compareSwitch(const Scene& scene, const CdctImprovements& without) {
    const auto cdct = [&](const CdctImprovements& improvements) {
        return renderPath(scene, CacheTechnique::Cdct, kFrames, false, kSize, 2, kFaces, nullptr,
                          TileBalance::Dynamic, 1, 0, false, VisibleFill::Off, improvements);
    };
    const PathRender plain = renderPath(scene, CacheTechnique::None, kFrames, false, kSize, 2, kFaces);
    const PathRender cct = renderPath(scene, CacheTechnique::Cct, kFrames, false, kSize, 2, kFaces);
    SwitchComparison c{cdct(without), cdct({}), meanPsnr(cct, plain), 0.0, 0.0};
    c.withoutDb = meanPsnr(c.without, plain);
    c.withDb = meanPsnr(c.with, plain);
    return c;
}

}  // namespace

TEST(CdctOwnSurface, ConcaveMirrorsCloserToUncachedThanCctAndThanWithoutTheTest) {
    CdctImprovements without;
    without.traceOwnSurface = false;
    const SwitchComparison c = compareSwitch(*makeBuiltinScene("bowl"), without);
    const PathRender &blind = c.without, &tested = c.with;
    const double cctDb = c.cctDb, blindDb = c.withoutDb, testedDb = c.withDb;
    std::printf("bowl %dx%d, %d^2 faces, frames 2-%d: CCT %.2f dB, CDCT without the own-surface test %.2f dB, "
                "with it %.2f dB\n", kSize, kSize, kFaces, kFrames, cctDb, blindDb, testedDb);
    RecordProperty("cct_psnr_db", std::to_string(cctDb));
    RecordProperty("cdct_blind_psnr_db", std::to_string(blindDb));
    RecordProperty("cdct_psnr_db", std::to_string(testedDb));
    EXPECT_EQ(total(blind, &FrameCacheStats::ownSurface), 0u);
    EXPECT_GT(total(tested, &FrameCacheStats::ownSurface), 1000u);
    // Without the test the bowl shows what lies behind its own wall.
    EXPECT_GE(testedDb - blindDb, 3.0);
    EXPECT_GE(testedDb, cctDb);
}

TEST(CdctOwnSurface, MirrorsSeenFromTheCentreAreTracedAndTheImageComesCloser) {
    CdctImprovements without;
    without.traceViewDependent = false;
    const SwitchComparison c = compareSwitch(*makeBuiltinScene("shapes"), without);
    const PathRender &cached = c.without, &traced = c.with;
    const double cctDb = c.cctDb, cachedDb = c.withoutDb, tracedDb = c.withDb;
    std::printf("shapes %dx%d, %d^2 faces, frames 2-%d: CCT %.2f dB, CDCT with mirrors cached as seen from the "
                "centre %.2f dB, traced %.2f dB\n", kSize, kSize, kFaces, kFrames, cctDb, cachedDb, tracedDb);
    EXPECT_EQ(total(cached, &FrameCacheStats::viewDependent), 0u);
    EXPECT_GT(total(traced, &FrameCacheStats::viewDependent), 100u);
    EXPECT_GT(tracedDb, cachedDb);
    EXPECT_GE(tracedDb, cctDb);
}

// The npm `teapot` (tests/data/meshes/teapot.obj, 992 triangles) made a
// mirror, in `bowl`'s place: its spout, handle and lid reflect its body.
TEST(CdctOwnSurface, MirrorTeapotCloserToUncachedThanCct) {
    Scene scene = *makeBuiltinScene("bowl");
    const TriangleMesh teapot = loadMeshFile(std::string(RAYCACHE_TEST_DATA_DIR) + "/meshes/teapot.obj").mesh;
    Box3 box;
    for (const Vec3& p : teapot.positions) box.add(p);
    const Vec3 centre = (box.lo + box.hi) * 0.5f;
    const float scale = 2.6f / maxComponent(box.hi - box.lo);
    const Vec3 place{-1.2f, 1.0f, 0};
    SceneObject& mirror = scene.objects[1];
    ASSERT_EQ(mirror.name, "bowl");
    mirror.name = "teapot";
    mirror.shape = MeshShape{std::make_shared<const TriangleMesh>(transformed(
        teapot, Transform::translate(place) * Transform::rotate({0, 1, 0}, -30.0f) *
                    Transform::scale({scale, scale, scale}) * Transform::translate(centre * -1.0f)))};
    mirror.origin = place;
    scene.objects.erase(scene.objects.begin() + 2);  // the ball that sat in the bowl
    CdctImprovements without;
    without.traceOwnSurface = false;
    const SwitchComparison c = compareSwitch(scene, without);
    const PathRender& cdctRun = c.with;
    const double cctDb = c.cctDb, cdctDb = c.withDb, blindDb = c.withoutDb;
    std::printf("mirror teapot %dx%d, %d^2 faces, frames 2-%d: CCT %.2f dB, CDCT without the own-surface test %.2f "
                "dB, with it %.2f dB (own surface %llu)\n",
                kSize, kSize, kFaces, kFrames, cctDb, blindDb, cdctDb,
                static_cast<unsigned long long>(total(cdctRun, &FrameCacheStats::ownSurface)));
    EXPECT_GT(total(cdctRun, &FrameCacheStats::ownSurface), 100u);  // it does see itself
    EXPECT_GT(cdctDb, blindDb + 1.0);  // measured 37.45 against 35.06 dB
    EXPECT_GE(cdctDb, cctDb);
}
