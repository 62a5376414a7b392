#include "render/PacketGBuffer.h"

#include <vector>

#include "render/CameraRays.h"
#include "render/SurfacePoint.h"

namespace raycache {

PacketGBuffer::PacketGBuffer(const Scene& scene, const TraceScene& tracer, const Parallel& parallel, int tileSize)
    : scene_(scene), tracer_(tracer), parallel_(parallel), tileSize_(tileSize) {}

std::uint64_t PacketGBuffer::fill(const Camera& camera, int width, int height, GBufferStorage& out) const {
    out.resize(width, height);
    const CameraRays cameraRays(camera, width, height);
    const auto tilePixels = static_cast<std::size_t>(tileSize_) * static_cast<std::size_t>(tileSize_);
    struct Scratch {
        std::vector<Ray> rays;
        std::vector<TraceHit> hits;
    };
    std::vector<Scratch> scratch(static_cast<std::size_t>(parallel_.threadCount()),
                                 Scratch{std::vector<Ray>(tilePixels), std::vector<TraceHit>(tilePixels)});
    parallel_.forEachTile(width, height, tileSize_, [&](const TileRange& tile, int worker) {
        Scratch& s = scratch[static_cast<std::size_t>(worker)];
        std::size_t n = 0;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) s.rays[n++] = cameraRays.ray(x, y);
        tracer_.intersectPrimary(std::span<const Ray>(s.rays.data(), n), std::span(s.hits.data(), n));
        const int tileWidth = tile.x1 - tile.x0;
        for (std::size_t k = 0; k < n; ++k) {
            const int x = tile.x0 + static_cast<int>(k) % tileWidth;
            const int y = tile.y0 + static_cast<int>(k) / tileWidth;
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x);
            const TraceHit& hit = s.hits[k];
            float* pd = &out.positionDepth[4 * i];
            if (!hit.hit()) {
                pd[3] = -1.0f;
                out.ids[2 * i] = -1;
                out.ids[2 * i + 1] = -1;
                continue;
            }
            const SceneObject& object = scene_.objects[static_cast<std::size_t>(hit.objectId)];
            const Material& material = object.material;
            const SurfacePoint sp = surfacePointAt(object, s.rays[k], hit, material.diffuseTexture.has_value());
            // The G-buffer holds the outward normal; the deferred pass turns it to the viewer.
            const Vec3 outward = sp.frontFace ? sp.normal : -sp.normal;
            const Rgb albedo = material.albedo(sp.u, sp.v);
            pd[0] = sp.position.x;
            pd[1] = sp.position.y;
            pd[2] = sp.position.z;
            pd[3] = hit.t;
            float* nn = &out.normal[4 * i];
            nn[0] = outward.x;
            nn[1] = outward.y;
            nn[2] = outward.z;
            nn[3] = 0.0f;
            float* a = &out.albedo[4 * i];
            a[0] = albedo.r;
            a[1] = albedo.g;
            a[2] = albedo.b;
            a[3] = 1.0f;
            out.ids[2 * i] = hit.objectId;
            out.ids[2 * i + 1] = hit.primitiveId;
        }
    });
    return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
}

}  // namespace raycache
