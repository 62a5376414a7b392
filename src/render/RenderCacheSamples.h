#pragma once
// What the Render Cache (rendercache/) and the tile kernel hand each other:
// the samples the kernel shades for it (TileKernel::renderCameraPixels) and
// the points it asks the kernel to shade again from a new eye
// (TileKernel::reshadeSurfaces).
#include <cstdint>

#include "core/Ray.h"
#include "core/Rgb.h"
#include "trace/TraceHit.h"

namespace raycache {

// What the Render Cache (rendercache/) keeps of a camera ray: its colour, its
// first hit, and the light there split in a view-independent part and the
// highlights (tests/render/ScalarShadingRule.h), so the view-dependent rest can be shaded again from a new eye.
struct PrimarySample {
    Rgb color;
    TraceHit hit;               // objectId -1: the ray saw the background
    Rgb viewIndependent;        // ambient plus the unshadowed lights' diffuse term
    // viewIndependent with the albedo divided out (computed with a white
    // albedo, so it is known where the albedo is black): the Render Cache
    // multiplies it by the albedo its pixel's centre sees on a texture.
    Rgb lighting;
    std::uint64_t litMask = 0;  // bit l: light l reached the hit
};

// A surface point seen again from a new eye (the Render Cache's reprojected
// samples on mirrors, glass and glossy surfaces).
struct ReshadeRequest {
    Ray ray;       // from the new eye through the point
    TraceHit hit;  // the point's object, primitive and barycentrics; t its distance along `ray`
    Rgb viewIndependent;
    std::uint64_t litMask = 0;
};

}  // namespace raycache
