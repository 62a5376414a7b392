#pragma once
// The Render Cache's point samples (Walter et al. 1999): each slot empty or holding
// what one camera ray found: where it hit, in its object's frame so the
// sample follows the object; the colour it brought back; how many frames the
// sample has been reprojected; and what shading it again from a new eye
// needs (render/TileKernel.h, ReshadeRequest). Stored as a few arrays of
// small records, each read whole by the passes that read it: reprojection
// reads every sample's point and look and copies them, 32 bytes a sample
// in two records (five arrays of 31 bytes before: every array is a stream
// of its own for the copy, to read and to write); the reshading fields are
// read only where the look says the sample depends on the eye.
//
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/Rgb.h"
#include "core/UninitializedAllocator.h"
#include "core/Vec3.h"

namespace raycache {

class Parallel;

// Where a sample is.
struct SamplePoint {
    Vec3 position;      // hit point minus the object's origin, or the direction of a miss
    int objectId = -1;  // SamplePool::kEmpty, kBackground or an index into Scene::objects
    bool operator==(const SamplePoint&) const = default;
};
static_assert(sizeof(SamplePoint) == 16);

// What a sample shows, and for how long it has.
struct SampleLook {
    Rgb color;              // what the pixel showed when last traced or reshaded
    std::uint16_t age = 0;  // reprojections since it was traced
    // Non-zero: a mirror, glass or highlight, whose colour depends on the
    // eye: kViewDependent, plus kShadedFromAnOlderEye while a moving frame
    // has left it unreshaded (rendercache/ReshadeSelection.h).
    unsigned char viewDependent = 0;
    unsigned char textured = 0;  // its albedo comes from a texture: SampleTexturing holds its colour's parts
    bool operator==(const SampleLook&) const = default;
};
static_assert(sizeof(SampleLook) == 16);
inline constexpr unsigned char kViewDependent = 1;
inline constexpr unsigned char kShadedFromAnOlderEye = 2;

// A textured sample's colour taken apart (only meaningful where
// SampleLook::textured is set): colour = albedo * lighting + rest, where
// `lighting` is the light that the albedo multiplies (ambient and the
// unshadowed lights' diffuse term: the view-independent part of the shading
// rule, tests/render/ScalarShadingRule.h, with a white albedo) and `rest` what it does not (highlights, reflected and
// refracted light). Reconstruction fetches the albedo where the pixel's
// centre meets `primitiveId` and multiplies it back
// (rendercache/SampleRetexturing.h).
struct SampleTexturing {
    Rgb lighting;
    Rgb rest;
    int primitiveId = 0;
    bool operator==(const SampleTexturing&) const = default;
};

// For reshading (only meaningful where SampleLook::viewDependent is set).
struct ReshadeInputs {
    int primitiveId = 0;
    float baryU = 0.0f, baryV = 0.0f;
    Rgb viewIndependent;
    std::uint64_t litMask = 0;
    bool operator==(const ReshadeInputs&) const = default;
};

struct SamplePool {
    static constexpr int kEmpty = -1;
    static constexpr int kBackground = -2;  // the ray hit nothing: `position` holds its direction

    // `pixelSlots` empty pixel slots and room for `overflowCapacity`
    // samples after them, none used. Only the pixel slots are written (over
    // `parallel`'s workers when given); an overflow slot is written fresh
    // when it is taken. No reader looks past used(), so the memory of
    // overflow slots never taken is never touched.
    void reset(std::size_t pixelSlots, std::size_t overflowCapacity, const Parallel* parallel = nullptr);
    std::size_t capacity() const { return point.size(); }
    // The slots that may hold a sample: the pixel slots and the used overflow slots.
    std::size_t used() const { return pixelSlots + overflowUsed; }
    bool empty(std::size_t slot) const { return point[slot].objectId == kEmpty; }
    // The next free overflow slot, empty (as a pixel slot after reset), to
    // be filled by the caller; throws RuntimeError when none is left.
    std::size_t takeOverflowSlot();
    std::size_t pixelSlots = 0;    // slots addressed by pixel
    std::size_t overflowUsed = 0;  // overflow slots [pixelSlots, pixelSlots + overflowUsed) in use

    template <typename T>
    using Records = std::vector<T, UninitializedAllocator<T>>;
    Records<SamplePoint> point;
    Records<SampleLook> look;
    Records<ReshadeInputs> reshade;
    Records<SampleTexturing> texturing;
};

}  // namespace raycache
