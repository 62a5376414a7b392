#pragma once
// A width x height grid of linear float RGB pixels, row-major, row 0 at the top.
#include <cstddef>
#include <utility>
#include <vector>

#include "core/Rgb.h"

namespace raycache {

class Image {
public:
    Image() = default;
    Image(int width, int height) : width_(width), height_(height),
        pixels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {}
    // Takes over `pixels`, which must hold width * height of them, row-major
    // (a decoder that grows its pixels as it reads need not copy them).
    Image(int width, int height, std::vector<Rgb> pixels)
        : width_(width), height_(height), pixels_(std::move(pixels)) {}

    int width() const { return width_; }
    int height() const { return height_; }
    bool empty() const { return pixels_.empty(); }

    Rgb& at(int x, int y) { return pixels_[index(x, y)]; }
    const Rgb& at(int x, int y) const { return pixels_[index(x, y)]; }
    const std::vector<Rgb>& pixels() const { return pixels_; }
    std::vector<Rgb>& pixels() { return pixels_; }

private:
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
    }
    int width_ = 0;
    int height_ = 0;
    std::vector<Rgb> pixels_;
};

}  // namespace raycache
