#pragma once
// Diffuse color source: an image (repeating, bilinear) or a procedural checkerboard.
#include <memory>

#include "core/Image.h"
#include "core/Rgb.h"

namespace raycache {

struct Checkerboard {
    Rgb even{0.9f};
    Rgb odd{0.1f};
    float squaresPerUnit = 1.0f;  // squares per texture-coordinate unit
};

class Texture {
public:
    static Texture checkerboard(const Checkerboard& pattern);
    static Texture image(std::shared_ptr<const Image> pixels);

    // (u, v) in texture space; repeats outside [0,1). v = 0 is the image's bottom row.
    Rgb sample(float u, float v) const;

    // What the texture is made of, for renderers that sample it themselves
    // (the OpenGL G-buffer): the image, or null for a checkerboard ...
    const std::shared_ptr<const Image>& pixels() const { return image_; }
    // ... and the checkerboard, or null for an image.
    const Checkerboard* checkerboardPattern() const { return image_ ? nullptr : &checker_; }

private:
    Checkerboard checker_;
    std::shared_ptr<const Image> image_;  // null for the checkerboard
};

}  // namespace raycache
