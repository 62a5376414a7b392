#pragma once
// CentreRetexturing (rendercache/SampleRetexturing.h) for the samples of
// one image row, pixel by pixel from left to right: the centre rays are
// made sixteen at a time (RowRays), and met with a triangle sixteen at a
// time (meetTriangle16): the textured samples of a block of sixteen pixels
// mostly lie on one triangle; on a checkerboard, its squares are found
// sixteen at a time too (checkerSquares16). The same colours bit for bit.
#include <optional>
#include <vector>

#include "rendercache/CheckerLanes.h"
#include "rendercache/RowRays.h"
#include "rendercache/SampleRetexturing.h"
#include "rendercache/TriangleMeetLanes.h"

namespace raycache {

class RowRetexturing {
public:
    // Row `y` of `rays`' image, samples of `objects`.
    RowRetexturing(const std::vector<SceneObject>& objects, const CameraRays& rays, int y)
        : objects_(objects), retexturing_(objects), rays_(rays, y) {}

    // CentreRetexturing::color(objectId, texturing, rays.ray(x, y),
    // sampleDistance, color).
    template <typename Distance>
    bool color(int x, int objectId, const SampleTexturing& texturing, const Distance& sampleDistance, Rgb& color) {
        const TriangleOnItsPlane* const triangle = retexturing_.meshTriangle(objectId, texturing.primitiveId);
        if (!triangle) return retexturing_.color(objectId, texturing, rays_.at(x), sampleDistance, color);
        if (!triangle->valid) return false;
        const int block = x - x % kFloatLanes;
        if (block != block_ || objectId != object_ || texturing.primitiveId != primitive_) {
            meetTriangle16(*triangle, rays_.block(x), meets_);
            block_ = block;
            object_ = objectId;
            primitive_ = texturing.primitiveId;
            // On a checkerboard, the block's squares at once (the texture
            // coordinates of lanes that miss are never looked at).
            checker_ = checkerboardOf(objectId);
            const auto* const uv = retexturing_.cornerTextureCoordinates();
            if (checker_ && uv) checkerSquares16(*checker_, *uv, meets_.u, meets_.v, odd_);
            else checker_ = nullptr;
        }
        const auto lane = static_cast<std::size_t>(x - block);
        if (!meets_.hit[lane]) return false;
        if (checker_)
            color = CentreRetexturing::shaded(odd_[lane] ? checker_->odd : checker_->even, texturing);
        else
            color = retexturing_.colorAt(objectId, texturing, meets_.u[lane], meets_.v[lane]);
        return true;
    }

private:
    // The checkerboard that object `objectId`'s diffuse texture is, or null.
    const Checkerboard* checkerboardOf(int objectId) const {
        const std::optional<Texture>& texture = objects_[static_cast<std::size_t>(objectId)].material.diffuseTexture;
        return texture ? texture->checkerboardPattern() : nullptr;
    }

    const std::vector<SceneObject>& objects_;
    CentreRetexturing retexturing_;
    RowRays rays_;
    // The block whose rays meets_ met with triangle primitive_ of object_.
    int block_ = -1, object_ = -1, primitive_ = -1;
    TriangleMeets16 meets_;
    // Where the block's textured samples lie on a checkerboard: its squares
    // (checkerSquares16), else null.
    const Checkerboard* checker_ = nullptr;
    int odd_[kFloatLanes];
};

}  // namespace raycache
