#include <gtest/gtest.h>

#include <cmath>

#include "XmlCheck.h"
#include "bench/SvgPlot.h"
#include "core/Errors.h"

using namespace raycache;
using raycache::test::countOccurrences;
using raycache::test::xmlProblem;

TEST(SvgPlot, LinePlotIsWellFormedWithEverySeries) {
    SvgPlot plot;
    plot.title = "speed-up <vs> N & more";
    plot.xLabel = "N";
    plot.yLabel = "speed-up";
    plot.categories = {"0", "1", "2", "4"};
    plot.referenceY = 1.0;
    plot.series.push_back({"ours", {{0, 1.1}, {1, 1.2}, {2, 1.3, 1.0, 1.5}, {3, 1.4}}});
    PlotSeries docs{"documents", {{0, 1.8}, {1, std::nan("")}, {2, 2.0}, {3, 2.2}}};
    docs.dashed = true;
    plot.series.push_back(docs);
    const std::string svg = plot.toSvg();
    EXPECT_EQ(xmlProblem(svg), "") << svg;
    EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
    EXPECT_NE(svg.find("speed-up &lt;vs&gt; N &amp; more"), std::string::npos);
    EXPECT_EQ(countOccurrences(svg, "data-name=\"ours\""), 1);
    EXPECT_EQ(countOccurrences(svg, "data-name=\"documents\""), 1);
    // One marker per finite point: 4 + 3 (the NaN is skipped).
    EXPECT_EQ(countOccurrences(svg, "<circle"), 7);
    EXPECT_EQ(countOccurrences(svg, "stroke-dasharray=\"6 4\""), 2);  // the dashed line and its legend
    EXPECT_EQ(countOccurrences(svg, "<path"), 2);
    // The whisker of the third point.
    EXPECT_GE(countOccurrences(svg, "<line"), 1);
    for (const char* label : {">0<", ">1<", ">2<", ">4<"}) EXPECT_NE(svg.find(label), std::string::npos) << label;
}

TEST(SvgPlot, NumericAxisAndBars) {
    SvgPlot lines;
    lines.series.push_back({"invalid", {{0, 100}, {1, 31}, {2, 10}, {10, 0.5}}});
    EXPECT_EQ(xmlProblem(lines.toSvg()), "");

    SvgPlot bars;
    bars.width = 500;  // narrow: the labels do not fit side by side
    bars.bars = true;
    bars.categories = {"uncached", "CCT", "CDCT parity 0.02/0.002"};
    bars.series.push_back({"Diffuse", {{0, 1.0}, {1, 1.1}, {2, 0.3}}});
    bars.series.push_back({"Reflective", {{0, 1.0}, {1, 2.2}, {2, std::nan("")}}});
    const std::string svg = bars.toSvg();
    EXPECT_EQ(xmlProblem(svg), "") << svg;
    // 5 finite bars plus 2 legend swatches and the background.
    EXPECT_EQ(countOccurrences(svg, "<rect"), 5 + 2 + 1);
    EXPECT_NE(svg.find("rotate(-30"), std::string::npos);  // long category labels are slanted

    SvgPlot broken;
    broken.bars = true;
    EXPECT_THROW(broken.toSvg(), InputError);
}

TEST(SvgPlot, EmptyPlotIsStillWellFormed) {
    EXPECT_EQ(xmlProblem(SvgPlot{}.toSvg()), "");
}
