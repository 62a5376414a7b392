// The first bounce of a camera tile with the wave in lanes
// (TileKernel::shadeCameraHitsInLanes, RenderSettings::firstBounceLanes):
// the tracer's packets stay the wave's records. Each row of the tile is one
// packet of sixteen pixels; each stage runs over the tile's packets before
// the next, as the general path's stages run over its records. Where a
// packet's lanes hit several objects, each stage takes one object at a time
// under a mask, so that a material and a sphere are read once per packet,
// not once per hit. What each lane computes is the general path's
// arithmetic, operation for operation (render/HitLanes.h), so the image is
// the same bit for bit.
#include <algorithm>
#include <cstring>

#include "core/FloatLanes.h"
#include "render/StageTimer.h"
#include "render/TileKernel.h"

namespace raycache {

namespace {

// Selects, among the lanes `remaining` still holds, those of the object of
// the first one; removes them from `remaining`. Returns that object, or -1
// when no lane remains.
int takeObjectLanes(const int* objectId, int* remaining, int* selected) {
    int object = -1;
    for (int k = 0; k < kFloatLanes; ++k)
        if (remaining[k]) {
            object = objectId[k];
            break;
        }
    for (int k = 0; k < kFloatLanes; ++k) {
        selected[k] = remaining[k] && objectId[k] == object ? -1 : 0;
        if (selected[k]) remaining[k] = 0;
    }
    return object;
}

Ray laneRay(const RayLanes16& rays, int k) {
    return Ray{{rays.originX[k], rays.originY[k], rays.originZ[k]},
               {rays.directionX[k], rays.directionY[k], rays.directionZ[k]}};
}

TraceHit laneHit(const RayHitLanes16& packet, const int* objectId, int k) {
    TraceHit hit;
    hit.t = packet.ray.tFar[k];
    hit.objectId = objectId[k];
    hit.primitiveId = static_cast<int>(packet.hit.primitiveId[k]);
    hit.u = packet.hit.u[k];
    hit.v = packet.hit.v[k];
    return hit;
}

void setLaneSurface(SurfaceLanes16& s, int k, const SurfacePoint& sp) {
    s.positionX[k] = sp.position.x, s.positionY[k] = sp.position.y, s.positionZ[k] = sp.position.z;
    s.normalX[k] = sp.normal.x, s.normalY[k] = sp.normal.y, s.normalZ[k] = sp.normal.z;
    s.geometricX[k] = sp.geometricNormal.x, s.geometricY[k] = sp.geometricNormal.y;
    s.geometricZ[k] = sp.geometricNormal.z;
    s.u[k] = sp.u;
    s.v[k] = sp.v;
    s.frontFace[k] = sp.frontFace ? 1 : 0;
}

}  // namespace

bool TileKernel::shadesCameraHitsInLanes() const {
    return settings_.firstBounceLanes && tracer_.accelerator() == Accelerator::Embree;
}

void TileKernel::shadeCameraHitsInLanes(const CameraRays& cameraRays, const TileRange& tile, TileScratch& s,
                                        CacheWorker* cache) const {
    const int tileWidth = tile.x1 - tile.x0;
    const std::size_t lights = scene_.lights.size();
    // One packet per sixteen pixels of a row.
    const int packetsPerRow = (tileWidth + kFloatLanes - 1) / kFloatLanes;
    const auto packets = static_cast<std::size_t>(packetsPerRow) * static_cast<std::size_t>(tile.y1 - tile.y0);
    s.cameraPackets.resize(packets);
    s.cameraLights.resize(packets * lights);
    std::uint64_t hits = 0;
    {
        StageTimer timer(settings_.stageTimes, s.stages.firstHits);
        std::size_t p = 0;
        int root = 0;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; x += kFloatLanes, ++p) {
                TileScratch::CameraPacket& packet = s.cameraPackets[p];
                packet.count = std::min(kFloatLanes, tile.x1 - x);
                packet.firstRoot = root;
                root += packet.count;
                cameraRays.rowOfRays(x, y, packet.rays.ray);
                PacketLanes traced;
                for (int k = 0; k < kFloatLanes; ++k) traced.valid[k] = k < packet.count ? -1 : 0;
                tracer_.intersectPacket(packet.rays, traced, packet.objectId);
                s.counts.primary += static_cast<std::uint64_t>(packet.count);
                for (int k = 0; k < kFloatLanes; ++k) {
                    const bool hit = k < packet.count && packet.objectId[k] >= 0;
                    packet.hits.valid[k] = hit ? -1 : 0;
                    if (k >= packet.count) continue;
                    const auto node = static_cast<std::size_t>(packet.firstRoot + k);
                    if (!hit) {
                        s.nodes[node].direct = shading_.background(laneRay(packet.rays.ray, k));
                        continue;
                    }
                    ++hits;
                    if (cache && fill_.active()) {
                        const Ray ray = laneRay(packet.rays.ray, k);
                        noteVisiblePoint(s, static_cast<int>(node), packet.objectId[k],
                                         ray.origin + ray.direction * packet.rays.ray.tFar[k]);
                    }
                }
            }
    }
    s.stages.hitsShaded += hits;
    {
        StageTimer timer(settings_.stageTimes, s.stages.surfaces);
        for (TileScratch::CameraPacket& packet : s.cameraPackets) cameraPacketSurfaces(packet, s.cameraMeshLanes);
    }
    {
        StageTimer timer(settings_.stageTimes, s.stages.shadowRays);
        for (std::size_t p = 0; p < packets; ++p) cameraPacketShadowRays(s, p);
    }
    {
        StageTimer timer(settings_.stageTimes, s.stages.directShading);
        for (std::size_t p = 0; p < packets; ++p) cameraPacketDirect(s, p);
    }
    StageTimer timer(settings_.stageTimes, s.stages.secondaryRays);
    s.leaving.clear();
    s.pending.clear();
    if (settings_.maxDepth > 1)
        for (std::size_t p = 0; p < packets; ++p)
            cameraPacketSpawn(s, p, cameraRays.pixelSpread(), cache && cache_ ? cache : nullptr);
    if (s.trackTrees) s.nodeBounds.resize(s.nodes.size());
}

void TileKernel::cameraPacketSurfaces(TileScratch::CameraPacket& packet, MeshHitLanes& meshLanes) const {
    alignas(64) int remaining[kFloatLanes], selected[kFloatLanes];
    std::memcpy(remaining, packet.hits.valid, sizeof remaining);
    SurfaceLanes16& surface = packet.surface;
    for (int id; (id = takeObjectLanes(packet.objectId, remaining, selected)) >= 0;) {
        const SceneObject& object = scene_.objects[static_cast<std::size_t>(id)];
        const Material& material = object.material;
        if (const Sphere* sphere = std::get_if<Sphere>(&object.shape)) {
            if (material.diffuseTexture) {
                // Texture coordinates on a sphere cost trigonometry: one lane at a time.
                for (int k = 0; k < kFloatLanes; ++k)
                    if (selected[k])
                        setLaneSurface(surface, k,
                                       surfacePointAt(object, laneRay(packet.rays.ray, k), laneHit(packet.rays, packet.objectId, k), true));
            } else {
                sphereSurfaceLanes16(packet.rays.ray, *sphere, selected, surface);
            }
        } else {
            // The triangles' records, lane by lane (the rays stay in the packet).
            MeshHitLanes& lanes = meshLanes;
            const TriangleMesh* mesh = std::get<MeshShape>(object.shape).mesh.get();
            const MeshShadingRecords* records = meshShading_.recordsFor(id, mesh);
            for (int k = 0; k < kFloatLanes; ++k)
                if (selected[k])
                    setMeshHitLane(lanes, static_cast<std::size_t>(k), *mesh, records,
                                   static_cast<int>(packet.rays.hit.primitiveId[k]), packet.rays.hit.u[k],
                                   packet.rays.hit.v[k]);
            meshSurfaceLanes16(packet.rays.ray, lanes, selected, surface);
        }
        // The albedo once the lanes' texture coordinates are known.
        if (material.diffuseTexture) {
            for (int k = 0; k < kFloatLanes; ++k)
                if (selected[k]) {
                    const Rgb albedo = material.diffuseTexture->sample(surface.u[k], surface.v[k]);
                    surface.albedoR[k] = albedo.r, surface.albedoG[k] = albedo.g, surface.albedoB[k] = albedo.b;
                }
        } else {
            const Rgb albedo = material.diffuse;
            for (int k = 0; k < kFloatLanes; ++k) {
                surface.albedoR[k] = selected[k] ? albedo.r : surface.albedoR[k];
                surface.albedoG[k] = selected[k] ? albedo.g : surface.albedoG[k];
                surface.albedoB[k] = selected[k] ? albedo.b : surface.albedoB[k];
            }
        }
    }
}

void TileKernel::cameraPacketShadowRays(TileScratch& s, std::size_t p) const {
    TileScratch::CameraPacket& packet = s.cameraPackets[p];
    const std::size_t lights = scene_.lights.size();
    std::fill_n(packet.shadowRays, kFloatLanes, 0);
    bool anyHit = false;
    for (int k = 0; k < kFloatLanes; ++k) anyHit |= packet.hits.valid[k] != 0;
    for (std::size_t l = 0; l < lights; ++l) {
        LightLanes16& seen = s.cameraLights[p * lights + l];
        std::fill_n(seen.lit, kFloatLanes, 0);
        if (!anyHit) continue;
        RayLanes16 rays;
        PacketLanes traced;
        shadowRayLanes16(scene_.lights[l], shading_.spotCones()[l], packet.surface, packet.hits.valid, rays, traced,
                         seen);
        int count = 0;
        for (int k = 0; k < kFloatLanes; ++k) count += traced.valid[k] != 0;
        if (count == 0) continue;
        alignas(64) unsigned char occluded[kFloatLanes];
        tracer_.occludedPacket(rays, traced, occluded);
        for (int k = 0; k < kFloatLanes; ++k) {
            seen.lit[k] = traced.valid[k] && !occluded[k] ? 1 : 0;
            packet.shadowRays[k] += traced.valid[k] ? 1 : 0;
        }
        s.counts.shadow += static_cast<std::uint64_t>(count);
    }
    // What a store tells the cache policy a hit spares counts these rays
    // (the general path's traceShadowRays).
    if (cache_)
        for (int k = 0; k < packet.count; ++k)
            s.nodes[static_cast<std::size_t>(packet.firstRoot + k)].tracedRays +=
                static_cast<std::uint32_t>(packet.shadowRays[k]);
}

void TileKernel::cameraPacketDirect(TileScratch& s, std::size_t p) const {
    TileScratch::CameraPacket& packet = s.cameraPackets[p];
    const std::size_t lights = scene_.lights.size();
    alignas(64) int remaining[kFloatLanes], selected[kFloatLanes];
    std::memcpy(remaining, packet.hits.valid, sizeof remaining);
    for (int id; (id = takeObjectLanes(packet.objectId, remaining, selected)) >= 0;)
        directLightLanes16(scene_.objects[static_cast<std::size_t>(id)].material, scene_.lights,
                           s.cameraLights.data() + p * lights, packet.surface, packet.rays.ray, selected,
                           packet.directR, packet.directG, packet.directB);
    for (int k = 0; k < packet.count; ++k)
        if (packet.hits.valid[k])
            s.nodes[static_cast<std::size_t>(packet.firstRoot + k)].direct =
                Rgb{packet.directR[k], packet.directG[k], packet.directB[k]};
}

void TileKernel::cameraPacketSpawn(TileScratch& s, std::size_t p, float pixelSpread, CacheWorker* cache) const {
    TileScratch::CameraPacket& packet = s.cameraPackets[p];
    SecondaryRayLanes16& spawned = s.cameraSpawn;
    alignas(64) int remaining[kFloatLanes], selected[kFloatLanes];
    std::memcpy(remaining, packet.hits.valid, sizeof remaining);
    bool any = false;
    for (int id; (id = takeObjectLanes(packet.objectId, remaining, selected)) >= 0;) {
        const SceneObject& object = scene_.objects[static_cast<std::size_t>(id)];
        const Material& material = object.material;
        if (!material.reflects() && !material.refracts()) {
            for (int k = 0; k < kFloatLanes; ++k)
                if (selected[k]) spawned.reflects[k] = spawned.refracts[k] = 0;
            continue;
        }
        any = true;
        secondaryRayLanes16(material, coneCurvature(object), pixelSpread, settings_.minWeight, packet.surface,
                            packet.rays.ray, selected, spawned);
    }
    if (!any) return;
    // Pixel by pixel, the reflected ray before the refracted one, as the
    // general path spawns them.
    for (int k = 0; k < packet.count; ++k) {
        if (!packet.hits.valid[k]) continue;
        const int node = packet.firstRoot + k;
        const int objectId = packet.objectId[k];
        const RayCone cone{spawned.coneWidth[k], spawned.coneSpread[k]};
        const bool frontFace = packet.surface.frontFace[k] != 0;
        if (spawned.reflects[k])
            emitSecondaryRay(s, cache, node, 1.0f, 1, objectId,
                             Ray{{spawned.aboveX[k], spawned.aboveY[k], spawned.aboveZ[k]},
                                 {spawned.reflectedX[k], spawned.reflectedY[k], spawned.reflectedZ[k]}},
                             cone, TileScratch::Kind::Reflection, spawned.reflectWeight[k], frontFace);
        if (spawned.refracts[k]) {
            const Material& material = scene_.objects[static_cast<std::size_t>(objectId)].material;
            emitSecondaryRay(s, cache, node, 1.0f, 1, objectId,
                             Ray{{spawned.belowX[k], spawned.belowY[k], spawned.belowZ[k]},
                                 {spawned.refractedX[k], spawned.refractedY[k], spawned.refractedZ[k]}},
                             cone, TileScratch::Kind::Refraction, material.transmissivity, !frontFace);
        }
    }
}

}  // namespace raycache
