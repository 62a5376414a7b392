#pragma once
// The world-space boxes around an object's shape as it stands.
#include <algorithm>
#include <vector>

#include "core/Box3.h"
#include "scene/SceneObject.h"

namespace raycache {

// Spheres: centre +- radius; meshes: the box of their vertices (empty for an
// empty mesh).
Box3 worldBounds(const SceneObject& object);

// A shape bounded more tightly than by one box: `whole`, and for a mesh of
// more than `trianglesPerPart` triangles the boxes of its runs of that many
// consecutive triangles (meshes keep neighbouring triangles close in their
// order, so the runs' boxes hug the surface).
struct PartedBounds {
    static constexpr std::size_t kPartsPerGroup = 16;
    Box3 whole;
    std::vector<Box3> parts;
    // groups[g] bounds parts [g * kPartsPerGroup, (g + 1) * kPartsPerGroup): a
    // test can skip sixteen parts at once.
    std::vector<Box3> groups;
    // A sphere's own shape (ballRadius >= 0), inside `whole`: tests that can
    // use it are tighter than with its box.
    Vec3 ballCentre{};
    float ballRadius = -1.0f;
    bool isBall() const { return ballRadius >= 0.0f; }

    // Every box grown by `fraction` of its largest absolute coordinate (at
    // least of 1): room for float rounding around the shape.
    PartedBounds grownRelative(float fraction) const;
    // Every box moved by `offset`.
    PartedBounds shifted(const Vec3& offset) const;

    // Whether `meets` holds for one of the boxes bounding the shape most
    // tightly (the parts, or the whole box for a shape without parts),
    // visiting only the parts whose whole box and group box it holds for.
    template <typename Predicate>
    bool any(const Predicate& meets) const {
        if (!meets(whole)) return false;
        if (parts.empty()) return true;
        for (std::size_t g = 0; g < groups.size(); ++g) {
            if (!meets(groups[g])) continue;
            const std::size_t end = std::min(parts.size(), (g + 1) * kPartsPerGroup);
            for (std::size_t p = g * kPartsPerGroup; p < end; ++p)
                if (meets(parts[p])) return true;
        }
        return false;
    }
};
PartedBounds partedBounds(const SceneObject& object, int trianglesPerPart);
// The margin PartedBounds::grownRelative adds on every side of `box`:
// `fraction` of its largest absolute coordinate, at least of 1.
float relativeMargin(const Box3& box, float fraction);

}  // namespace raycache
