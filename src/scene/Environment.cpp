#include "scene/Environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/CubeMapping.h"

namespace raycache {

Environment Environment::constant(const Rgb& color) {
    Environment e;
    e.color_ = color;
    return e;
}

Environment Environment::equirectangular(std::shared_ptr<const Image> image) {
    Environment e;
    e.kind_ = Kind::Equirectangular;
    e.images_[0] = std::move(image);
    return e;
}

Environment Environment::cubeFaces(std::array<std::shared_ptr<const Image>, 6> faces) {
    Environment e;
    e.kind_ = Kind::CubeFaces;
    e.images_ = std::move(faces);
    return e;
}

namespace {
// Nearest texel at normalized (s, t), t measured from the top row.
Rgb nearest(const Image& img, float s, float t) {
    const int x = std::clamp(static_cast<int>(s * static_cast<float>(img.width())), 0, img.width() - 1);
    const int y = std::clamp(static_cast<int>(t * static_cast<float>(img.height())), 0, img.height() - 1);
    return img.at(x, y);
}
}  // namespace

Rgb Environment::lookup(const Vec3& d) const {
    switch (kind_) {
    case Kind::Constant:
        return color_;
    case Kind::Equirectangular: {
        constexpr float pi = std::numbers::pi_v<float>;
        const Vec3 n = normalize(d);
        const float phi = std::atan2(n.x, -n.z);                 // 0 at -z, increasing toward +x
        const float theta = std::acos(std::clamp(n.y, -1.0f, 1.0f));  // 0 at +y
        return nearest(*images_[0], 0.5f + phi / (2.0f * pi), theta / pi);
    }
    case Kind::CubeFaces: {
        const CubeCoord c = cubeCoordFromDirection(d);
        return nearest(*images_[static_cast<int>(c.face)], c.s, c.t);
    }
    }
    return color_;
}

}  // namespace raycache
