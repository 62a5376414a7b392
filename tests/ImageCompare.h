#pragma once
// Whether two images are the same bit for bit: the check behind every test
// that two ways of rendering (thread counts, pipelines, lane levels, caches
// on and off) give the very same picture.
#include <cstring>

#include "core/Image.h"

namespace raycache {

inline bool identicalImages(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Rgb)) == 0;
}

}  // namespace raycache
