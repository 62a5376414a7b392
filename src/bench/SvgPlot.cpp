#include "bench/SvgPlot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "core/TextFormat.h"

namespace raycache {

namespace {

constexpr std::array<const char*, 8> kColors{"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                             "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"};

std::string escapeXml(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string num(double v) {
    return formatFixed(v, 2);
}

// A 1, 2 or 5 times a power of ten close to range / 5.
double niceStep(double range) {
    if (!(range > 0.0)) return 1.0;
    const double raw = range / 5.0;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    const double f = raw / power;
    return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * power;
}

std::string tickLabel(double v, double step) {
    const int decimals = step >= 1.0 ? 0 : std::min(6, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
    return formatFixed(std::fabs(v) < step * 1e-6 ? 0.0 : v, decimals);
}

}  // namespace

std::string SvgPlot::toSvg() const {
    if (bars && categories.empty()) throw InputError("a bar chart needs categories");
    // Long category labels are drawn slanted, which needs room below the axis.
    std::size_t longestCategory = 0;
    for (const std::string& c : categories) longestCategory = std::max(longestCategory, c.size());
    const bool slanted = !categories.empty() && 7.0 * static_cast<double>(longestCategory) >
                                                    (width - 72.0 - 250.0) / static_cast<double>(categories.size());
    const double left = 72, right = 250, top = 40;
    const double bottom = slanted ? 56 + 5.0 * static_cast<double>(std::min<std::size_t>(longestCategory, 24)) : 56;
    const double plotW = width - left - right, plotH = height - top - bottom;

    // Data ranges.
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, xlo = lo, xhi = -lo;
    for (const PlotSeries& s : series)
        for (const PlotPoint& p : s.points) {
            if (!std::isfinite(p.y)) continue;
            lo = std::min({lo, p.y, p.low.value_or(p.y)});
            hi = std::max({hi, p.y, p.high.value_or(p.y)});
            xlo = std::min(xlo, p.x);
            xhi = std::max(xhi, p.x);
        }
    if (referenceY) {
        lo = std::min(lo, *referenceY);
        hi = std::max(hi, *referenceY);
    }
    if (!std::isfinite(lo)) lo = 0.0, hi = 1.0, xlo = 0.0, xhi = 1.0;
    double y0 = yMin.value_or(std::min(0.0, lo));
    double y1 = yMax.value_or(hi + 0.08 * (hi - y0));
    if (!(y1 > y0)) y1 = y0 + 1.0;
    const double yStep = niceStep(y1 - y0);
    if (!yMax) y1 = std::ceil(y1 / yStep - 1e-9) * yStep;
    if (!yMin) y0 = std::floor(y0 / yStep + 1e-9) * yStep;

    const bool categorical = !categories.empty();
    double x0 = xlo, x1 = xhi;
    if (categorical) x0 = -0.5, x1 = static_cast<double>(categories.size()) - 0.5;
    if (!(x1 > x0)) x0 -= 0.5, x1 += 0.5;
    const auto sx = [&](double x) { return left + (x - x0) / (x1 - x0) * plotW; };
    const auto sy = [&](double y) { return top + (1.0 - (std::clamp(y, y0, y1) - y0) / (y1 - y0)) * plotH; };

    std::ostringstream o;
    o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height << "\" fill=\"white\"/>\n"
      << "<text x=\"" << num(width / 2.0) << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << escapeXml(title)
      << "</text>\n";

    // Grid and y ticks.
    for (double v = y0; v <= y1 + yStep * 1e-6; v += yStep) {
        const std::string y = num(sy(v));
        o << "<line x1=\"" << num(left) << "\" y1=\"" << y << "\" x2=\"" << num(left + plotW) << "\" y2=\"" << y
          << "\" stroke=\"#e0e0e0\"/>\n"
          << "<text x=\"" << num(left - 6) << "\" y=\"" << y << "\" text-anchor=\"end\" dominant-baseline=\"middle\">"
          << tickLabel(v, yStep) << "</text>\n";
    }
    // X ticks.
    if (categorical) {
        for (std::size_t i = 0; i < categories.size(); ++i) {
            const std::string x = num(sx(static_cast<double>(i))), y = num(top + plotH + 18);
            if (slanted)
                o << "<text x=\"" << x << "\" y=\"" << y << "\" text-anchor=\"end\" transform=\"rotate(-30 " << x << " "
                  << y << ")\">" << escapeXml(categories[i]) << "</text>\n";
            else
                o << "<text x=\"" << x << "\" y=\"" << y << "\" text-anchor=\"middle\">" << escapeXml(categories[i])
                  << "</text>\n";
        }
    } else {
        const double xStep = niceStep(x1 - x0);
        for (double v = std::ceil(x0 / xStep - 1e-9) * xStep; v <= x1 + xStep * 1e-6; v += xStep)
            o << "<line x1=\"" << num(sx(v)) << "\" y1=\"" << num(top + plotH) << "\" x2=\"" << num(sx(v)) << "\" y2=\""
              << num(top + plotH + 5) << "\" stroke=\"black\"/>\n"
              << "<text x=\"" << num(sx(v)) << "\" y=\"" << num(top + plotH + 18) << "\" text-anchor=\"middle\">"
              << tickLabel(v, xStep) << "</text>\n";
    }
    // Axes and labels.
    o << "<line x1=\"" << num(left) << "\" y1=\"" << num(top) << "\" x2=\"" << num(left) << "\" y2=\""
      << num(top + plotH) << "\" stroke=\"black\"/>\n"
      << "<line x1=\"" << num(left) << "\" y1=\"" << num(top + plotH) << "\" x2=\"" << num(left + plotW) << "\" y2=\""
      << num(top + plotH) << "\" stroke=\"black\"/>\n"
      << "<text x=\"" << num(left + plotW / 2) << "\" y=\"" << num(height - 14.0) << "\" text-anchor=\"middle\">"
      << escapeXml(xLabel) << "</text>\n"
      << "<text x=\"18\" y=\"" << num(top + plotH / 2) << "\" text-anchor=\"middle\" transform=\"rotate(-90 18 "
      << num(top + plotH / 2) << ")\">" << escapeXml(yLabel) << "</text>\n";
    if (referenceY)
        o << "<line x1=\"" << num(left) << "\" y1=\"" << num(sy(*referenceY)) << "\" x2=\"" << num(left + plotW)
          << "\" y2=\"" << num(sy(*referenceY)) << "\" stroke=\"#555\" stroke-dasharray=\"2 3\"/>\n";

    // Series.
    const double groupWidth = categorical ? 0.8 * plotW / static_cast<double>(categories.size()) : 0.0;
    const double barWidth = series.empty() ? 0.0 : groupWidth / static_cast<double>(series.size());
    for (std::size_t si = 0; si < series.size(); ++si) {
        const PlotSeries& s = series[si];
        const std::string color = kColors[si % kColors.size()];
        o << "<g class=\"series\" data-name=\"" << escapeXml(s.name) << "\">\n";
        if (bars) {
            for (const PlotPoint& p : s.points) {
                if (!std::isfinite(p.y)) continue;
                const double bx = sx(p.x) - groupWidth / 2 + barWidth * static_cast<double>(si);
                const double top0 = std::min(sy(p.y), sy(0.0)), h = std::fabs(sy(p.y) - sy(0.0));
                o << "<rect x=\"" << num(bx) << "\" y=\"" << num(top0) << "\" width=\"" << num(barWidth * 0.92)
                  << "\" height=\"" << num(h) << "\" fill=\"" << color << "\""
                  << (s.dashed ? " fill-opacity=\"0.45\" stroke=\"" + color + "\" stroke-dasharray=\"3 2\"" : "")
                  << "><title>" << escapeXml(s.name) << ": " << num(p.y) << "</title></rect>\n";
                if (p.low && p.high) {
                    // The range (e.g. a confidence interval) as a whisker over the bar's middle.
                    const double cx = bx + barWidth * 0.46;
                    o << "<line class=\"whisker\" x1=\"" << num(cx) << "\" y1=\"" << num(sy(*p.low)) << "\" x2=\""
                      << num(cx) << "\" y2=\"" << num(sy(*p.high)) << "\" stroke=\"#222\"/>\n";
                }
            }
        } else {
            std::string path;
            for (const PlotPoint& p : s.points) {
                if (!std::isfinite(p.y)) continue;
                path += (path.empty() ? "M" : " L") + num(sx(p.x)) + " " + num(sy(p.y));
            }
            if (s.line && !path.empty())
                o << "<path d=\"" << path << "\" fill=\"none\" stroke=\"" << color << "\" stroke-width=\"2\""
                  << (s.dashed ? " stroke-dasharray=\"6 4\"" : "") << "/>\n";
            for (const PlotPoint& p : s.points) {
                if (!std::isfinite(p.y)) continue;
                if (p.low && p.high)
                    o << "<line x1=\"" << num(sx(p.x)) << "\" y1=\"" << num(sy(*p.low)) << "\" x2=\"" << num(sx(p.x))
                      << "\" y2=\"" << num(sy(*p.high)) << "\" stroke=\"" << color << "\"/>\n";
                if (s.markers)
                    o << "<circle cx=\"" << num(sx(p.x)) << "\" cy=\"" << num(sy(p.y)) << "\" r=\"3.5\" fill=\""
                      << (s.dashed ? "white" : color) << "\" stroke=\"" << color << "\"><title>" << escapeXml(s.name)
                      << ": " << num(p.y) << "</title></circle>\n";
            }
        }
        // Legend entry.
        const double ly = top + 10 + 20.0 * static_cast<double>(si), lx = left + plotW + 16;
        if (bars)
            o << "<rect x=\"" << num(lx) << "\" y=\"" << num(ly - 6) << "\" width=\"22\" height=\"12\" fill=\"" << color
              << "\"" << (s.dashed ? " fill-opacity=\"0.45\"" : "") << "/>\n";
        else
            o << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly) << "\" x2=\"" << num(lx + 22) << "\" y2=\""
              << num(ly) << "\" stroke=\"" << color << "\" stroke-width=\"2\""
              << (s.dashed ? " stroke-dasharray=\"6 4\"" : "") << "/>\n";
        o << "<text x=\"" << num(lx + 28) << "\" y=\"" << num(ly) << "\" dominant-baseline=\"middle\">"
          << escapeXml(s.name) << "</text>\n";
        o << "</g>\n";
    }
    o << "</svg>\n";
    return o.str();
}

void writeSvgPlot(const SvgPlot& plot, const std::string& path) {
    writeTextFileAtomically(path, plot.toSvg());
}

}  // namespace raycache
