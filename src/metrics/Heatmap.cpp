#include "metrics/Heatmap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

#include "core/ColorSpace.h"
#include "core/Errors.h"
#include "core/TextFormat.h"

namespace raycache {

namespace {

Rgb toLinear(const Rgb& display) {
    return {srgbToLinear(display.r), srgbToLinear(display.g), srgbToLinear(display.b)};
}

// A 3x5 pixel font for the color bar's labels: digits, '.', and the letters
// of SAME and DIFFERENT. Each row is 3 bits, most significant on the left.
std::array<std::uint8_t, 5> glyph(char c) {
    switch (c) {
        case '0':
            return {7, 5, 5, 5, 7};
        case '1':
            return {2, 6, 2, 2, 7};
        case '2':
            return {7, 1, 7, 4, 7};
        case '3':
            return {7, 1, 7, 1, 7};
        case '4':
            return {5, 5, 7, 1, 1};
        case '5':
            return {7, 4, 7, 1, 7};
        case '6':
            return {7, 4, 7, 5, 7};
        case '7':
            return {7, 1, 1, 1, 1};
        case '8':
            return {7, 5, 7, 5, 7};
        case '9':
            return {7, 5, 7, 1, 7};
        case '.':
            return {0, 0, 0, 0, 2};
        case 'A':
            return {2, 5, 7, 5, 5};
        case 'D':
            return {6, 5, 5, 5, 6};
        case 'E':
            return {7, 4, 6, 4, 7};
        case 'F':
            return {7, 4, 6, 4, 4};
        case 'I':
            return {7, 2, 2, 2, 7};
        case 'M':
            return {5, 7, 7, 5, 5};
        case 'N':
            return {5, 7, 7, 7, 5};
        case 'R':
            return {6, 5, 6, 5, 5};
        case 'S':
            return {7, 4, 7, 1, 7};
        case 'T':
            return {7, 2, 2, 2, 2};
        default:
            return {0, 0, 0, 0, 0};
    }
}

void drawText(Image& image, int x, int y, int scale, std::string_view text, const Rgb& color) {
    for (char c : text) {
        const auto rows = glyph(c);
        for (int gy = 0; gy < 5; ++gy)
            for (int gx = 0; gx < 3; ++gx) {
                if (!(rows[static_cast<std::size_t>(gy)] & (4 >> gx))) continue;
                for (int sy = 0; sy < scale; ++sy)
                    for (int sx = 0; sx < scale; ++sx) {
                        const int px = x + gx * scale + sx, py = y + gy * scale + sy;
                        if (px >= 0 && py >= 0 && px < image.width() && py < image.height()) image.at(px, py) = color;
                    }
            }
        x += 4 * scale;
    }
}

int textWidth(std::string_view text, int scale) {
    return static_cast<int>(text.size()) * 4 * scale - scale;
}

std::string formatLabel(double v) {
    std::string s = formatFixed(v, 3);
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    return s;
}

}  // namespace

std::vector<float> pixelDifferences(const Image& a, const Image& b) {
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError("images differ in size: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) +
                         " vs " + std::to_string(b.width()) + "x" + std::to_string(b.height()));
    std::vector<float> d(a.pixels().size());
    for (std::size_t i = 0; i < d.size(); ++i) {
        const Rgb& p = a.pixels()[i];
        const Rgb& q = b.pixels()[i];
        d[i] = (std::fabs(displayedValue(p.r) - displayedValue(q.r)) + std::fabs(displayedValue(p.g) - displayedValue(q.g)) +
                std::fabs(displayedValue(p.b) - displayedValue(q.b))) /
               3.0f;
    }
    return d;
}

Rgb heatColorDisplay(double t) {
    // Blue, cyan, green, yellow, red at 0, 1/4, 1/2, 3/4, 1, linear in between.
    static constexpr std::array<std::array<float, 3>, 5> stops{{{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}};
    const double u = std::clamp(std::isfinite(t) ? t : 1.0, 0.0, 1.0) * 4.0;
    const int i = std::min(3, static_cast<int>(u));
    const float f = static_cast<float>(u - i);
    const auto& lo = stops[static_cast<std::size_t>(i)];
    const auto& hi = stops[static_cast<std::size_t>(i + 1)];
    return {lo[0] + f * (hi[0] - lo[0]), lo[1] + f * (hi[1] - lo[1]), lo[2] + f * (hi[2] - lo[2])};
}

Image renderHeatmap(const Image& a, const Image& b, const HeatmapSettings& settings) {
    if (!(settings.maxDifference > 0.0) || !std::isfinite(settings.maxDifference))
        throw InputError("heat map scale must be a finite number > 0");
    const std::vector<float> diff = pixelDifferences(a, b);
    if (a.empty()) throw InputError("cannot draw the heat map of empty images");
    const int w = a.width(), h = a.height();

    // Layout: picture | gap | bar | gap | labels. The labels scale with the picture.
    const int scale = std::max(1, h / 150);
    const int pad = 4 * scale;
    const int barWidth = 6 * scale;
    const std::string top = formatLabel(settings.maxDifference), mid = formatLabel(settings.maxDifference / 2.0);
    const int labelWidth = std::max(textWidth("DIFFERENT", scale), textWidth(top, scale));
    const int lineHeight = 7 * scale;
    const int minBarHeight = 6 * lineHeight;
    const int height = std::max(h, minBarHeight + 2 * pad);
    const int width = w + pad + barWidth + pad + labelWidth + pad;

    const Rgb background = toLinear({1.0f, 1.0f, 1.0f}), ink = toLinear({0.0f, 0.0f, 0.0f});
    Image out(width, height);
    std::fill(out.pixels().begin(), out.pixels().end(), background);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            out.at(x, y) = toLinear(heatColorDisplay(static_cast<double>(diff[static_cast<std::size_t>(y * w + x)]) /
                                                     settings.maxDifference));

    const int barX = w + pad, barTop = pad, barBottom = height - pad;  // bar spans [barTop, barBottom)
    const int barHeight = barBottom - barTop;
    for (int y = barTop; y < barBottom; ++y) {
        const double t = barHeight > 1 ? 1.0 - static_cast<double>(y - barTop) / (barHeight - 1) : 1.0;
        const Rgb c = toLinear(heatColorDisplay(t));
        for (int x = barX; x < barX + barWidth; ++x) out.at(x, y) = c;
    }
    const int labelX = barX + barWidth + pad;
    drawText(out, labelX, barTop, scale, top, ink);
    drawText(out, labelX, barTop + lineHeight, scale, "DIFFERENT", ink);
    drawText(out, labelX, barTop + barHeight / 2 - 2 * scale, scale, mid, ink);
    drawText(out, labelX, barBottom - 5 * scale - lineHeight, scale, "SAME", ink);
    drawText(out, labelX, barBottom - 5 * scale, scale, "0", ink);
    return out;
}

}  // namespace raycache
