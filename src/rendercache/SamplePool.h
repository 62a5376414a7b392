#pragma once
// The Render Cache's point samples (SPEC §6): a fixed number of slots, each
// empty or holding what one camera ray found: where it hit, in its object's
// frame so the sample follows the object; the colour it brought back; how
// many frames the sample has been reprojected; and what shading it again
// from a new eye needs (render/TileKernel.h, ReshadeRequest). Stored as
// parallel arrays: reprojection reads only positions and objects.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/Rgb.h"
#include "core/Vec3.h"

namespace raycache {

struct SamplePool {
    static constexpr int kEmpty = -1;
    static constexpr int kBackground = -2;  // the ray hit nothing: `position` holds its direction

    // All slots empty.
    void reset(std::size_t capacity);
    std::size_t capacity() const { return objectId.size(); }
    bool empty(std::size_t slot) const { return objectId[slot] == kEmpty; }

    std::vector<int> objectId;      // kEmpty, kBackground or an index into Scene::objects
    std::vector<Vec3> position;     // hit point minus the object's origin, or the direction of a miss
    std::vector<Rgb> color;         // what the pixel showed when last traced or reshaded
    std::vector<std::uint16_t> age; // reprojections since it was traced
    // For reshading (only meaningful where viewDependent is set).
    std::vector<unsigned char> viewDependent;  // mirror, glass or highlight: its colour depends on the eye
    std::vector<int> primitiveId;
    std::vector<float> baryU, baryV;
    std::vector<Rgb> viewIndependent;
    std::vector<std::uint64_t> litMask;
};

}  // namespace raycache
