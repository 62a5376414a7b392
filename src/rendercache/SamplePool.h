#pragma once
// The Render Cache's point samples (SPEC §6): each slot empty or holding
// what one camera ray found: where it hit, in its object's frame so the
// sample follows the object; the colour it brought back; how many frames the
// sample has been reprojected; and what shading it again from a new eye
// needs (render/TileKernel.h, ReshadeRequest). Stored as parallel arrays:
// reprojection reads only positions, objects and ages.
//
// The slots are in pixel order, as on the GPU: slot i < pixelSlots belongs
// to pixel i of the image and its margin (PointImage::pixelIndex), so every
// pass over the image reads the pool in order and a new sample goes to its
// pixel's slot without a search. Samples that have no pixel yet (traced
// through the predicted camera) go to the overflow slots after them, used
// from the front and emptied each frame when reprojection moves the
// samples into the other buffer (reproject()).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/Rgb.h"
#include "core/Vec3.h"

namespace raycache {

struct SamplePool {
    static constexpr int kEmpty = -1;
    static constexpr int kBackground = -2;  // the ray hit nothing: `position` holds its direction

    // `pixelSlots` empty pixel slots and room for `overflowCapacity`
    // samples after them, none used.
    void reset(std::size_t pixelSlots, std::size_t overflowCapacity);
    std::size_t capacity() const { return objectId.size(); }
    // The slots that may hold a sample: the pixel slots and the used overflow slots.
    std::size_t used() const { return pixelSlots + overflowUsed; }
    bool empty(std::size_t slot) const { return objectId[slot] == kEmpty; }
    // The next free overflow slot, to be filled by the caller; throws
    // RuntimeError when none is left.
    std::size_t takeOverflowSlot();
    std::size_t pixelSlots = 0;    // slots addressed by pixel
    std::size_t overflowUsed = 0;  // overflow slots [pixelSlots, pixelSlots + overflowUsed) in use

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
