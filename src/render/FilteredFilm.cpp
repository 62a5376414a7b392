#include "render/FilteredFilm.h"

#include <algorithm>
#include <cmath>

#include "render/PixelFilter.h"

namespace raycache {

FilteredFilm::FilteredFilm(int width, int height)
    : width_(width), height_(height),
      sums_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)),
      weights_(sums_.size(), 0.0f) {}

void FilteredFilm::addLayer(const Image& layer, const PixelSamples& samples, int sample, const Parallel& parallel) {
    static_assert(kReach + 1 >= PixelFilter::kRadius + 0.5f, "every sample within the filter's reach is gathered");
    const auto at = [&](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
    };
    // Each sample's weights along each axis, once (kSpan each), rather than
    // once per output pixel that gathers it.
    weightsX_.resize(sums_.size() * kSpan);
    weightsY_.resize(sums_.size() * kSpan);
    parallel.forEachIndex(height_, [&](int y, int) {
        for (int x = 0; x < width_; ++x) {
            const PixelOffset o = samples.offset(x, y, sample);
            float* wx = &weightsX_[at(x, y) * kSpan];
            float* wy = &weightsY_[at(x, y) * kSpan];
            // Output pixel n + k - kReach has its centre at n + k - kReach + 0.5.
            for (int k = 0; k < kSpan; ++k) {
                const float fromCentre = o.x - static_cast<float>(k - kReach) - 0.5f;
                wx[k] = PixelFilter::weight1d(fromCentre);
                wy[k] = PixelFilter::weight1d(o.y - static_cast<float>(k - kReach) - 0.5f);
            }
        }
    });
    parallel.forEachIndex(height_, [&](int y, int) {
        for (int x = 0; x < width_; ++x) {
            Rgb sum = sums_[at(x, y)];
            float weight = weights_[at(x, y)];
            for (int ny = std::max(0, y - kReach); ny <= std::min(height_ - 1, y + kReach); ++ny) {
                const int ky = y - ny + kReach;
                for (int nx = std::max(0, x - kReach); nx <= std::min(width_ - 1, x + kReach); ++nx) {
                    const std::size_t n = at(nx, ny);
                    const float w = weightsX_[n * kSpan + static_cast<std::size_t>(x - nx + kReach)] *
                                    weightsY_[n * kSpan + static_cast<std::size_t>(ky)];
                    if (w <= 0.0f) continue;
                    sum += layer.at(nx, ny) * w;
                    weight += w;
                }
            }
            sums_[at(x, y)] = sum;
            weights_[at(x, y)] = weight;
        }
    });
}

void FilteredFilm::resolve(Image& film, const Parallel& parallel) const {
    if (film.width() != width_ || film.height() != height_) film = Image(width_, height_);
    parallel.forEachIndex(height_, [&](int y, int) {
        for (int x = 0; x < width_; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                                  static_cast<std::size_t>(x);
            film.at(x, y) = sums_[i] * (1.0f / weights_[i]);
        }
    });
}

}  // namespace raycache
