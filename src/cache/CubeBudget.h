#pragma once
// The caching cubes under a memory budget (RayCacheSettings::memoryBudget):
// when the cubes at their asked resolutions would take more, resolutions are
// halved one cube at a time, always the cube with the most texels per unit of
// its object's size (a small object with a large cube loses least: its
// texels are the finest on screen), until they fit. Decided before anything
// is allocated; a scene that cannot fit even at the smallest resolution is
// refused with one clear error.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace raycache {

struct CubeRequest {
    std::string name;     // the object's, for the report
    bool depth = false;   // CDCT: a depth word per texel
    int resolution = 0;   // asked for
    float size = 1.0f;    // the object's extent (bounding half-diagonal), > 0
    // A CCT cube whose resolution follows the view (cache/ViewSizedResolution.h):
    // `resolution` is the finest it may grow to, and it keeps a byte per
    // texel for inherited colours.
    bool viewSized = false;
};

struct CubeBudgetPlan {
    std::vector<int> resolutions;  // per request, after the budget
    std::size_t askedBytes = 0;    // at the asked resolutions
    std::size_t bytes = 0;         // at the planned ones
    int lowered = 0;               // cubes below their asked resolution
    // One line saying what was lowered and why; empty when nothing was.
    std::string note;
};

// The memory of one cube of `resolution` texels per face side, as RayCache
// allocates it: colour words (and depth words), validity bits, the coarser
// levels of a multi-resolution CCT cube (`levels` > 1) and, in animated
// scenes, its dependency blocks and dropped-texel bits; sized from the view,
// its inherited-level bytes.
std::size_t cubeBytes(bool depth, int resolution, int levels, bool tracksDependencies, bool viewSized = false);

// Throws InputError when even `minResolution` for every cube exceeds `budget`.
CubeBudgetPlan planCubeBudget(std::span<const CubeRequest> cubes, std::optional<std::size_t> budget, int levels,
                              bool tracksDependencies, int minResolution);

}  // namespace raycache
