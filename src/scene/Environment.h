#pragma once
// What a ray that hits nothing sees.
#include <array>
#include <memory>

#include "core/Image.h"
#include "core/Rgb.h"
#include "core/Vec3.h"

namespace raycache {

class Environment {
public:
    Environment() = default;  // black
    static Environment constant(const Rgb& color);
    // Latitude-longitude image; +y is up, the image centre looks along -z.
    static Environment equirectangular(std::shared_ptr<const Image> image);
    // Six square images in OpenGL cubemap order: +x, -x, +y, -y, +z, -z.
    static Environment cubeFaces(std::array<std::shared_ptr<const Image>, 6> faces);

    Rgb lookup(const Vec3& direction) const;

private:
    enum class Kind { Constant, Equirectangular, CubeFaces };
    Kind kind_ = Kind::Constant;
    Rgb color_{0.0f};
    std::array<std::shared_ptr<const Image>, 6> images_;  // [0] for equirectangular
};

}  // namespace raycache
