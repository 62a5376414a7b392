// The documents' figures are transcribed by hand: their printed speed-ups
// must agree with their frame rates, which catches a mistyped number.
#include <gtest/gtest.h>

#include "bench/PaperFigures.h"

using namespace raycache;

TEST(PaperFigures, PrintedSpeedupsMatchFrameRates) {
    for (const PaperTable& t : {paperTable51(), paperTable52()}) {
        ASSERT_FALSE(t.rows.empty()) << t.source;
        for (const PaperRow& r : t.rows) {
            const double standard = t.value(r.label, "standard").value();
            const double cct = t.value(r.label, "cct").value();
            EXPECT_NEAR(cct / standard, t.value(r.label, "speedup").value(), 0.011) << t.source << " N=" << r.label;
        }
    }
}

TEST(PaperFigures, LookupByRowAndColumn) {
    const PaperTable t = paperTable53();
    EXPECT_DOUBLE_EQ(t.value("Reflective", "cdct-0.02/0.002").value(), 9.5);
    EXPECT_DOUBLE_EQ(t.value("Diffuse", "standard").value(), 69.6);
    EXPECT_FALSE(t.value("Diffuse", "cdct-improved").has_value());
    EXPECT_FALSE(t.value("Nothing", "cct").has_value());
    EXPECT_DOUBLE_EQ(paperFigure59().value("512", "invalid-after-frame-1").value(), 73.0);
}

TEST(PaperFigures, RenderCacheFrameRatesAndTimesAgree) {
    const PaperTable t = paperRenderCache();
    EXPECT_DOUBLE_EQ(t.value("512", "fps").value(), 123.0);
    EXPECT_DOUBLE_EQ(t.value("1024", "fps").value(), 38.0);
    EXPECT_NEAR(t.value("512", "ms").value(), 8.1, 0.05);
    EXPECT_NEAR(t.value("1024", "ms").value(), 26.3, 0.05);
}
