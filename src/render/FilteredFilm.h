#pragma once
// A film made of several samples per pixel (`--spp N`): sample layer s holds
// every pixel's s-th jittered ray (render/PixelSamples.h) as the ray pipeline
// renders a frame; each layer is gathered into running sums, every output
// pixel adding the samples of its neighbours within the filter's reach
// (render/PixelFilter.h), weighted, in a fixed order. Rows are gathered in
// parallel, each by one thread, so the image does not depend on the thread
// count. Memory: two images and a weight per pixel, whatever N.
#include <vector>

#include "core/Image.h"
#include "core/Parallel.h"
#include "render/PixelSamples.h"

namespace raycache {

class FilteredFilm {
public:
    // Empty sums for a width x height image.
    FilteredFilm(int width, int height);

    // Adds sample layer `sample` of `samples`: layer.at(x, y) is the colour
    // of pixel (x, y)'s ray through samples.offset(x, y, sample).
    void addLayer(const Image& layer, const PixelSamples& samples, int sample, const Parallel& parallel);

    // The filtered image: each pixel's weighted sum over its weights (every
    // pixel's own sample has a weight > 0, so no pixel is left undefined).
    void resolve(Image& film, const Parallel& parallel) const;

private:
    // Per pixel n of the layer being added, its sample's weight along x in
    // the output pixels n - kReach .. n + kReach, and along y likewise. A
    // sample of pixel n lies in [n, n + 1]; it reaches an output centre
    // x + 0.5 closer than the filter's radius only when |n - x| < radius + 0.5.
    static constexpr int kReach = 1;
    static constexpr int kSpan = 2 * kReach + 1;

    int width_, height_;
    std::vector<Rgb> sums_;
    std::vector<float> weights_;
    std::vector<float> weightsX_, weightsY_;  // kSpan per pixel
};

}  // namespace raycache
