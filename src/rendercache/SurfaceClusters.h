#pragma once
// The edge-aware part of the Render Cache's hole fills:
// the samples around a hole are grouped by the surface they lie on, and the
// hole takes the mean of one group only, so that a hole on a silhouette
// shows either the object or what lies behind it, never a blend of the two
// (a colour neither has). Two samples lie on one surface when they belong
// to the same object (or both to the background) and their depths differ
// by at most kSurfaceDepthTolerance of the nearer one; a sample joins the
// first group whose first member it lies on one surface with. The chosen
// group is the heaviest (by the filter's weights); of equally heavy groups
// the farther one, since the holes a moving camera opens at a silhouette
// are disocclusions, where what lies behind comes into view; of equally
// heavy groups at one depth the first. The grouping depends on the order
// the samples are added in, which the filters fix (row by row): the image
// does not depend on the thread count.
//
// Not weighted: normals (a sample keeps no normal; the surface's depth
// continuity stands for it) and shadow edges within one surface (nothing
// in a hole tells which side of the edge it lies on).
#include <array>
#include <cmath>

#include "core/Rgb.h"

namespace raycache {

// Two samples whose depths differ by more than this share of the nearer
// one's lie on different surfaces (depth culling's default threshold,
// RenderCacheSettings::depthCullThreshold, for the same question).
inline constexpr float kSurfaceDepthTolerance = 0.1f;

class SurfaceClusters {
public:
    static constexpr int kMaxGroups = 4;  // samples beyond four surfaces are left out

    // A sample of colour `color` with filter weight `weight`, at `depth`
    // (+infinity for the background) on object `object`; `source` names it
    // for the caller (chosenSource()).
    void add(const Rgb& color, float weight, float depth, int object, int source = -1) {
        for (int g = 0; g < count_; ++g) {
            Group& group = groups_[static_cast<std::size_t>(g)];
            if (group.object == object && sameDepth(group.depth, depth)) {
                group.sum += color * weight;
                group.weight += weight;
                return;
            }
        }
        if (count_ < kMaxGroups)
            groups_[static_cast<std::size_t>(count_++)] = Group{color * weight, weight, depth, object, source};
    }
    bool empty() const { return count_ == 0; }
    // The weighted mean of the chosen group; empty() must be false.
    Rgb mean() const {
        const Group& group = chosen();
        return group.sum * (1.0f / group.weight);
    }
    // The `source` of the chosen group's first sample; empty() must be false.
    int chosenSource() const { return chosen().source; }

private:
    static bool sameDepth(float a, float b) {
        if (a == b) return true;  // also both +infinity (the background)
        return std::fabs(a - b) <= kSurfaceDepthTolerance * smaller(a, b);
    }
    // std::fmin(a, b) without the library call GCC makes for it where it may
    // not assume away NaNs (a third of the 3x3 fill's instructions): the
    // same value for every input, NaNs included (a zero's sign aside, which
    // the comparison above does not see).
    static float smaller(float a, float b) { return b < a || a != a ? b : a; }
    struct Group {
        Rgb sum;
        float weight;
        float depth;  // of its first member
        int object;
        int source;   // of its first member
    };
    const Group& chosen() const {
        const Group* best = &groups_[0];
        for (int g = 1; g < count_; ++g) {
            const Group& group = groups_[static_cast<std::size_t>(g)];
            if (group.weight > best->weight || (group.weight == best->weight && group.depth > best->depth))
                best = &group;
        }
        return *best;
    }
    std::array<Group, kMaxGroups> groups_;
    int count_ = 0;
};

}  // namespace raycache
