#include "viewer/ProgressiveFilm.h"

#include "core/Errors.h"

namespace raycache {

ProgressiveFilm::ProgressiveFilm(int samplesPerPixel) : samples_(samplesPerPixel) {}

void ProgressiveFilm::restart(int width, int height) {
    film_ = FilteredFilm(width, height);
    width_ = width;
    height_ = height;
    added_ = 0;
}

void ProgressiveFilm::add(const Image& layer, Image& image, const Parallel& parallel) {
    if (complete() || layer.width() != width_ || layer.height() != height_)
        throw RuntimeError("ProgressiveFilm::add: a layer past the last or of another size");
    film_.addLayer(layer, samples_, added_, parallel);
    ++added_;
    film_.resolve(image, parallel);
}

}  // namespace raycache
