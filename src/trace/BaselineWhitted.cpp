#include "trace/BaselineWhitted.h"

#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>
#include <numbers>
#include <string>

#include "trace/EmbreeDeviceConfig.h"

namespace raycache {

namespace {

struct BaselineContext {
    const Scene& scene;
    RTCScene rtcScene;
    int maxDepth;
};

Rgb traceBaseline(const BaselineContext& ctx, const Vec3& origin, const Vec3& dir, int depth,
                  std::uint64_t& rays) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.dir_x = dir.x;
    rh.ray.dir_y = dir.y;
    rh.ray.dir_z = dir.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(ctx.rtcScene, &context, &rh);
    ++rays;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return ctx.scene.environment.lookup(dir);

    const SceneObject& object = ctx.scene.objects[rh.hit.geomID];
    const Vec3 p = origin + dir * rh.ray.tfar;
    Vec3 n = normalize(Vec3{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
    if (dot(n, dir) > 0.0f) n = -n;
    const Vec3 lifted = p + n * 1e-3f;
    const Material& m = object.material;
    Rgb color = m.ambient * m.diffuse;
    for (const Light& light : ctx.scene.lights) {
        const Vec3 d = light.type == LightType::Directional ? -light.direction * 1e6f : light.position - p;
        const float dist = length(d);
        const Vec3 l = d / dist;
        const float nDotL = dot(n, l);
        if (nDotL <= 0.0f) continue;
        RTCRay shadow{};
        shadow.org_x = lifted.x;
        shadow.org_y = lifted.y;
        shadow.org_z = lifted.z;
        shadow.dir_x = l.x;
        shadow.dir_y = l.y;
        shadow.dir_z = l.z;
        shadow.tnear = 0.0f;
        shadow.tfar = dist;
        shadow.mask = 0xFFFFFFFFu;
        rtcOccluded1(ctx.rtcScene, &context, &shadow);
        ++rays;
        if (shadow.tfar >= 0.0f) color += m.diffuse * light.intensity * nDotL;
    }
    if (m.reflectivity > 0.0f && depth < ctx.maxDepth) {
        const Vec3 r = dir - n * (2.0f * dot(dir, n));
        color += traceBaseline(ctx, lifted, r, depth + 1, rays) * m.reflectivity;
    }
    return color;
}

}  // namespace

struct BaselineWhitted::Impl {
    const Scene& scene;
    RTCDevice device = nullptr;  // only when the baseline owns its scene
    RTCScene rtcScene = nullptr;

    ~Impl() {
        if (device) {
            rtcReleaseScene(rtcScene);
            rtcReleaseDevice(device);
        }
    }
};

BaselineWhitted::BaselineWhitted(const Scene& scene, const TraceScene* shared)
    : impl_(new Impl{scene}) {
    if (shared) {
        impl_->rtcScene = static_cast<RTCScene>(shared->embreeScene());
        return;
    }
    const std::string config = embreeDeviceConfig(0);
    impl_->device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    impl_->rtcScene = rtcNewScene(impl_->device);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        RTCGeometry geom;
        if (const auto* sphere = std::get_if<Sphere>(&scene.objects[i].shape)) {
            geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
            auto* v = static_cast<float*>(
                rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
            v[0] = sphere->center.x;
            v[1] = sphere->center.y;
            v[2] = sphere->center.z;
            v[3] = sphere->radius;
        } else {
            const TriangleMesh& mesh = *std::get<MeshShape>(scene.objects[i].shape).mesh;
            geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                  3 * sizeof(float), mesh.positions.size()));
            for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
                v[3 * k] = mesh.positions[k].x;
                v[3 * k + 1] = mesh.positions[k].y;
                v[3 * k + 2] = mesh.positions[k].z;
            }
            auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
                geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
            for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
                for (int c = 0; c < 3; ++c) idx[3 * k + static_cast<std::size_t>(c)] = mesh.triangles[k][static_cast<std::size_t>(c)];
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(impl_->rtcScene, geom, static_cast<unsigned>(i));
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(impl_->rtcScene);
}

BaselineWhitted::~BaselineWhitted() = default;

std::uint64_t BaselineWhitted::render(const Parallel& parallel, int maxDepth, Image& film) const {
    const Scene& scene = impl_->scene;
    const BaselineContext ctx{scene, impl_->rtcScene, maxDepth};
    const Camera& cam = scene.camera;
    const float tanHalf = std::tan(0.5f * cam.verticalFovDeg * std::numbers::pi_v<float> / 180.0f);
    const float aspect = static_cast<float>(film.width()) / static_cast<float>(film.height());
    const Vec3 forward = normalize(cam.lookAt - cam.position);
    const Vec3 right = normalize(cross(forward, cam.up));
    const Vec3 up = cross(right, forward);
    std::atomic<std::uint64_t> total{0};
    parallel.forEachTile(film.width(), film.height(), 16, [&](const TileRange& tile, int) {
        std::uint64_t rays = 0;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const float sx = (2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(film.width()) - 1.0f);
                const float sy = (1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(film.height()));
                const Vec3 d = normalize(forward + right * (sx * tanHalf * aspect) + up * (sy * tanHalf));
                film.at(x, y) = traceBaseline(ctx, cam.position, d, 1, rays);
            }
        total += rays;
    });
    return total.load();
}

}  // namespace raycache
