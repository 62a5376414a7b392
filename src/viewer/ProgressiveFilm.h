#pragma once
// The viewer's anti-aliasing of a still view (`view --spp N`): while the
// camera and everything else that shapes the image stay as they are, each
// frame adds one more jittered sample layer (render/PixelSamples.h) to a
// filtered film (render/FilteredFilm.h) and shows what the layers so far
// give. After N frames the image is `raycache render --spp N`'s, bit for
// bit: the same layers, gathered in the same order. A frame that shows
// something else starts it again.
#include "core/Image.h"
#include "core/Parallel.h"
#include "render/FilteredFilm.h"
#include "render/PixelSamples.h"

namespace raycache {

class ProgressiveFilm {
public:
    // `samplesPerPixel` >= 1: the layers a still view is refined to.
    explicit ProgressiveFilm(int samplesPerPixel);

    // Drops the layers so far; the next one added is layer 0 of a
    // width x height image.
    void restart(int width, int height);
    // The layer to render next (samples().offset(x, y, nextSample())), while
    // not complete().
    int nextSample() const { return added_; }
    const PixelSamples& samples() const { return samples_; }
    int target() const { return samples_.count(); }
    bool complete() const { return added_ >= samples_.count(); }
    bool empty() const { return added_ == 0; }

    // Adds layer nextSample() (rendered at the size restart() gave) and
    // writes the filtered image of every layer so far into `image`.
    void add(const Image& layer, Image& image, const Parallel& parallel);

private:
    PixelSamples samples_;
    FilteredFilm film_{1, 1};
    int width_ = 0, height_ = 0;
    int added_ = 0;
};

}  // namespace raycache
