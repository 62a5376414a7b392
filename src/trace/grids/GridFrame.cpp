#include "trace/grids/GridFrame.h"

namespace raycache {

namespace {

Point3d normalized(Point3d p) {
    const double length = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    return {p.x / length, p.y / length, p.z / length};
}

Point3d cross(const Point3d& a, const Point3d& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

double lengthSquared(const Point3d& p) { return p.x * p.x + p.y * p.y + p.z * p.z; }

}  // namespace

GridFrame makeGridFrame(const Vec3& apex, const Vec3& forward, const Vec3& upHint, GridMapping mapping) {
    GridFrame frame;
    frame.mapping = mapping;
    frame.apex = {apex.x, apex.y, apex.z};
    frame.forward = normalized({forward.x, forward.y, forward.z});
    Point3d right = cross(frame.forward, {upHint.x, upHint.y, upHint.z});
    if (lengthSquared(right) < 1e-12) right = cross(frame.forward, {1.0, 0.0, 0.0});
    if (lengthSquared(right) < 1e-12) right = cross(frame.forward, {0.0, 0.0, 1.0});
    frame.right = normalized(right);
    frame.up = cross(frame.right, frame.forward);
    return frame;
}

}  // namespace raycache
