#include "scene/ImageFileChecks.h"

#include <string>

#include "core/Errors.h"
#include "scene/ImageLoader.h"

namespace raycache {

void checkImageSize(const std::filesystem::path& path, long long width, long long height) {
    const InputLocation where{.file = path.string()};
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (width <= 0 || height <= 0) throw InputError(where, "image has zero size (" + size + ")");
    if (width > maxImageSide || height > maxImageSide)
        throw InputError(
            where, "image is " + size + ", larger than the limit of " + std::to_string(maxImageSide) + " per side");
}

void checkImageFinite(const std::filesystem::path& path, const Image& image) {
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (!image.at(x, y).isFinite())
                throw InputError(InputLocation{.file = path.string()},
                                 "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is not a finite number");
}

}  // namespace raycache
