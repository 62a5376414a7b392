#include "metrics/Ssim.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/ColorSpace.h"
#include "core/Errors.h"

namespace raycache {

namespace {

// One display-encoded channel as doubles, row-major.
std::vector<double> displayChannel(const Image& image, int channel) {
    std::vector<double> out(image.pixels().size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const Rgb& p = image.pixels()[i];
        const float linear = channel == 0 ? p.r : channel == 1 ? p.g : p.b;
        out[i] = displayedValue(linear);
    }
    return out;
}

// Normalized 1-D Gaussian taps; the 2-D window is their outer product.
std::vector<double> gaussianTaps(int size, double sigma) {
    std::vector<double> taps(static_cast<std::size_t>(size));
    const double c = 0.5 * (size - 1);
    double total = 0.0;
    for (int i = 0; i < size; ++i) {
        const double v = sigma > 0.0 ? std::exp(-(i - c) * (i - c) / (2.0 * sigma * sigma)) : 1.0;
        taps[static_cast<std::size_t>(i)] = v;
        total += v;
    }
    for (double& v : taps) v /= total;
    return taps;
}

// SSIM of the sizeX x sizeY window at (x0, y0), with weights summing to 1.
double windowSsim(const std::vector<double>& a, const std::vector<double>& b, int width, int x0, int y0, int sizeX,
                  int sizeY, const std::vector<double>& weights, const SsimSettings& s) {
    double mx = 0, my = 0;
    for (int y = 0; y < sizeY; ++y)
        for (int x = 0; x < sizeX; ++x) {
            const std::size_t i = static_cast<std::size_t>((y0 + y) * width + x0 + x);
            const double w = weights[static_cast<std::size_t>(y * sizeX + x)];
            mx += w * a[i];
            my += w * b[i];
        }
    double vx = 0, vy = 0, cxy = 0;
    for (int y = 0; y < sizeY; ++y)
        for (int x = 0; x < sizeX; ++x) {
            const std::size_t i = static_cast<std::size_t>((y0 + y) * width + x0 + x);
            const double w = weights[static_cast<std::size_t>(y * sizeX + x)];
            const double dx = a[i] - mx, dy = b[i] - my;
            vx += w * dx * dx;
            vy += w * dy * dy;
            cxy += w * dx * dy;
        }
    return ssimFromStatistics(mx, my, vx, vy, cxy, s);
}

}  // namespace

double ssimFromStatistics(double meanX, double meanY, double varianceX, double varianceY, double covariance,
                          const SsimSettings& s) {
    const double c1 = (s.k1 * 1.0) * (s.k1 * 1.0);
    const double c2 = (s.k2 * 1.0) * (s.k2 * 1.0);
    return ((2.0 * meanX * meanY + c1) * (2.0 * covariance + c2)) /
           ((meanX * meanX + meanY * meanY + c1) * (varianceX + varianceY + c2));
}

double ssim(const Image& a, const Image& b, const SsimSettings& settings) {
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError("images differ in size: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) +
                         " vs " + std::to_string(b.width()) + "x" + std::to_string(b.height()));
    if (a.empty()) throw InputError("cannot compute SSIM of empty images");
    if (settings.windowSize < 1 || settings.windowSize % 2 == 0)
        throw InputError("SSIM window size must be odd and positive");
    const int w = a.width(), h = a.height();

    double sum = 0.0;
    if (w < settings.windowSize || h < settings.windowSize) {
        // One uniform window over the whole image.
        const std::vector<double> weights(static_cast<std::size_t>(w) * static_cast<std::size_t>(h),
                                          1.0 / (static_cast<double>(w) * h));
        for (int channel = 0; channel < 3; ++channel)
            sum += windowSsim(displayChannel(a, channel), displayChannel(b, channel), w, 0, 0, w, h, weights, settings);
        return sum / 3.0;
    }

    // The Gaussian window is separable: filter the five moment images (x, y,
    // x^2, y^2, xy) along rows, then columns, keeping only positions where the
    // window fits ("valid"), as Wang et al.'s reference implementation does.
    const int n = settings.windowSize;
    const std::vector<double> taps = gaussianTaps(n, settings.sigma);
    const int ow = w - n + 1, oh = h - n + 1;
    const auto filter = [&](const std::vector<double>& image) {
        std::vector<double> rows(static_cast<std::size_t>(ow) * static_cast<std::size_t>(h));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < ow; ++x) {
                double s = 0.0;
                for (int k = 0; k < n; ++k)
                    s += taps[static_cast<std::size_t>(k)] * image[static_cast<std::size_t>(y * w + x + k)];
                rows[static_cast<std::size_t>(y * ow + x)] = s;
            }
        std::vector<double> out(static_cast<std::size_t>(ow) * static_cast<std::size_t>(oh));
        for (int y = 0; y < oh; ++y)
            for (int x = 0; x < ow; ++x) {
                double s = 0.0;
                for (int k = 0; k < n; ++k)
                    s += taps[static_cast<std::size_t>(k)] * rows[static_cast<std::size_t>((y + k) * ow + x)];
                out[static_cast<std::size_t>(y * ow + x)] = s;
            }
        return out;
    };
    for (int channel = 0; channel < 3; ++channel) {
        const std::vector<double> x = displayChannel(a, channel), y = displayChannel(b, channel);
        std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
        for (std::size_t i = 0; i < x.size(); ++i) {
            xx[i] = x[i] * x[i];
            yy[i] = y[i] * y[i];
            xy[i] = x[i] * y[i];
        }
        const std::vector<double> mx = filter(x), my = filter(y), mxx = filter(xx), myy = filter(yy), mxy = filter(xy);
        double channelSum = 0.0;
        for (std::size_t i = 0; i < mx.size(); ++i)
            channelSum += ssimFromStatistics(mx[i], my[i], mxx[i] - mx[i] * mx[i], myy[i] - my[i] * my[i],
                                             mxy[i] - mx[i] * my[i], settings);
        sum += channelSum / static_cast<double>(mx.size());
    }
    return sum / 3.0;
}

}  // namespace raycache
