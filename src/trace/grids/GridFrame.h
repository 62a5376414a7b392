#pragma once
// The space a frustum grid lives in: an orthonormal frame (right, up,
// forward) at an apex, and how a point of that frame maps to the grid's 2D
// coordinates (s, t) and its depth z = distance along forward.
//   Perspective: s = x/z, t = y/z (the camera's image plane; primary rays)
//   Angular:     s = atan(x/z), t = atan(y/z) (the spherical light space of
//                the document: azimuth in the forward-right plane, elevation
//                in the forward-up plane; point and spot lights)
//   Orthographic: s = x, t = y (directional lights)
// Both perspective mappings map a straight segment in z > 0 to a curve whose
// s and t are monotonic along it, so the box of a convex polygon's corners
// bounds its image: the binning and the ray traversal rest on that.
// Everything is computed in double so the grids' bounds are exact to far
// below the margins the binning adds.
#include <cmath>

#include "core/DoubleLanes.h"
#include "core/Vec3.h"

namespace raycache {

struct Point3d {
    double x = 0.0, y = 0.0, z = 0.0;
};

enum class GridMapping { Perspective, Angular, Orthographic };

struct GridFrame {
    Point3d apex, right, up, forward;  // forward, right, up orthonormal
    GridMapping mapping = GridMapping::Perspective;

    bool perspective() const { return mapping != GridMapping::Orthographic; }

    // A world point in frame coordinates.
    Point3d toFrame(const Vec3& p) const {
        const double px = p.x - apex.x, py = p.y - apex.y, pz = p.z - apex.z;
        return {px * right.x + py * right.y + pz * right.z, px * up.x + py * up.y + pz * up.z,
                px * forward.x + py * forward.y + pz * forward.z};
    }
    // A world direction in frame coordinates.
    Point3d directionToFrame(const Vec3& d) const {
        return {d.x * right.x + d.y * right.y + d.z * right.z, d.x * up.x + d.y * up.y + d.z * up.z,
                d.x * forward.x + d.y * forward.y + d.z * forward.z};
    }
    // The same two for kDoubleLanes points or directions at once (world
    // coordinates in, frame coordinates out, in place), with the same
    // operations in the same order: each lane's result is the scalar one's
    // bits. directionZToFrame: the depth alone.
    [[gnu::always_inline]] void toFrame(DoubleLanes& x, DoubleLanes& y, DoubleLanes& z) const {
        x -= apex.x;
        y -= apex.y;
        z -= apex.z;
        directionToFrame(x, y, z);
    }
    [[gnu::always_inline]] void directionToFrame(DoubleLanes& x, DoubleLanes& y, DoubleLanes& z) const {
        const DoubleLanes fx = x * right.x + y * right.y + z * right.z;
        const DoubleLanes fy = x * up.x + y * up.y + z * up.z;
        z = x * forward.x + y * forward.y + z * forward.z;
        x = fx;
        y = fy;
    }
    [[gnu::always_inline]] void directionZToFrame(const DoubleLanes& x, const DoubleLanes& y, const DoubleLanes& z,
                                                  DoubleLanes& frameZ) const {
        frameZ = x * forward.x + y * forward.y + z * forward.z;
    }
};

// The frame whose forward is `forward` (need not be unit), with `upHint`
// deciding the roll; a fallback hint is used when the two are parallel.
GridFrame makeGridFrame(const Vec3& apex, const Vec3& forward, const Vec3& upHint, GridMapping mapping);

}  // namespace raycache
