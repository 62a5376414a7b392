// Pipeline auto's choice between full frames and the Render Cache, from the
// render times of the frames shown (no window, no clock).
#include "viewer/AutoPipelineRule.h"

#include <gtest/gtest.h>

using namespace raycache;

namespace {
constexpr std::int64_t kFull = 1024 * 1024;
constexpr std::int64_t kHalf = 512 * 512;  // the size full frames take while moving (moving scale 0.5)
constexpr double kTargetMs = 1000.0 / 30.0;
}  // namespace

TEST(AutoPipelineRule, AStillCameraAlwaysGetsFullFrames) {
    AutoPipelineRule rule(kTargetMs);
    rule.observe(ShownPipeline::FullFrame, 500.0, kFull);  // far too slow to keep any rate
    rule.observe(ShownPipeline::RenderCache, 5.0, kFull);  // and the Render Cache far faster
    EXPECT_EQ(rule.choose(false, true, kFull, kFull), ShownPipeline::FullFrame);
}

TEST(AutoPipelineRule, FullFramesThatKeepTheRateAreShownWhileMoving) {
    AutoPipelineRule rule(kTargetMs);
    // 80 ms at 1024² is 20 ms at the moving size: within 33 ms.
    rule.observe(ShownPipeline::FullFrame, 80.0, kFull);
    rule.observe(ShownPipeline::RenderCache, 5.0, kFull);
    EXPECT_NEAR(rule.estimateMs(ShownPipeline::FullFrame, kHalf), 20.0, 1e-9);
    EXPECT_EQ(rule.choose(true, true, kHalf, kFull), ShownPipeline::FullFrame);
    // Without the reduction (moving scale 1) the same full frame misses it.
    EXPECT_EQ(rule.choose(true, true, kFull, kFull), ShownPipeline::RenderCache);
}

TEST(AutoPipelineRule, WithoutAMeasurementFullFramesComeFirstThenTheRenderCacheIsTried) {
    AutoPipelineRule rule(kTargetMs);
    EXPECT_LT(rule.estimateMs(ShownPipeline::FullFrame, kFull), 0.0);
    EXPECT_EQ(rule.choose(true, true, kFull, kFull), ShownPipeline::FullFrame);
    rule.observe(ShownPipeline::FullFrame, 100.0, kFull);
    // Full frames miss the target; the Render Cache's cost is unknown: try it.
    EXPECT_EQ(rule.choose(true, true, kFull, kFull), ShownPipeline::RenderCache);
}

TEST(AutoPipelineRule, TheRenderCacheIsShownOnlyWhereItIsFaster) {
    AutoPipelineRule rule(kTargetMs);
    rule.observe(ShownPipeline::FullFrame, 100.0, kFull);
    rule.observe(ShownPipeline::RenderCache, 130.0, kFull);  // slower: it would not help
    EXPECT_EQ(rule.choose(true, true, kFull, kFull), ShownPipeline::FullFrame);
    AutoPipelineRule faster(kTargetMs);
    faster.observe(ShownPipeline::FullFrame, 100.0, kFull);
    faster.observe(ShownPipeline::RenderCache, 40.0, kFull);
    EXPECT_EQ(faster.choose(true, true, kFull, kFull), ShownPipeline::RenderCache);
    // A scene that moves never gets it.
    EXPECT_EQ(faster.choose(true, false, kFull, kFull), ShownPipeline::FullFrame);
}

TEST(AutoPipelineRule, NearlyEqualCostsDoNotFlipFromFrameToFrame) {
    AutoPipelineRule rule(kTargetMs);
    rule.observe(ShownPipeline::FullFrame, 100.0, kFull);
    rule.observe(ShownPipeline::RenderCache, 90.0, kFull);  // 0.9 of a full frame: not enough to switch
    EXPECT_EQ(rule.choose(true, true, kFull, kFull), ShownPipeline::FullFrame);
    AutoPipelineRule showing(kTargetMs);
    showing.observe(ShownPipeline::FullFrame, 100.0, kFull);
    EXPECT_EQ(showing.choose(true, true, kFull, kFull), ShownPipeline::RenderCache);  // tried
    showing.observe(ShownPipeline::RenderCache, 90.0, kFull);
    // Once shown, it stays while it beats a full frame at all.
    EXPECT_EQ(showing.choose(true, true, kFull, kFull), ShownPipeline::RenderCache);
    for (int i = 0; i < 20; ++i) showing.observe(ShownPipeline::RenderCache, 120.0, kFull);
    EXPECT_EQ(showing.choose(true, true, kFull, kFull), ShownPipeline::FullFrame);
    // Stopping the camera gives full frames again.
    showing.observe(ShownPipeline::RenderCache, 10.0, kFull);
    EXPECT_EQ(showing.choose(false, true, kFull, kFull), ShownPipeline::FullFrame);
}

TEST(AutoPipelineRule, EstimatesFollowNewMeasurementsGradually) {
    AutoPipelineRule rule(kTargetMs);
    rule.observe(ShownPipeline::FullFrame, 100.0, kFull);
    rule.observe(ShownPipeline::FullFrame, 20.0, kFull);
    const double blended = (1.0 - AutoPipelineRule::kNewWeight) * 100.0 + AutoPipelineRule::kNewWeight * 20.0;
    EXPECT_NEAR(rule.estimateMs(ShownPipeline::FullFrame, kFull), blended, 1e-9);
    // Measurements of no pixels, or no time, teach nothing.
    rule.observe(ShownPipeline::FullFrame, 5.0, 0);
    rule.observe(ShownPipeline::FullFrame, -1.0, kFull);
    EXPECT_NEAR(rule.estimateMs(ShownPipeline::FullFrame, kFull), blended, 1e-9);
}
