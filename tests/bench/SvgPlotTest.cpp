#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

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

namespace {

// The SVG y coordinate of the y-axis tick labelled `label`, read from the
// document (right-aligned labels left of the axis); NaN if there is none.
double yTickPosition(const std::string& svg, const std::string& label) {
    const std::string tail = "\" text-anchor=\"end\" dominant-baseline=\"middle\">" + label + "</text>";
    const std::size_t end = svg.find(tail);
    if (end == std::string::npos) return std::nan("");
    const std::size_t start = svg.rfind("y=\"", end) + 3;
    return std::stod(svg.substr(start, end - start));
}
// The x coordinate of the x-axis tick labelled `label` (numeric axis).
double xTickPosition(const std::string& svg, const std::string& label) {
    const std::string tail = "\" text-anchor=\"middle\">" + label + "</text>";
    for (std::size_t end = svg.find(tail); end != std::string::npos; end = svg.find(tail, end + 1)) {
        const std::size_t xStart = svg.rfind("<text x=\"", end) + 9;
        const std::size_t xEnd = svg.find('"', xStart);
        return std::stod(svg.substr(xStart, xEnd - xStart));
    }
    return std::nan("");
}
// cx and cy of the marker whose tooltip ends with ": <value>".
bool markerAt(const std::string& svg, const std::string& value, double& cx, double& cy) {
    const std::size_t title = svg.find(": " + value + "</title></circle>");
    if (title == std::string::npos) return false;
    const std::size_t circle = svg.rfind("<circle cx=\"", title);
    cx = std::stod(svg.substr(circle + 12));
    cy = std::stod(svg.substr(svg.find("cy=\"", circle) + 4));
    return true;
}

}  // namespace

// A point lands where the axes' own tick labels say its value is: y = 7.5 on
// a 0..10 axis three quarters of the way from the "0" tick to the "10" tick,
// x = 3 halfway between the "2" and "4" ticks; whisker ends likewise.
TEST(SvgPlot, PointsLandWhereTheAxesPutTheirValues) {
    SvgPlot plot;
    plot.yMin = 0.0;
    plot.yMax = 10.0;
    plot.series.push_back({"s", {{0, 1.0}, {3, 7.5, 5.0, 9.0}, {6, 2.0}}});
    const std::string svg = plot.toSvg();
    const double y0 = yTickPosition(svg, "0"), y10 = yTickPosition(svg, "10");
    const double x2 = xTickPosition(svg, "2"), x4 = xTickPosition(svg, "4");
    ASSERT_FALSE(std::isnan(y0) || std::isnan(y10) || std::isnan(x2) || std::isnan(x4)) << svg;
    ASSERT_GT(y0 - y10, 100.0) << "the axis spans the plot";
    double cx = 0, cy = 0;
    ASSERT_TRUE(markerAt(svg, "7.50", cx, cy)) << svg;
    EXPECT_NEAR(cy, y0 + 0.75 * (y10 - y0), 0.02);
    EXPECT_NEAR(cx, 0.5 * (x2 + x4), 0.02);
    // The whisker from 5 to 9: the line element just before that marker.
    const std::size_t line = svg.rfind("<line x1=\"", svg.find(": 7.50</title>"));
    ASSERT_NE(line, std::string::npos);
    const auto attribute = [&](const char* name) {
        return std::stod(svg.substr(svg.find(std::string(name) + "=\"", line) + std::strlen(name) + 2));
    };
    EXPECT_NEAR(attribute("x1"), cx, 0.02);
    EXPECT_NEAR(attribute("y1"), y0 + 0.5 * (y10 - y0), 0.02);
    EXPECT_NEAR(attribute("y2"), y0 + 0.9 * (y10 - y0), 0.02);
}
