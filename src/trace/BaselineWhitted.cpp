#include "trace/BaselineWhitted.h"

#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>
#include <numbers>

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

std::uint64_t renderBaselineWhitted(const Scene& scene, const TraceScene& tracer, const Parallel& parallel,
                                    int maxDepth, Image& film) {
    const BaselineContext ctx{scene, static_cast<RTCScene>(tracer.embreeScene()), maxDepth};
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
