#include "trace/grids/GridAccelerator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "core/Elapsed.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

// The largest coordinate magnitude of the scene's geometry, camera and
// lights: the scale the grids' margins and near planes are set against.
double worldScaleOf(const Scene& scene, const Camera& camera) {
    double scale = 1.0;
    auto grow = [&](const Vec3& p) {
        scale = std::max({scale, static_cast<double>(std::fabs(p.x)), static_cast<double>(std::fabs(p.y)),
                          static_cast<double>(std::fabs(p.z))});
    };
    grow(camera.position);
    for (const Light& light : scene.lights) grow(light.position);
    for (const SceneObject& object : scene.objects) {
        if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
            grow(sphere->center + Vec3{sphere->radius, sphere->radius, sphere->radius});
            grow(sphere->center - Vec3{sphere->radius, sphere->radius, sphere->radius});
        } else {
            for (const Vec3& p : std::get<MeshShape>(object.shape).mesh->positions) grow(p);
        }
    }
    return scale;
}

constexpr double kDegrees = std::numbers::pi / 180.0;
// Fractions of the world's scale (its largest coordinate): every grid's
// positional margin, and where perspective grids start their slices.
constexpr double kMarginOfScale = 1e-5;
constexpr double kNearOfScale = 1e-3;
// Shadow rays start a surface offset off the hit (render/LocalShading.cpp)
// and end that far from a point light: light grids are padded by twice it.
constexpr double kShadowPadOfScale = 2e-4;

}  // namespace

GridFrameStats GridAccelerator::buildFrame(const Scene& scene, const Camera& camera, int width, int height,
                                           const Parallel& parallel) {
    GridFrameStats stats;
    auto start = Clock::now();
    if (!primitives_) primitives_ = std::make_unique<GridPrimitives>();
    primitives_->rebuild(scene, parallel);
    stats.primitives = primitives_->count();
    worldScale_ = worldScaleOf(scene, camera);

    // The camera grid: the image plane at distance 1, as render/CameraRays.h spans it.
    FrustumGridSpec spec;
    spec.frame = makeGridFrame(camera.position, camera.lookAt - camera.position, camera.up, GridMapping::Perspective);
    const double tanHalf = std::tan(0.5 * camera.verticalFovDeg * kDegrees);
    const double aspect = static_cast<double>(width) / height;
    // A little wider than the image, so pixel-centre rays never touch the edge.
    spec.s1 = tanHalf * aspect * 1.001;
    spec.s0 = -spec.s1;
    spec.t1 = tanHalf * 1.001;
    spec.t0 = -spec.t1;
    spec.margin = kMarginOfScale * worldScale_;
    spec.zNear = kNearOfScale * worldScale_;
    // Camera rays start at the apex: before zNear they stay in the frustum's tip.
    spec.nearZone = {{spec.s0 * spec.zNear, spec.t0 * spec.zNear, -spec.margin},
                     {spec.s1 * spec.zNear, spec.t1 * spec.zNear, spec.zNear}};
    spec.nx = std::max(1, (width + settings_.pixelsPerColumn - 1) / settings_.pixelsPerColumn);
    spec.ny = std::max(1, (height + settings_.pixelsPerColumn - 1) / settings_.pixelsPerColumn);
    spec.maxSlices = settings_.maxSlices;
    spec.cellsPerPrimitive = settings_.cellsPerPrimitive;
    camera_.build(spec, *primitives_, parallel);
    stats.primaryPairs = camera_.stats().pairs;
    stats.primaryNearZone = camera_.stats().nearZone;
    stats.primaryBuildMs = millisecondsSince(start);

    // What the camera can see: the corners of every column's occupied
    // slices. Shadow-ray origins (primary hits) lie inside their hull.
    start = Clock::now();
    const std::vector<Vec3> visible = camera_.occupiedColumnCorners();
    lights_.resize(scene.lights.size());
    lightPositions_.clear();
    for (const Light& light : scene.lights) lightPositions_.push_back(light.position);
    for (std::size_t l = 0; l < scene.lights.size(); ++l) buildLightGrid(scene.lights[l], l, visible, parallel, stats);
    stats.shadowBuildMs = millisecondsSince(start);
    return stats;
}

namespace {

// Spot and point lights: an angular grid around `forward`, its rectangle the
// box of the visible corners' azimuth and elevation (or `fixedHalfAngle`
// around the axis when set), its depth up to the farthest of them.
FrustumGridSpec angularSpec(const Light& light, const Vec3& forward, const std::vector<Vec3>& visible,
                            double fixedHalfAngle, double pad, double worldScale) {
    FrustumGridSpec spec;
    spec.frame = makeGridFrame(light.position, forward, Vec3{0.0f, 1.0f, 0.0f}, GridMapping::Angular);
    double sLo = 1e300, sHi = -1e300, tLo = 1e300, tHi = -1e300, zMax = -1e300;
    // In front of the light (z > 0: every corner, when one rectangle holds
    // them) atan2(x, z) = atan(x / z) rises with x / z: the box is taken on
    // the ratios, and only its ends are turned into angles.
    double ratioXLo = 1e300, ratioXHi = -1e300, ratioYLo = 1e300, ratioYHi = -1e300;
    for (const Vec3& p : visible) {
        const Point3d q = spec.frame.toFrame(p);
        zMax = std::max(zMax, q.z);
        if (fixedHalfAngle > 0.0) continue;
        if (q.z > 0.0) {
            const double inverseZ = 1.0 / q.z;
            ratioXLo = std::min(ratioXLo, q.x * inverseZ);
            ratioXHi = std::max(ratioXHi, q.x * inverseZ);
            ratioYLo = std::min(ratioYLo, q.y * inverseZ);
            ratioYHi = std::max(ratioYHi, q.y * inverseZ);
        } else {
            sLo = std::min(sLo, std::atan2(q.x, q.z));
            sHi = std::max(sHi, std::atan2(q.x, q.z));
            tLo = std::min(tLo, std::atan2(q.y, q.z));
            tHi = std::max(tHi, std::atan2(q.y, q.z));
        }
    }
    if (ratioXLo <= ratioXHi) {
        sLo = std::min(sLo, std::atan(ratioXLo));
        sHi = std::max(sHi, std::atan(ratioXHi));
        tLo = std::min(tLo, std::atan(ratioYLo));
        tHi = std::max(tHi, std::atan(ratioYHi));
    }
    if (fixedHalfAngle > 0.0) {
        sLo = tLo = -fixedHalfAngle;
        sHi = tHi = fixedHalfAngle;
    }
    const double widen = 1e-3 * std::max(sHi - sLo, tHi - tLo) + 1e-6;
    spec.s0 = sLo - widen;
    spec.s1 = sHi + widen;
    spec.t0 = tLo - widen;
    spec.t1 = tHi + widen;
    spec.zNear = kNearOfScale * worldScale;
    // Shadow rays end at the light: inside the rectangle's pyramid up to
    // zNear, give or take the surface offset.
    const double uLo = std::min(0.0, std::tan(spec.s0)), uHi = std::max(0.0, std::tan(spec.s1));
    const double vLo = std::min(0.0, std::tan(spec.t0)), vHi = std::max(0.0, std::tan(spec.t1));
    spec.nearZone = {{uLo * spec.zNear - pad, vLo * spec.zNear - pad, -pad},
                     {uHi * spec.zNear + pad, vHi * spec.zNear + pad, spec.zNear}};
    spec.zFarLimit = zMax + pad;
    return spec;
}

// Which of the six axis faces (+x, -x, +y, -y, +z, -z) a direction falls in.
int faceOf(const Vec3& d) {
    const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    if (ax >= ay && ax >= az) return d.x >= 0.0f ? 0 : 1;
    if (ay >= az) return d.y >= 0.0f ? 2 : 3;
    return d.z >= 0.0f ? 4 : 5;
}

const Vec3 kFaceAxes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
// A face grid's rectangle spans ±kFaceHalfAngle (45° + 0.01 rad), which
// angularSpec widens by 0.1 %: a tangent of 1.0205. Primitives are culled
// against a wider pyramid; the two constants go together.
constexpr double kFaceHalfAngle = 0.25 * std::numbers::pi + 0.01;
constexpr double kFaceCullTangent = 1.05;

// Which of a light's six face grids each primitive may meet: bit f for
// kFaceAxes[f]. A face grid answers only rays inside its rectangle's
// pyramid around the light or inside its near zone (the pyramid's tip,
// padded); a primitive that lies wholly beyond one side of the wider
// pyramid (every corner beyond it by `slack`, so one plane separates them)
// and away from the light's neighbourhood cannot be met by them, and that
// face's grid need not bin it. Without this, each of the six grids bins
// every primitive of the scene.
void faceCandidates(const GridPrimitives& primitives, const Vec3& light, double slack, double nearRadius,
                    const Parallel& parallel, std::vector<std::uint8_t>& masks) {
    masks.resize(primitives.count());
    // Inside face +x: x >= k |y| and x >= k |z|. The side planes' normals
    // (1, ±k) are shorter than 1.5, so 1.5 slack in value is slack in distance.
    const double k = 1.0 / kFaceCullTangent, beyond = -1.5 * slack;
    constexpr std::uint32_t kBlock = 16384;
    const int blocks = static_cast<int>((primitives.count() + kBlock - 1) / kBlock);
    parallel.forEachIndex(blocks, [&](int b, int) {
        const std::uint32_t begin = static_cast<std::uint32_t>(b) * kBlock;
        const std::uint32_t end = std::min(primitives.count(), begin + kBlock);
        for (std::uint32_t p = begin; p < end; ++p) {
            // The corners relative to the light: a triangle's three or a sphere's box's eight.
            double corners[8][3];
            int count = 0;
            if (const Sphere* sphere = primitives.sphere(p)) {
                for (int c = 0; c < 8; ++c, ++count) {
                    corners[c][0] = sphere->center.x + ((c & 1) ? sphere->radius : -sphere->radius) - light.x;
                    corners[c][1] = sphere->center.y + ((c & 2) ? sphere->radius : -sphere->radius) - light.y;
                    corners[c][2] = sphere->center.z + ((c & 4) ? sphere->radius : -sphere->radius) - light.z;
                }
            } else {
                const GridPrimitives::TriangleCoordinates& t = primitives.triangleCoordinates(p);
                for (int c = 0; c < 3; ++c, ++count)
                    for (int axis = 0; axis < 3; ++axis)
                        corners[c][axis] = static_cast<double>(t[static_cast<std::size_t>(3 * c + axis)]) -
                                           static_cast<double>(light[axis]);
            }
            // Near the light every face's near zone may reach it.
            bool nearLight = true;
            for (int axis = 0; axis < 3 && nearLight; ++axis) {
                double lo = corners[0][axis], hi = corners[0][axis];
                for (int c = 1; c < count; ++c) {
                    lo = std::min(lo, corners[c][axis]);
                    hi = std::max(hi, corners[c][axis]);
                }
                nearLight = lo <= nearRadius && hi >= -nearRadius;
            }
            std::uint8_t mask = 0;
            for (int face = 0; face < 6; ++face) {
                const int axis = face / 2, v = (axis + 1) % 3, w = (axis + 2) % 3;
                const double sign = (face & 1) ? -1.0 : 1.0;
                bool separated = false;
                for (int side = 0; side < 4 && !separated; ++side) {
                    const int across = side < 2 ? v : w;
                    const double slope = (side & 1) ? k : -k;
                    separated = true;
                    for (int c = 0; c < count && separated; ++c)
                        separated = sign * corners[c][axis] + slope * corners[c][across] < beyond;
                }
                if (nearLight || !separated) mask = static_cast<std::uint8_t>(mask | (1u << face));
            }
            masks[p] = mask;
        }
    });
}

}  // namespace

void GridAccelerator::buildLightGrid(const Light& light, std::size_t index, const std::vector<Vec3>& visible,
                                     const Parallel& parallel, GridFrameStats& stats) {
    LightGrids& grids = lights_[index];
    // Last frame's grids are rebuilt in place: their arrays keep their memory.
    for (std::unique_ptr<FrustumGrid>& grid : grids.grids)
        if (grid) grids.spare.push_back(std::move(grid));
    grids.grids.clear();
    grids.faces = false;
    if (visible.empty()) return;
    const double pad = kShadowPadOfScale * worldScale_;
    std::vector<FrustumGridSpec> specs;
    if (light.type == LightType::Directional) {
        FrustumGridSpec spec;
        spec.frame = makeGridFrame(Vec3{0.0f, 0.0f, 0.0f}, light.direction, Vec3{0.0f, 1.0f, 0.0f},
                                   GridMapping::Orthographic);
        double sLo = 1e300, sHi = -1e300, tLo = 1e300, tHi = -1e300, zMax = -1e300;
        for (const Vec3& p : visible) {
            const Point3d q = spec.frame.toFrame(p);
            sLo = std::min(sLo, q.x);
            sHi = std::max(sHi, q.x);
            tLo = std::min(tLo, q.y);
            tHi = std::max(tHi, q.y);
            zMax = std::max(zMax, q.z);
        }
        spec.s0 = sLo - pad;
        spec.s1 = sHi + pad;
        spec.t0 = tLo - pad;
        spec.t1 = tHi + pad;
        spec.zFarLimit = zMax + pad;
        specs.push_back(spec);
    } else {
        // One grid around the spot's axis, or around the mean direction of
        // what is seen; when what must be covered strays too far from that
        // axis (a light among the geometry), six grids, one per axis face.
        Vec3 forward = light.direction;
        if (light.type == LightType::Point) {
            Point3d sum;
            for (const Vec3& p : visible) {
                const double dx = p.x - light.position.x, dy = p.y - light.position.y, dz = p.z - light.position.z;
                const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
                if (length <= 0.0) continue;
                sum = {sum.x + dx / length, sum.y + dy / length, sum.z + dz / length};
            }
            forward = Vec3{static_cast<float>(sum.x), static_cast<float>(sum.y), static_cast<float>(sum.z)};
        }
        const double minCos = std::cos(settings_.maxLightHalfAngleDeg * kDegrees);
        const bool spot = light.type == LightType::Spot;
        const double cone = light.coneAngleDeg * kDegrees;
        bool fits = dot(forward, forward) > 1e-12f && (!spot || cone < settings_.maxLightHalfAngleDeg * kDegrees);
        bool outsideCone = false;
        if (fits) {
            const GridFrame frame = makeGridFrame(light.position, forward, Vec3{0.0f, 1.0f, 0.0f}, GridMapping::Angular);
            for (const Vec3& p : visible) {
                const Point3d q = frame.toFrame(p);
                const double length = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
                if (spot && q.z < std::cos(cone) * length) outsideCone = true;
                else if (q.z < minCos * length) fits = false;
            }
        }
        if (fits) {
            // A spot lights nothing outside its cone; when the seen region
            // reaches past it, the cone's square bounds the rectangle.
            specs.push_back(angularSpec(light, forward, visible, outsideCone ? cone : 0.0, pad, worldScale_));
        } else {
            grids.faces = true;
            ++stats.lightsWithSixFaces;
            // Shadow rays end at the light give or take `pad`; a face's near
            // zone reaches 1.0205 zNear + pad from it sideways and zNear ahead.
            const double zNear = kNearOfScale * worldScale_, margin = kMarginOfScale * worldScale_;
            faceCandidates(*primitives_, light.position, 2.0 * (pad + margin), 2.0 * (zNear + pad) + margin, parallel,
                           faceMasks_);
            for (const Vec3& axis : kFaceAxes)
                specs.push_back(angularSpec(light, axis, visible, kFaceHalfAngle, pad, worldScale_));
        }
    }
    for (FrustumGridSpec& spec : specs) {
        spec.margin = kMarginOfScale * worldScale_;
        spec.maxSlices = settings_.maxSlices;
        spec.cellsPerPrimitive = settings_.cellsPerPrimitive;
        spec.nx = camera_.spec().nx;
        spec.ny = camera_.spec().ny;
        spec.refineAboveSlices = settings_.lightRefineAboveSlices;
        // A face nothing visible lies in front of holds no ray origin.
        if (spec.zFarLimit <= 0.0 && spec.frame.perspective()) {
            grids.grids.emplace_back();
            continue;
        }
        std::unique_ptr<FrustumGrid> grid;
        if (grids.spare.empty()) {
            grid = std::make_unique<FrustumGrid>();
        } else {
            grid = std::move(grids.spare.back());
            grids.spare.pop_back();
        }
        grid->build(spec, *primitives_, parallel,
                    grids.faces ? PrimitiveFilter{faceMasks_, static_cast<std::uint8_t>(1u << grids.grids.size())}
                                : PrimitiveFilter{});
        stats.shadowPairs += grid->stats().pairs;
        ++stats.lightGrids;
        grids.grids.push_back(std::move(grid));
    }
}

const FrustumGrid* GridAccelerator::lightGridFor(const Ray& ray, int light, int& face) const {
    face = 0;
    if (light < 0 || static_cast<std::size_t>(light) >= lights_.size()) return nullptr;
    const LightGrids& grids = lights_[static_cast<std::size_t>(light)];
    if (grids.grids.empty()) return nullptr;
    if (grids.faces) face = faceOf(ray.origin - lightPositions_[static_cast<std::size_t>(light)]);
    return grids.grids[static_cast<std::size_t>(face)].get();
}

bool GridAccelerator::occludedShadow(const Ray& ray, int light, bool& blocked) const {
    int face = 0;
    const FrustumGrid* grid = lightGridFor(ray, light, face);
    return grid && grid->occluded(ray, blocked);
}

void GridAccelerator::occludedShadowBatch(std::span<const Ray> rays, int light, std::span<unsigned char> blocked,
                                          std::span<unsigned char> refused) const {
    // Runs of rays that go to the same grid (a point light's six faces
    // split them), each run answered as one batch.
    for (std::size_t begin = 0; begin < rays.size();) {
        int face = 0;
        const FrustumGrid* grid = lightGridFor(rays[begin], light, face);
        std::size_t end = begin + 1;
        for (int next = 0; end < rays.size() && lightGridFor(rays[end], light, next) == grid; ++end) {
        }
        if (grid) {
            grid->occludedBatch(rays.subspan(begin, end - begin), blocked.subspan(begin, end - begin),
                                refused.subspan(begin, end - begin));
        } else {
            std::fill(blocked.begin() + static_cast<std::ptrdiff_t>(begin), blocked.begin() + static_cast<std::ptrdiff_t>(end), 0);
            std::fill(refused.begin() + static_cast<std::ptrdiff_t>(begin), refused.begin() + static_cast<std::ptrdiff_t>(end), 1);
        }
        begin = end;
    }
}

}  // namespace raycache
