#include "cache/CdctSearch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cache/CubeAddressing.h"

namespace raycache {

namespace {

constexpr float kCdctInfinity = std::numeric_limits<float>::infinity();

// The ray parameter at which the line origin + t * direction leaves the box
// center ± half (the far slab crossing); 0 if it is behind the origin.
float tLeavingBox(const Vec3& center, const Vec3& half, const Vec3& origin, const Vec3& direction) {
    float tExit = kCdctInfinity;
    for (int a = 0; a < 3; ++a) {
        const float d = direction[a];
        if (std::fabs(d) < 1e-12f) continue;  // parallel to this slab pair: it does not bound the exit
        const float t1 = (center[a] - half[a] - origin[a]) / d;
        const float t2 = (center[a] + half[a] - origin[a]) / d;
        tExit = std::min(tExit, std::max(t1, t2));
    }
    return std::isfinite(tExit) ? std::max(0.0f, tExit) : 0.0f;
}

bool usable(const Vec3& origin, const Vec3& direction) {
    return isFinite(origin) && isFinite(direction) && dot(direction, direction) > 0.0f;
}

// The point texel `index` stands for: centre + (unit texel direction) * stored depth.
Vec3 storedPoint(const CachingCube& cube, int index) {
    const int n = cube.size();
    const CubeTexel texel{static_cast<CubeFace>(index / (n * n)), index % n, (index / n) % n};
    return cube.center() + normalize(cubeTexelCenterDirection(texel, n)) * cube.depth(index);
}

// Whether the point texel `index` stores lies within `tolerance` texel
// footprints (the width of one texel at the point's depth) of the ray.
bool onRay(const CachingCube& cube, int index, float tolerance, const Vec3& origin, const Vec3& direction) {
    const Vec3 w = storedPoint(cube, index) - origin;
    const float along = dot(w, direction);
    if (!(along > 0.0f)) return false;  // behind the ray's origin
    const float footprint = cube.depth(index) * 2.0f / static_cast<float>(cube.size());
    return length(w - direction * along) <= tolerance * footprint;
}

// Bilinear blend of the (up to) four texels around `v` (a direction from the
// centre) on the face of `found`, leaving out neighbours whose stored point is
// off the ray (another surface across a depth edge). Falls back to `found`.
Rgb filteredColor(const CachingCube& cube, int found, const Vec3& v, float tolerance, const Vec3& origin,
                  const Vec3& direction) {
    const int n = cube.size();
    const CubeCoord coord = cubeCoordFromDirection(v);
    const Rgb own = *cube.read(found);
    if (static_cast<int>(coord.face) != found / (n * n)) return own;
    const float u = coord.s * static_cast<float>(n) - 0.5f;
    const float w = coord.t * static_cast<float>(n) - 0.5f;
    const float x0f = std::floor(u), y0f = std::floor(w);
    const float fx = u - x0f, fy = w - y0f;
    const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
    const int faceBase = found / (n * n) * n * n;
    Rgb sum{};
    float weightSum = 0.0f;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const int x = std::clamp(x0 + i, 0, n - 1), y = std::clamp(y0 + j, 0, n - 1);
            const int index = faceBase + y * n + x;
            const float weight = (i ? fx : 1.0f - fx) * (j ? fy : 1.0f - fy);
            if (weight <= 0.0f || !cube.isValid(index) || !onRay(cube, index, tolerance, origin, direction)) continue;
            sum += *cube.read(index) * weight;
            weightSum += weight;
        }
    return weightSum > 0.0f ? sum * (1.0f / weightSum) : own;
}

// The sine of the angle between direction (u, v, 1) of a face (u, v in
// [-1, 1], from coord) and the nearest edge of the `blockSide`-texel block
// holding it, a little under. Block edges are great circles (planes u = const
// through the centre), and the sine of the angle to the plane u = e is
// |u - e| / (sqrt(1 + u^2 + v^2) * sqrt(1 + e^2)).
float sineToBlockEdge(const CubeCoord& coord, int n, int blockSide) {
    const float size = static_cast<float>(n);
    const float u = 2.0f * coord.s - 1.0f, v = 2.0f * coord.t - 1.0f;
    const auto distance = [&](float along, float faceCoord) {
        const int texel = std::clamp(static_cast<int>(faceCoord * size), 0, n - 1);
        const int first = texel / blockSide * blockSide;
        const float e0 = 2.0f * static_cast<float>(first) / size - 1.0f;
        const float e1 = 2.0f * static_cast<float>(std::min(first + blockSide, n)) / size - 1.0f;
        return std::min((along - e0) / std::sqrt(1.0f + e0 * e0), (e1 - along) / std::sqrt(1.0f + e1 * e1));
    };
    const float nearest = std::min(distance(u, coord.s), distance(v, coord.t));
    // Shaved a little: s and t carry float rounding.
    return std::max(0.0f, nearest / std::sqrt(1.0f + u * u + v * v) - 1e-5f);
}

// The search's answer once it met texel `found` at `v` (a direction from the
// centre): rejected by error control, filtered, or the texel's colour.
CdctResult answerAt(const CachingCube& cube, const CdctParameters& p, const CdctImprovements& improvements,
                    int found, const Vec3& v, const Vec3& origin, const Vec3& d, int samples) {
    if (improvements.errorControl && !onRay(cube, found, p.tolerance, origin, d))
        return {CdctOutcome::Rejected, {}, samples, found};
    if (improvements.filter)
        return {CdctOutcome::Found, filteredColor(cube, found, v, p.tolerance, origin, d), samples, found};
    return {CdctOutcome::Found, *cube.read(found), samples, found};
}

// The frame of a cube face: a point p (relative to the centre) lies in the
// face's cone when p·n > 0 and |p·a|, |p·b| <= p·n, and then addresses face
// coordinates sc = p·a / p·n, tc = p·b / p·n in [-1, 1] (core/CubeMapping.h:
// s = (sc + 1) / 2, t = (tc + 1) / 2; texel column x holds s in [x/n, (x+1)/n)).
struct FaceFrame {
    Vec3 n, a, b;
};
constexpr FaceFrame kFaceFrames[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},   // +x
    {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},   // -x
    {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},     // +y
    {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},   // -y
    {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},    // +z
    {{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}},  // -z
};

// One face coordinate of the ray p0 + t·d along a face: c(t) = (c0 + cd·t) /
// (w0 + wd·t). It moves one way only while the ray stays in the face's cone
// (its derivative has the sign of cd·w0 - c0·wd), so the texel columns (or
// rows) it crosses come in order, and the ray parameter at which it reaches
// the edge e (a plane through the centre) is (e·w0 - c0) / (cd - e·wd).
struct FaceAxis {
    double c0, cd;
    int step;  // +1, -1, or 0 (does not move)
    double tAt(double edge, double w0, double wd) const {
        const double denominator = cd - edge * wd;
        const double t = (edge * w0 - c0) / denominator;
        return denominator != 0.0 && std::isfinite(t) ? t : kCdctInfinity;
    }
};

}  // namespace

float rayParameterAtDistance(const Vec3& center, const Vec3& origin, const Vec3& direction, float radius) {
    const Vec3 w = origin - center;
    const double b = dot(w, direction);
    const double c = static_cast<double>(dot(w, w)) - static_cast<double>(radius) * radius;
    const double t = -b + std::sqrt(std::max(0.0, b * b - c));
    return static_cast<float>(std::max(0.0, t));
}

CdctResult searchCdctParity(const CachingCube& cube, const CdctParameters& p, const Vec3& origin,
                            const Vec3& direction) {
    // Algorithm 4 (thesis §4.5): a linear search along the ray from where its
    // line leaves the box, then a binary search; bounded in both.
    if (!usable(origin, direction)) return {};
    const Vec3 c = cube.center();
    const Vec3 d = normalize(direction);
    const float tStart = tLeavingBox(c, cube.halfSize(), origin, d);
    // Stored depths never exceed maxDepth, so the point at maxDepth ends the search.
    const float tEnd = std::max(tStart, rayParameterAtDistance(c, origin, d, p.maxDepth));
    const double wanted = std::ceil(static_cast<double>(tEnd - tStart) / p.step);
    const double cap = std::ceil(2.0 * p.maxDepth / p.step) + 1.0;
    const int steps = static_cast<int>(std::clamp(wanted, 1.0, cap));

    int samples = 0;
    // The texel addressed by centre -> point at t; -1 if invalid (aborts the search).
    const auto texelAt = [&](float t, float& distance) {
        ++samples;
        const Vec3 v = origin + d * t - c;
        distance = length(v);
        const int texel = cube.texelIndexFor(v);
        return cube.isValid(texel) ? texel : -1;
    };

    float previous = tStart;
    for (int i = 1; i <= steps; ++i) {
        const float t = i == steps ? tEnd : tStart + static_cast<float>(i) * p.step;
        float distance;
        const int texel = texelAt(t, distance);
        if (texel < 0) return {CdctOutcome::Invalid, {}, samples};
        if (cube.depth(texel) <= distance) {
            // Crossed between `previous` (in front of the stored surface) and t (at or behind it).
            float lo = previous, hi = t;
            int found = texel;
            for (int k = 0; k < kCdctMaxBinarySteps && hi - lo >= p.epsilon; ++k) {
                const float mid = 0.5f * (lo + hi);
                if (!(mid > lo && mid < hi)) break;  // float resolution reached
                const int midTexel = texelAt(mid, distance);
                if (midTexel < 0) return {CdctOutcome::Invalid, {}, samples};
                if (cube.depth(midTexel) <= distance) {
                    hi = mid;
                    found = midTexel;
                } else {
                    lo = mid;
                }
            }
            return {CdctOutcome::Found, *cube.read(found), samples, found};
        }
        // Reached maxDepth without crossing (rounding only): what lies there is the environment.
        if (i == steps) return {CdctOutcome::Found, *cube.read(texel), samples, texel};
        previous = t;
    }
    return {};  // not reached: the last step returns
}

namespace {

// Improved CDCT's search as a walk over the texels the ray crosses
// (CdctImprovements::faceWalk): on each face the ray's image is a line, so
// its texels follow one another as in a 2D DDA, each entered and left at ray
// parameters given by one division. The ray's distance from the centre is
// convex in t, so over a texel it is largest at an end: the ray reaches the
// texel's surface within it exactly when the stored depth is at most the
// larger end distance. A block of the depth pyramid whose smallest depth
// exceeds the ray's distance at both ends of its stretch is crossed in one
// step. Every texel the ray crosses is tested, none is stepped over.
CdctResult faceWalk(const CachingCube& cube, const CdctParameters& p, const CdctImprovements& improvements,
                    const DepthPyramid* pyramid, const Vec3& origin, const Vec3& d, float tStart, float tEnd,
                    float tMaxDepth, long maxSteps) {
    constexpr double kNever = std::numeric_limits<double>::infinity();
    const int n = cube.size();
    const double size = static_cast<double>(n);
    const Vec3 p0 = origin - cube.center();
    const auto distance2 = [&](double t) {
        const double x = p0.x + d.x * t, y = p0.y + d.y * t, z = p0.z + d.z * t;
        return x * x + y * y + z * z;
    };
    // Face coordinate of texel edge k (0..n).
    const auto edgeAt = [&](int k) { return 2.0 * static_cast<double>(k) / size - 1.0; };
    const auto texelOf = [&](double c) {
        return std::clamp(static_cast<int>(std::floor((c + 1.0) * 0.5 * size)), 0, n - 1);
    };

    int samples = 0;
    double t = tStart;
    // Where the walk stands: a face, its frame along the ray, a texel.
    int face = 0, x = 0, y = 0;
    double w0 = 0.0, wd = 0.0;
    FaceAxis ax{}, ay{};
    const auto enter = [&](double at) {
        // The face and texel holding the ray at `at`, as lookups address them.
        const Vec3 v = p0 + d * static_cast<float>(at);
        const CubeCoord coord = cubeCoordFromDirection(v);
        face = static_cast<int>(coord.face);
        x = std::clamp(static_cast<int>(coord.s * static_cast<float>(n)), 0, n - 1);
        y = std::clamp(static_cast<int>(coord.t * static_cast<float>(n)), 0, n - 1);
        const FaceFrame& f = kFaceFrames[face];
        w0 = dot(p0, f.n);
        wd = dot(d, f.n);
        ax = {dot(p0, f.a), dot(d, f.a), 0};
        ay = {dot(p0, f.b), dot(d, f.b), 0};
        const auto direction = [&](const FaceAxis& axis) {
            const double rate = axis.cd * w0 - axis.c0 * wd;
            return rate > 0.0 ? 1 : rate < 0.0 ? -1 : 0;
        };
        ax.step = direction(ax);
        ay.step = direction(ay);
    };
    // Ray parameter at which the ray leaves texels [lo, lo + span) along an
    // axis; infinity when it never does (the coordinate tends to a limit
    // inside, or the edge's plane is met only behind the centre, w <= 0).
    const auto leaves = [&](const FaceAxis& axis, int lo, int span) {
        if (axis.step == 0) return kNever;
        const double at = axis.tAt(edgeAt(axis.step > 0 ? std::min(lo + span, n) : lo), w0, wd);
        return at >= t - 1e-9 * (1.0 + std::fabs(t)) && w0 + wd * at > 0.0 ? std::max(at, t) : kNever;
    };
    const auto found = [&](int texel, double tIn, double tOut) {
        // Where along [tIn, tOut] the ray reaches the stored depth.
        const float depth = cube.depth(texel);
        double tHit = tIn;
        if (distance2(tIn) < static_cast<double>(depth) * depth)
            tHit = std::clamp(static_cast<double>(rayParameterAtDistance(cube.center(), origin, d, depth)), tIn, tOut);
        return answerAt(cube, p, improvements, texel, p0 + d * static_cast<float>(tHit), origin, d, samples);
    };

    enter(t);
    const double tLast = tEnd;  // in double, as the walk's parameters
    for (long step = 0; step <= maxSteps; ++step) {
        if (t >= tLast) break;
        ++samples;
        // The largest pyramid block around the texel that the ray crosses
        // nearer than all its depths.
        bool skipped = false;
        if (pyramid) {
            const double near2 = distance2(t);
            for (int level = pyramid->levelCount() - 1; level >= 0 && !skipped; --level) {
                const float nearest = pyramid->minDepth(level, face, x, y);
                if (!(nearest > 0.0f) || static_cast<double>(nearest) * nearest <= near2) continue;
                const int side = pyramid->blockSide(level);
                const int bx = x / side * side, by = y / side * side;
                const double tx = leaves(ax, bx, side), ty = leaves(ay, by, side);
                const double tOut = std::min({tx, ty, tLast});
                if (static_cast<double>(nearest) * nearest <= distance2(tOut)) continue;  // may meet it: look finer
                skipped = true;
                if (tOut >= tLast) {
                    t = tLast;
                    break;
                }
                // Into the block's neighbour across the edge it left by.
                t = tOut;
                if (tx <= ty) {
                    x = ax.step > 0 ? bx + side : bx - 1;
                    y = std::clamp(texelOf((ay.c0 + ay.cd * t) / (w0 + wd * t)), by, std::min(by + side, n) - 1);
                } else {
                    y = ay.step > 0 ? by + side : by - 1;
                    x = std::clamp(texelOf((ax.c0 + ax.cd * t) / (w0 + wd * t)), bx, std::min(bx + side, n) - 1);
                }
            }
        }
        if (!skipped) {
            const int texel = (face * n + y) * n + x;
            if (!cube.isValid(texel)) return {CdctOutcome::Invalid, {}, samples};
            const double tx = leaves(ax, x, 1), ty = leaves(ay, y, 1);
            const double tOut = std::min({tx, ty, tLast});
            const double depth = cube.depth(texel);
            if (depth * depth <= std::max(distance2(t), distance2(tOut))) return found(texel, t, tOut);
            t = tOut;
            if (t >= tLast) break;
            if (tx <= ty)
                x += ax.step;
            else
                y += ay.step;
        }
        if (x < 0 || x >= n || y < 0 || y >= n || !(w0 + wd * t > 0.0)) {
            // Off the face: on to the face the ray enters, a hair past its edge.
            const int previous = face;
            enter(t + 1e-6 * (1.0 + std::fabs(t)));
            if (face == previous) {
                // Rounding kept it on this face: step past the edge by more.
                t += 1e-4 * (1.0 + std::fabs(t));
                enter(t);
            }
        }
    }
    if (samples > maxSteps) return {CdctOutcome::Exhausted, {}, samples};
    // No crossing before the end: the environment, cached at maxDepth.
    ++samples;
    const Vec3 far = origin + d * tMaxDepth - cube.center();
    const int texel = cube.texelIndexFor(far);
    if (!cube.isValid(texel)) return {CdctOutcome::Invalid, {}, samples};
    return answerAt(cube, p, improvements, texel, far, origin, d, samples);
}

}  // namespace

CdctResult searchCdctImproved(const CachingCube& cube, const CdctParameters& p, const CdctImprovements& improvements,
                              float farthestSurface, const DepthPyramid* pyramid, const Vec3& origin,
                              const Vec3& direction) {
    if (!usable(origin, direction)) return {};
    const Vec3 c = cube.center();
    const Vec3 d = normalize(direction);
    const float n = static_cast<float>(cube.size());
    const float tStart = tLeavingBox(c, cube.halfSize(), origin, d);
    const float tMaxDepth = std::max(tStart, rayParameterAtDistance(c, origin, d, p.maxDepth));
    float tEnd = tMaxDepth;
    if (improvements.earlyExit && farthestSurface < p.maxDepth) {
        // No cached surface lies farther from the centre than farthestSurface:
        // a ray that gets past it without crossing one sees the environment,
        // so marching on to maxDepth would only confirm that.
        const float bound = farthestSurface * (1.0f + 1e-3f) + 1e-6f;
        tEnd = std::clamp(rayParameterAtDistance(c, origin, d, bound), tStart, tMaxDepth);
    }

    // One step turns the ray, seen from the centre, by 0.8 / n: 40% of a
    // texel's width at a face's centre, 98% of the narrowest (at its corners),
    // so no texel is stepped over.
    const float stepAngle = 0.8f / n;
    // Seen from the centre, the ray passes closest at tClosest, at distance
    // `impact`; the line from the centre to the point at t makes an angle a
    // with tan a = (t - tClosest) / impact with the closest-approach line. The
    // ray parameter after a further turn by b, tan b = k, follows from
    // tan(a + b) = (tan a + k) / (1 - k tan a), exactly and without trigonometry;
    // infinite when the ray never turns that far.
    const float tClosest = -dot(origin - c, d);
    const float impact = length(origin - c + d * tClosest);
    const auto tAfterTurn = [&](float t, float k) {
        const float x = t - tClosest;
        const float denominator = impact - k * x;
        return denominator > 0.0f ? tClosest + impact * (x + k * impact) / denominator : kCdctInfinity;
    };
    const float stepTangent = std::tan(stepAngle);
    const long maxSteps = improvements.texelSteps
                              ? static_cast<long>(kCdctTexelStepsPerSide) * cube.size() + 64
                              : static_cast<long>(std::ceil(2.0 * p.maxDepth / p.step)) + 1;
    // A ray through the centre has no line on the faces to walk along.
    if (improvements.texelSteps && improvements.faceWalk && impact > 1e-6f * (1.0f + length(origin - c)))
        return faceWalk(cube, p, improvements, improvements.skipEmptySpace ? pyramid : nullptr, origin, d, tStart, tEnd,
                        tMaxDepth, 2 * maxSteps);

    struct Sample {
        int texel;
        float distance;  // from the centre
        Vec3 v;          // centre -> point
        CubeCoord coord;
        int x, y;        // texel column and row on coord.face
    };
    int samples = 0;
    const auto sampleAt = [&](float t) {
        ++samples;
        Sample s;
        s.v = origin + d * t - c;
        s.distance = length(s.v);
        // As cubeTexelFromDirection, keeping the face coordinates for the pyramid.
        s.coord = cubeCoordFromDirection(s.v);
        s.x = std::clamp(static_cast<int>(s.coord.s * n), 0, cube.size() - 1);
        s.y = std::clamp(static_cast<int>(s.coord.t * n), 0, cube.size() - 1);
        s.texel = cubeTexelIndex(CubeTexel{s.coord.face, s.x, s.y}, cube.size());
        return s;
    };

    float previous = tStart, t = tStart;
    Sample s = sampleAt(t);
    int found = -1;
    Vec3 foundV;
    for (long step = 0;; ++step) {
        if (!cube.isValid(s.texel)) return {CdctOutcome::Invalid, {}, samples};
        if (cube.depth(s.texel) <= s.distance) {
            // Crossed between `previous` (in front of the stored surface) and t.
            float lo = previous, hi = t;
            int loTexel = -1;
            found = s.texel;
            foundV = s.v;
            for (int k = 0; k < kCdctMaxBinarySteps && hi > lo; ++k) {
                if (improvements.texelSteps ? loTexel == found : hi - lo < p.epsilon) break;
                const float mid = 0.5f * (lo + hi);
                if (!(mid > lo && mid < hi)) break;  // float resolution reached
                const Sample m = sampleAt(mid);
                if (!cube.isValid(m.texel)) return {CdctOutcome::Invalid, {}, samples};
                if (cube.depth(m.texel) <= m.distance) {
                    hi = mid;
                    found = m.texel;
                    foundV = m.v;
                } else {
                    lo = mid;
                    loTexel = m.texel;
                }
            }
            break;
        }
        if (t >= tEnd) {
            // No crossing up to the end: the environment, cached at maxDepth.
            const Sample far = sampleAt(tMaxDepth);
            if (!cube.isValid(far.texel)) return {CdctOutcome::Invalid, {}, samples};
            found = far.texel;
            foundV = far.v;
            break;
        }
        if (step >= maxSteps) return {CdctOutcome::Exhausted, {}, samples};
        previous = t;
        float next = improvements.texelSteps ? tAfterTurn(t, stepTangent) : t + p.step;
        if (pyramid && improvements.skipEmptySpace) {
            // A block all of whose depths exceed the ray's distance, at both
            // ends of a step that stays inside the block, holds no crossing:
            // step to where the ray leaves the block or reaches that depth.
            const int face = static_cast<int>(s.coord.face);
            for (int level = pyramid->levelCount() - 1; level >= 0; --level) {
                const float nearest = pyramid->minDepth(level, face, s.x, s.y);
                if (!(nearest > s.distance)) continue;
                // The sine of the angle to the block's edge is below its tangent: a safe turn.
                const float leaves = tAfterTurn(t, sineToBlockEdge(s.coord, cube.size(), pyramid->blockSide(level)));
                // The finer blocks holding this point lie inside this one, so
                // the ray leaves them no later: once leaving this block
                // limits the step (or cannot lengthen it), none of them can
                // take it farther.
                if (leaves <= next) break;
                const float reaches = rayParameterAtDistance(c, origin, d, nearest);
                next = std::max(next, std::min(leaves, reaches));
                if (leaves <= reaches) break;
            }
        }
        t = std::min(tEnd, std::max(next, t + 1e-6f * (1.0f + t)));
        s = sampleAt(t);
    }

    return answerAt(cube, p, improvements, found, foundV, origin, d, samples);
}

}  // namespace raycache
