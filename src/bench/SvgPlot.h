#pragma once
// Small line and bar charts written as standalone SVG: axes with ticks,
// axis labels, a title and a legend. Enough for the experiments' plots
// (speed-up vs N, invalid texels vs frame, PSNR vs resolution, error vs frame).
#include <optional>
#include <string>
#include <vector>

namespace raycache {

struct PlotPoint {
    double x = 0.0;  // with categories: the category's index
    double y = 0.0;
    // Optional range drawn as a whisker (e.g. min-max of the timed frames).
    std::optional<double> low;
    std::optional<double> high;
};

struct PlotSeries {
    std::string name;
    std::vector<PlotPoint> points;  // non-finite y values are skipped
    bool line = true;               // join the points (line charts)
    bool markers = true;            // a dot at every point
    bool dashed = false;            // e.g. the documents' figures beside ours
};

struct SvgPlot {
    std::string title;
    std::string xLabel;
    std::string yLabel;
    // When not empty the x axis is categorical: one tick per label, points'
    // x are indices into it. Otherwise x is numeric with automatic ticks.
    std::vector<std::string> categories;
    // Grouped bars over the categories instead of lines (needs categories).
    bool bars = false;
    std::optional<double> yMin;        // default: 0, or below the lowest value if negative
    std::optional<double> yMax;        // default: a little above the highest value
    std::optional<double> referenceY;  // a dashed horizontal line, e.g. speed-up 1
    std::vector<PlotSeries> series;
    int width = 860;
    int height = 420;

    // The whole SVG document. Throws InputError if a bar chart has no categories.
    std::string toSvg() const;
};

// Writes plot.toSvg() to `path` atomically.
void writeSvgPlot(const SvgPlot& plot, const std::string& path);

}  // namespace raycache
