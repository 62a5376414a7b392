// validateRenderCacheSettings(): every range boundary accepted, every value
// just outside refused with an InputError naming the option.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "core/Errors.h"
#include "render/RenderCacheSettings.h"

using namespace raycache;

namespace {

// The message of the InputError `change` provokes, or "" when none is thrown.
std::string errorOf(const std::function<void(RenderCacheSettings&)>& change) {
    RenderCacheSettings s;
    change(s);
    try {
        validateRenderCacheSettings(s);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(RenderCacheSettings, DefaultsAndBoundariesAreValid) {
    EXPECT_EQ(errorOf([](RenderCacheSettings&) {}), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.alpha = 0.0f; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.alpha = 1.0f; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.budget = 1.0f; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.budget = 1e-6f; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.maxAge = 1; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.maxAge = 65000; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.predictShare = 0.0f; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.predictShare = 0.9f; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.targetFrameMs = 60000.0f; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.margin = 0.0f; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.requestTileSize = 1; }), "");
    EXPECT_EQ(errorOf([](RenderCacheSettings& s) { s.requestTileSize = 256; }), "");
}

TEST(RenderCacheSettings, ValuesOutOfRangeNameTheirOption) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const struct {
        std::function<void(RenderCacheSettings&)> change;
        const char* option;
    } cases[] = {
        {[](RenderCacheSettings& s) { s.alpha = -0.01f; }, "--rc-alpha"},
        {[](RenderCacheSettings& s) { s.alpha = 1.01f; }, "--rc-alpha"},
        {[&](RenderCacheSettings& s) { s.alpha = nan; }, "--rc-alpha"},
        {[](RenderCacheSettings& s) { s.budget = 0.0f; }, "--rc-budget"},
        {[](RenderCacheSettings& s) { s.budget = -1.0f; }, "--rc-budget"},
        {[](RenderCacheSettings& s) { s.budget = 1.01f; }, "--rc-budget"},
        {[&](RenderCacheSettings& s) { s.budget = inf; }, "--rc-budget"},
        {[](RenderCacheSettings& s) { s.targetFrameMs = -1.0f; }, "--rc-target-ms"},
        {[&](RenderCacheSettings& s) { s.targetFrameMs = nan; }, "--rc-target-ms"},
        {[](RenderCacheSettings& s) { s.maxAge = 0; }, "--rc-max-age"},
        {[](RenderCacheSettings& s) { s.maxAge = 65001; }, "--rc-max-age"},  // ages are 16-bit
        {[](RenderCacheSettings& s) { s.predictShare = 0.91f; }, "--rc-predict"},
        {[](RenderCacheSettings& s) { s.predictShare = -0.1f; }, "--rc-predict"},
        {[](RenderCacheSettings& s) { s.margin = 0.51f; }, "--rc-margin"},
        {[](RenderCacheSettings& s) { s.depthCullThreshold = 1.5f; }, "--rc-depth-cull"},
        {[](RenderCacheSettings& s) { s.requestTileSize = 0; }, "--rc-tile"},
        {[](RenderCacheSettings& s) { s.requestTileSize = 257; }, "--rc-tile"},
        {[](RenderCacheSettings& s) { s.reshadeInterval = 0; }, "--rc-reshade-every"},
        {[](RenderCacheSettings& s) { s.reshadeInterval = kMaxReshadeInterval + 1; }, "--rc-reshade-every"},
        {[](RenderCacheSettings& s) { s.refreshAllHoleShare = 1.5f; }, "refresh-all"},
    };
    for (const auto& c : cases) {
        const std::string message = errorOf(c.change);
        EXPECT_NE(message.find(c.option), std::string::npos) << c.option << ": '" << message << "'";
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    }
}

// The names the scene file and --rc-reflections take (and list, reshade first).
TEST(RenderCacheSettings, ReflectionModesByName) {
    ASSERT_EQ(kReprojectedReflections.size(), 2u);
    EXPECT_STREQ(reprojectedReflectionsName(kReprojectedReflections[0]), "reshade");
    EXPECT_STREQ(reprojectedReflectionsName(kReprojectedReflections[1]), "reproject");
    EXPECT_EQ(kReprojectedReflections[0], ReprojectedReflections::Reshade);
}
