// cct_minimal: the smallest tracer loop of its own that puts CCT (per-object
// caching cubes, cache/RayCache.h) in: one ray per pixel through a pinhole
// camera, Lambert shading with one shadow ray toward the first light, and
// mirror reflections answered by the mirror's caching cube when an earlier
// frame already traced them. Single-threaded (one CacheWorker); no refraction.
//
// Usage: cct_minimal [width height frames out.png]. Prints one parseable line
// per frame ("frame 3/3 lookups 120 hits 97 hit_rate 0.8083"), writes the last.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "cache/RayCache.h"
#include "core/Errors.h"
#include "core/Optics.h"
#include "render/ImageWriter.h"
#include "render/SurfacePoint.h"
#include "scene/BuiltinScenes.h"
#include "trace/TraceScene.h"

using namespace raycache;

namespace {

constexpr int kMaxDepth = 4;             // rays on a path, the primary ray being 1
constexpr float kSurfaceOffset = 1e-3f;  // lifts spawned rays off the surface they leave
// Coarser than the built-in scenes' 512: a small image sends few rays per
// frame, and they only meet earlier frames' rays in texels this large.
constexpr int kCacheResolution = 64;

// Ray through the centre of pixel (x, y), y = 0 at the top.
Ray pinholeRay(const Camera& camera, int x, int y, int width, int height) {
    const Vec3 forward = normalize(camera.lookAt - camera.position);
    const Vec3 right = normalize(cross(forward, camera.up));
    const float halfHeight = std::tan(camera.verticalFovDeg * 3.14159265f / 360.0f);
    const float sx = (2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f) * halfHeight *
                     static_cast<float>(width) / static_cast<float>(height);
    const float sy = (1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height)) * halfHeight;
    return Ray{camera.position, normalize(forward + right * sx + cross(right, forward) * sy)};
}

// The whole tracer: plain references to what it reads.
struct MiniTracer {
    const Scene& scene;
    const TraceScene& tracer;
    const RayCache& cache;

    // Color arriving along `ray`; `distance`, if given, receives the distance to its first hit.
    Rgb trace(const Ray& ray, int depth, CacheWorker& worker, float* distance = nullptr) const {
        const TraceHit hit = tracer.intersect(ray);
        if (distance) *distance = hit.hit() ? hit.t : std::numeric_limits<float>::infinity();
        if (!hit.hit()) return scene.environment.lookup(ray.direction);
        const SceneObject& object = scene.objects[static_cast<std::size_t>(hit.objectId)];
        const Material& m = object.material;
        const SurfacePoint sp = surfacePointAt(object, ray, hit, m.diffuseTexture.has_value());
        const Vec3 lifted = sp.position + sp.geometricNormal * kSurfaceOffset;
        const Rgb albedo = m.albedo(sp.u, sp.v);
        Rgb color = m.ambient * albedo;
        if (!scene.lights.empty()) {  // the first light, taken as a point light
            const Vec3 toLight = scene.lights.front().position - sp.position;
            const Vec3 l = normalize(toLight);
            if (dot(sp.normal, l) > 0.0f && !tracer.occluded(Ray{lifted, l, 0.0f, length(toLight)}))
                color += albedo * scene.lights.front().intensity * dot(sp.normal, l);
        }
        if (m.reflects() && depth < kMaxDepth) {
            const Ray r{lifted, normalize(reflect(ray.direction, sp.normal))};
            color += reflected(hit.objectId, r, depth + 1, worker) * m.reflectivity;
        }
        return color;
    }

    // The reflected ray leaving object `objectId`: from its cube when the
    // texel is valid, else traced and offered to the cube.
    Rgb reflected(int objectId, const Ray& ray, int depth, CacheWorker& worker) const {
        if (!cache.cachesObject(objectId)) return trace(ray, depth, worker);
        if (const auto cached = cache.lookup(objectId, ray.origin, ray.direction, worker)) return *cached;
        float distance = 0.0f;
        const Rgb color = trace(ray, depth, worker, &distance);
        cache.store(objectId, ray.origin, ray.direction, color, distance, worker);
        return color;
    }
};

void run(int width, int height, int frames, const std::string& outPath) {
    // Like `raycache render`: the output's directory is created if need be.
    if (const auto parent = std::filesystem::path(outPath).parent_path(); !parent.empty())
        std::filesystem::create_directories(parent);
    checkWritableImagePath(outPath);
    const Scene scene = *makeBuiltinScene("behind-8");
    const TraceScene tracer(scene);
    // Named members: a positional list silently shifts when RayCacheSettings gains a field
    // (an old `false` meant for `ideal` had landed in cdctStepOverride).
    RayCache cache(scene,
                   RayCacheSettings{.techniqueOverride = CacheTechnique::Cct, .resolutionOverride = kCacheResolution});
    std::vector<CacheWorker> workers = cache.makeWorkers(1);
    const MiniTracer mini{scene, tracer, cache};
    Image image(width, height);
    for (int frame = 0; frame < frames; ++frame) {
        const Camera camera = scene.cameraPath.cameraAt(scene.camera, frame);
        cache.beginFrame(workers);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                workers[0].beginBatch(static_cast<std::uint32_t>(y * width + x));
                image.at(x, y) = mini.trace(pinholeRay(camera, x, y, width, height), 1, workers[0]);
            }
        const FrameCacheStats s = cache.endFrame(workers);
        std::printf("frame %d/%d lookups %llu hits %llu hit_rate %.4f\n", frame + 1, frames,
                    static_cast<unsigned long long>(s.lookups()), static_cast<unsigned long long>(s.hits()),
                    s.lookups() ? static_cast<double>(s.hits()) / static_cast<double>(s.lookups()) : 0.0);
    }
    writeImage(image, outPath);
}

}  // namespace

int main(int argc, char** argv) {
    try {
        if (argc != 1 && argc != 5) throw InputError("usage: cct_minimal [width height frames out.png]");
        const auto arg = [&](int i, int fallback) { return argc == 5 ? std::atoi(argv[i]) : fallback; };
        const int width = arg(1, 256), height = arg(2, 256), frames = arg(3, 10);
        if (width < 1 || height < 1 || frames < 1) throw InputError("width, height and frames must be positive");
        run(width, height, frames, argc == 5 ? argv[4] : "cct_minimal.png");
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << '\n';
        return dynamic_cast<const InputError*>(&e) ? 2 : 1;  // bad input : failure while running
    }
}
