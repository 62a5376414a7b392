// The tile kernel's waves (render/TileKernel.h): a wave is a list of
// packets of sixteen rays in the tracer's own layout, the camera rays of
// one tile row, sixteen first hits of a caller, or sixteen secondary rays in
// the order they were spawned. Each stage (surfaces, shadow rays, direct
// light, secondary rays) runs over the wave's packets before the next.
// Where a packet's lanes hit several objects, a stage takes one object at a
// time under a mask, so that a material and a sphere are read once per
// packet. What each lane computes is the scalar rule's arithmetic,
// operation for operation (render/HitLanes.h).
#include <emmintrin.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#include "cache/CubeAddressingLanes.h"
#include "core/FloatLanes.h"
#include "render/StageTimer.h"
#include "render/SurfaceTextures.h"
#include "render/TileKernel.h"

namespace raycache {

namespace {

// Selects, among the lanes `remaining` still holds (nonzero), those of the
// object of the first one; removes them from `remaining`. Returns that
// object, or -1 when no lane remains. Four lanes at a time with SSE2, which
// every x86-64 has: it runs once per object of every packet and stage, and
// its scalar form branched lane by lane.
int takeObjectLanes(const int* objectId, int* remaining, int* selected) {
    static_assert(kFloatLanes == 16);
    const __m128i zero = _mm_setzero_si128();
    __m128i unused[4];
    unsigned unusedBits = 0;
    for (int q = 0; q < 4; ++q) {
        unused[q] = _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(remaining + 4 * q)), zero);
        unusedBits |= static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(unused[q]))) << (4 * q);
    }
    if (unusedBits == 0xFFFFu) return -1;
    const int object = objectId[std::countr_one(unusedBits)];
    const __m128i target = _mm_set1_epi32(object);
    for (int q = 0; q < 4; ++q) {
        const __m128i same =
            _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(objectId + 4 * q)), target);
        const __m128i taken = _mm_andnot_si128(unused[q], same);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(selected + 4 * q), taken);
        auto* lanes = reinterpret_cast<__m128i*>(remaining + 4 * q);
        _mm_storeu_si128(lanes, _mm_andnot_si128(taken, _mm_loadu_si128(lanes)));
    }
    return object;
}

// -1 in the first `count` lanes, 0 past them: the lanes a packet traces.
void setLanesBelow(int count, int* lanes) {
    for (int k = 0; k < kFloatLanes; ++k) lanes[k] = -static_cast<int>(k < count);
}

// Marks which of `packet`'s first `count` lanes hit something (hits.valid
// -1; 0 for the others and for the lanes past `count`); returns how many hit.
int markHitLanes(TileWave::HitPacket& packet) {
    const int count = packet.count;
    int hits = 0;
    for (int k = 0; k < kFloatLanes; ++k) {
        const int hit = -static_cast<int>((k < count) & (packet.objectId[k] >= 0));
        packet.hits.valid[k] = hit;
        hits -= hit;
    }
    return hits;
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

// Lane k of `packet` hit as `hit` says (the ray is set apart).
void setLaneHit(RayHitLanes16& packet, int k, const TraceHit& hit) {
    packet.ray.tFar[k] = hit.t;
    packet.hit.primitiveId[k] = static_cast<std::uint32_t>(hit.primitiveId);
    packet.hit.u[k] = hit.u;
    packet.hit.v[k] = hit.v;
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

// A G-buffer hit as the tracer's would be where the material has data
// textures: the texture coordinates (the G-buffer carries only the albedo)
// and the normal texture's normal.
SurfacePoint texturedGBufferSurface(const SceneObject& object, int primitiveId, SurfacePoint sp) {
    const Material& material = object.material;
    const auto* shape = std::get_if<MeshShape>(&object.shape);
    if (!shape || shape->mesh->uvs.empty() || (!material.metallicRoughnessTexture && !material.normalTexture))
        return sp;
    triangleUvAt(*shape->mesh, primitiveId, sp.position, sp.u, sp.v);
    if (material.normalTexture) sp.normal = normalFromTexture(material, *shape->mesh, primitiveId, sp);
    return sp;
}

}  // namespace

void TileKernel::startTilePackets(const CameraRays& cameraRays, const TileRange& tile, TileScratch& s) {
    // One packet per sixteen pixels of a row, row after row: lane k of a
    // packet is the pixel of root firstRoot + k, its camera ray as ray() has it.
    const int packetsPerRow = (tile.x1 - tile.x0 + kFloatLanes - 1) / kFloatLanes;
    s.wave.packets.resize(static_cast<std::size_t>(packetsPerRow) * static_cast<std::size_t>(tile.y1 - tile.y0));
    const float pixelSpread = cameraRays.pixelSpread();
    std::size_t p = 0;
    int root = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; x += kFloatLanes, ++p) {
            TileWave::HitPacket& packet = s.wave.packets[p];
            packet.count = std::min(kFloatLanes, tile.x1 - x);
            cameraRays.rowOfRays(x, y, packet.rays.ray);
            for (int k = 0; k < kFloatLanes; ++k) {
                packet.node[k] = root + k;
                packet.pathWeight[k] = 1.0f;
                packet.depth[k] = 1;
                packet.coneWidth[k] = 0.0f;
                packet.coneSpread[k] = pixelSpread;
            }
            root += packet.count;
        }
}

void TileKernel::traceCameraRaysInLanes(const CameraRays& cameraRays, const TileRange& tile, TileScratch& s,
                                        CacheWorker* cache) const {
    StageTimer timer(settings_.stageTimes, s.stages.firstHits);
    startTilePackets(cameraRays, tile, s);
    const bool grids = tracer_.accelerator() != Accelerator::Embree;
    if (grids) {
        // The grids answer a tile's rays together: their hits go back into the lanes.
        s.batch.rays.resize(s.wave.nodes.size());
        s.batch.hits.resize(s.wave.nodes.size());
        std::size_t i = 0;
        for (const TileWave::HitPacket& packet : s.wave.packets)
            for (int k = 0; k < packet.count; ++k) s.batch.rays[i++] = laneRay(packet.rays.ray, k);
        tracer_.intersectPrimary(std::span(s.batch.rays.data(), i), std::span(s.batch.hits.data(), i));
        i = 0;
        for (TileWave::HitPacket& packet : s.wave.packets)
            for (int k = 0; k < kFloatLanes; ++k) {
                const TraceHit hit = k < packet.count ? s.batch.hits[i++] : TraceHit{};
                packet.objectId[k] = hit.objectId;
                if (hit.hit()) setLaneHit(packet.rays, k, hit);
            }
    }
    std::uint64_t hits = 0;
    const bool notesVisiblePoints = cache && fill_.active();
    for (TileWave::HitPacket& packet : s.wave.packets) {
        if (!grids) {
            PacketLanes traced;
            setLanesBelow(packet.count, traced.valid);
            tracer_.intersectPacket(packet.rays, traced, packet.objectId);
        }
        s.counts.primary += static_cast<std::uint64_t>(packet.count);
        const int packetHits = markHitLanes(packet);
        hits += static_cast<std::uint64_t>(packetHits);
        // Lane by lane only where a ray missed or a hit may fill a cube.
        if (packetHits == packet.count && !notesVisiblePoints) continue;
        for (int k = 0; k < packet.count; ++k) {
            const auto node = static_cast<std::size_t>(packet.node[k]);
            if (!packet.hits.valid[k]) {
                s.wave.nodes[node].direct = shading_.background(laneRay(packet.rays.ray, k));
                continue;
            }
            if (notesVisiblePoints) {
                const Ray ray = laneRay(packet.rays.ray, k);
                noteVisiblePoint(s, static_cast<int>(node), packet.objectId[k],
                                 ray.origin + ray.direction * packet.rays.ray.tFar[k]);
            }
        }
    }
    s.stages.hitsShaded += hits;
}

void TileKernel::beginFirstHits(TileScratch& s, std::size_t count) {
    s.wave.packets.resize((count + kFloatLanes - 1) / kFloatLanes);
    s.wave.filledLanes = 0;
}

void TileKernel::addFirstHit(TileScratch& s, const Ray& ray, const TraceHit& hit, int node, int depth,
                             const RayCone& cone) {
    TileWave::HitPacket& packet = s.wave.packets[s.wave.filledLanes / kFloatLanes];
    const int k = static_cast<int>(s.wave.filledLanes % kFloatLanes);
    ++s.wave.filledLanes;
    setLaneRay(packet.rays.ray, k, ray);
    setLaneHit(packet.rays, k, hit);
    packet.objectId[k] = hit.objectId;
    packet.hits.valid[k] = -1;
    packet.node[k] = node;
    packet.pathWeight[k] = 1.0f;
    packet.depth[k] = depth;
    packet.coneWidth[k] = cone.width;
    packet.coneSpread[k] = cone.spread;
    packet.count = k + 1;
}

void TileKernel::endFirstHits(TileScratch& s) {
    const std::size_t packets = (s.wave.filledLanes + kFloatLanes - 1) / kFloatLanes;
    s.wave.packets.resize(packets);
    if (packets == 0) return;
    // Lanes past the last hit repeat it, not shaded.
    TileWave::HitPacket& last = s.wave.packets.back();
    const int from = last.count - 1;
    for (int k = last.count; k < kFloatLanes; ++k) {
        setLaneRay(last.rays.ray, k, laneRay(last.rays.ray, from));
        last.rays.ray.tFar[k] = last.rays.ray.tFar[from];
        last.objectId[k] = -1;
        last.hits.valid[k] = 0;
        last.node[k] = last.node[from];
        last.pathWeight[k] = last.pathWeight[from];
        last.depth[k] = last.depth[from];
        last.coneWidth[k] = last.coneWidth[from];
        last.coneSpread[k] = last.coneSpread[from];
    }
    s.stages.hitsShaded += s.wave.filledLanes;
}

void TileKernel::readGBufferInLanes(const CameraRays& cameraRays, const GBufferView& gbuffer, const TileRange& tile,
                                    TileScratch& s, CacheWorker* cache) const {
    StageTimer timer(settings_.stageTimes, s.stages.firstHits);
    startTilePackets(cameraRays, tile, s);
    const int tileWidth = tile.x1 - tile.x0;
    std::uint64_t hits = 0;
    for (TileWave::HitPacket& packet : s.wave.packets) {
        for (int k = 0; k < kFloatLanes; ++k) {
            packet.hits.valid[k] = 0;
            packet.objectId[k] = -1;
            if (k >= packet.count) continue;
            const int root = packet.node[k];
            const std::size_t i = gbuffer.index(tile.x0 + root % tileWidth, tile.y0 + root / tileWidth);
            const Ray ray = laneRay(packet.rays.ray, k);
            if (!gbuffer.hasSurface(i)) {
                s.wave.nodes[static_cast<std::size_t>(root)].direct = shading_.background(ray);
                continue;
            }
            packet.hits.valid[k] = -1;
            packet.objectId[k] = gbuffer.objectId(i);
            packet.rays.hit.primitiveId[k] = static_cast<std::uint32_t>(gbuffer.primitiveId(i));
            const SceneObject& object = scene_.objects[static_cast<std::size_t>(packet.objectId[k])];
            const SurfacePoint sp = texturedGBufferSurface(object, gbuffer.primitiveId(i),
                                                           surfacePointFromGBuffer(scene_, gbuffer, i, ray.direction));
            setLaneSurface(packet.surface, k, sp);
            packet.rays.ray.tFar[k] = length(sp.position - ray.origin);
            const Rgb albedo = gbuffer.albedoAt(i);
            packet.surface.albedoR[k] = albedo.r, packet.surface.albedoG[k] = albedo.g;
            packet.surface.albedoB[k] = albedo.b;
            if (object.material.model == ShadingModel::MetallicRoughness)
                materialFactorLane(object.material, k, packet.surface);
            ++hits;
            if (cache && fill_.active()) noteVisiblePoint(s, root, packet.objectId[k], sp.position);
        }
    }
    s.stages.hitsShaded += hits;
}

void TileKernel::traceSecondaryRaysInLanes(TileScratch& s) const {
    StageTimer timer(settings_.stageTimes, s.stages.traceSecondary);
    const std::size_t n = s.wave.pending.size();
    s.wave.packets.resize((n + kFloatLanes - 1) / kFloatLanes);
    std::uint64_t hits = 0;
    for (std::size_t p = 0; p < s.wave.packets.size(); ++p) {
        TileWave::HitPacket& packet = s.wave.packets[p];
        const std::size_t base = p * kFloatLanes;
        packet.count = static_cast<int>(std::min<std::size_t>(kFloatLanes, n - base));
        PacketLanes traced;
        for (int k = 0; k < kFloatLanes; ++k) {
            // Lanes past the last ray repeat it, not traced.
            const TileWave::PendingRay& ray =
                s.wave.pending[base + static_cast<std::size_t>(std::min(k, packet.count - 1))];
            setLaneRay(packet.rays.ray, k, ray.ray);
            packet.node[k] = ray.node;
            packet.pathWeight[k] = ray.pathWeight;
            packet.depth[k] = ray.depth;
            packet.coneWidth[k] = ray.cone.width;
            packet.coneSpread[k] = ray.cone.spread;
        }
        setLanesBelow(packet.count, traced.valid);
        tracer_.intersectPacket(packet.rays, traced, packet.objectId);
        hits += static_cast<std::uint64_t>(markHitLanes(packet));
        for (int k = 0; k < packet.count; ++k)
            recordTracedRay(s, s.wave.pending[base + static_cast<std::size_t>(k)], packet.hits.valid[k] != 0,
                            packet.rays.ray.tFar[k]);
    }
    s.stages.hitsShaded += hits;
}

void TileKernel::shadePackets(TileScratch& s, CacheWorker* cache, bool surfacesKnown, WaveShadows shadows) const {
    if (!surfacesKnown) {
        StageTimer timer(settings_.stageTimes, s.stages.surfaces);
        for (TileWave::HitPacket& packet : s.wave.packets) packetSurfaces(packet, s.wave.meshLanes);
    }
    if (shadows == WaveShadows::Known) {
        StageTimer timer(settings_.stageTimes, s.stages.directShading);
        for (std::size_t p = 0; p < s.wave.packets.size(); ++p) reshadePacket(s, p);
    } else {
        {
            StageTimer timer(settings_.stageTimes, s.stages.shadowRays);
            s.wave.packetLights.resize(s.wave.packets.size() * scene_.lights.size());
            // Camera hits' shadow rays start close together and head for the
            // same lights: the grids, when they are on, answer them per light.
            if (shadows == WaveShadows::OfCameraHits && tracer_.accelerator() != Accelerator::Embree) {
                cameraHitShadowRays(s);
            } else {
                for (std::size_t p = 0; p < s.wave.packets.size(); ++p) packetShadowRays(s, p);
            }
            // A camera hit's node is a root: no cube stores its tree and
            // no parent sums its rays, and roots are never tracked.
            if (shadows == WaveShadows::Traced && (s.caching.countTreeRays || s.caching.trackTrees))
                for (std::size_t p = 0; p < s.wave.packets.size(); ++p) recordShadowRays(s, p);
        }
        StageTimer timer(settings_.stageTimes, s.stages.directShading);
        for (std::size_t p = 0; p < s.wave.packets.size(); ++p) packetDirect(s, p);
        if (s.renderCache.recordFirstHits)
            for (std::size_t p = 0; p < s.wave.packets.size(); ++p) recordFirstHitLight(s, p);
    }
    StageTimer timer(settings_.stageTimes, s.stages.secondaryRays);
    s.caching.leaving.clear();
    s.caching.cacheQueries.clear();
    s.wave.pending.clear();
    // Trees tracked for animated scenes and the cache-level record take the
    // lookup batch.
    const bool lookUpInLanes = cache && !s.caching.trackTrees && !s.levelRecord.on;
    const std::size_t packets = s.wave.packets.size();
    if (!lookUpInLanes) {
        // Packet by packet, its rays still in the cache when their nodes are made.
        if (s.wave.spawnLanes.empty()) s.wave.spawnLanes.resize(1);
        for (const TileWave::HitPacket& packet : s.wave.packets) {
            packetSpawnLanes(packet, s.wave.spawnLanes[0], cache, false);
            packetEmit(s, packet, s.wave.spawnLanes[0], cache);
        }
    } else {
        // Every packet's rays first, then their nodes and lookups: the memory
        // the lookups read is fetched for the whole wave at once, its
        // latencies overlapping (packet by packet they added up, and the
        // ideal frame stalled on the validity bits); without lookups the
        // detour only costs, so it is taken only with them.
        // Between the two, the texels of valid bits are fetched: a filled
        // cube's hits read them, and CCT with filled cubes waited on them
        // (docs/log/2026-11-27-lookups-at-spawn.md).
        if (s.wave.spawnLanes.size() < packets) s.wave.spawnLanes.resize(packets);
        for (std::size_t p = 0; p < packets; ++p)
            packetSpawnLanes(s.wave.packets[p], s.wave.spawnLanes[p], cache, true);
        for (std::size_t p = 0; p < packets; ++p) {
            const SecondaryRayLanes16& spawned = s.wave.spawnLanes[p];
            if (!spawned.any) continue;
            for (int k = 0; k < kFloatLanes; ++k) {
                if (spawned.reflectedAnswered[k] == SecondaryRayLanes16::kAskedAtEmit)
                    cache_->prefetchTexelIfValid(s.wave.packets[p].objectId[k], spawned.reflectedTexel[k]);
                if (spawned.refractedAnswered[k] == SecondaryRayLanes16::kAskedAtEmit)
                    cache_->prefetchTexelIfValid(s.wave.packets[p].objectId[k], spawned.refractedTexel[k]);
            }
        }
        for (std::size_t p = 0; p < packets; ++p) packetEmit(s, s.wave.packets[p], s.wave.spawnLanes[p], cache);
    }
}

void TileKernel::packetSurfaces(TileWave::HitPacket& packet, MeshHitLanes& meshLanes) const {
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
                                       surfacePointAt(object, laneRay(packet.rays.ray, k),
                                                      laneHit(packet.rays, packet.objectId, k), true));
            } else {
                sphereSurfaceLanes16(packet.rays.ray, *sphere, selected, surface);
            }
        } else {
            // The triangles' records, lane by lane (the rays stay in the packet).
            const TriangleMesh* mesh = std::get<MeshShape>(object.shape).mesh.get();
            const MeshShadingRecords* records = meshShading_.recordsFor(id, mesh);
            for (int k = 0; k < kFloatLanes; ++k)
                if (selected[k])
                    setMeshHitLane(meshLanes, static_cast<std::size_t>(k), *mesh, records,
                                   static_cast<int>(packet.rays.hit.primitiveId[k]), packet.rays.hit.u[k],
                                   packet.rays.hit.v[k]);
            meshSurfaceLanes16(packet.rays.ray, meshLanes, selected, surface);
            if (material.normalTexture && !mesh->uvs.empty())
                normalTextureLanes(material, *mesh, packet.rays.hit.primitiveId, selected, surface);
        }
        // The albedo once the lanes' texture coordinates are known.
        const Checkerboard* checker = material.diffuseTexture ? material.diffuseTexture->checkerboardPattern() : nullptr;
        if (checker) {
            checkerAlbedoLanes16(*checker, selected, surface);
        } else if (material.diffuseTexture) {
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
        if (material.model == ShadingModel::MetallicRoughness) materialFactorLanes(material, selected, surface);
    }
}

void TileKernel::packetShadowRays(TileScratch& s, std::size_t p) const {
    TileWave::HitPacket& packet = s.wave.packets[p];
    const std::size_t lights = scene_.lights.size();
    bool anyHit = false;
    for (int k = 0; k < kFloatLanes; ++k) anyHit |= packet.hits.valid[k] != 0;
    for (std::size_t l = 0; l < lights; ++l) {
        LightLanes16& seen = s.wave.packetLights[p * lights + l];
        std::fill_n(seen.lit, kFloatLanes, 0);
        std::fill_n(seen.traced, kFloatLanes, 0);
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
            seen.traced[k] = traced.valid[k] ? 1 : 0;
            seen.lit[k] = traced.valid[k] && !occluded[k] ? 1 : 0;
        }
        s.counts.shadow += static_cast<std::uint64_t>(count);
    }
}

void TileKernel::cameraHitShadowRays(TileScratch& s) const {
    TileWave& wave = s.wave;
    TileTraceBatch& batch = s.batch;
    const std::size_t lights = scene_.lights.size();
    const std::size_t packets = wave.packets.size();
    batch.shadowLanes.resize(packets * lights);
    batch.shadowTraced.resize(packets * lights);
    for (std::size_t p = 0; p < packets; ++p)
        for (std::size_t l = 0; l < lights; ++l) {
            LightLanes16& seen = wave.packetLights[p * lights + l];
            std::fill_n(seen.lit, kFloatLanes, 0);
            std::fill_n(seen.traced, kFloatLanes, 0);
            shadowRayLanes16(scene_.lights[l], shading_.spotCones()[l], wave.packets[p].surface,
                             wave.packets[p].hits.valid, batch.shadowLanes[p * lights + l],
                             batch.shadowTraced[p * lights + l], seen);
        }
    // Hit after hit, each hit's lights in order, as LocalShading::shadowQueries lists them.
    batch.rays.clear();
    batch.shadowLights.clear();
    for (std::size_t p = 0; p < packets; ++p)
        for (int k = 0; k < wave.packets[p].count; ++k)
            for (std::size_t l = 0; l < lights; ++l) {
                if (!wave.packets[p].hits.valid[k] || !batch.shadowTraced[p * lights + l].valid[k]) continue;
                const RayLanes16& rays = batch.shadowLanes[p * lights + l];
                Ray ray = laneRay(rays, k);
                ray.tNear = rays.tNear[k];
                ray.tFar = rays.tFar[k];
                batch.rays.push_back(ray);
                batch.shadowLights.push_back(static_cast<int>(l));
            }
    const std::size_t count = batch.rays.size();
    batch.occluded.resize(count);
    tracer_.occludedPrimaryShadows(std::span(batch.rays.data(), count), std::span(batch.shadowLights.data(), count),
                                   std::span(batch.occluded.data(), count));
    std::size_t q = 0;
    for (std::size_t p = 0; p < packets; ++p)
        for (int k = 0; k < wave.packets[p].count; ++k)
            for (std::size_t l = 0; l < lights; ++l) {
                if (!wave.packets[p].hits.valid[k] || !batch.shadowTraced[p * lights + l].valid[k]) continue;
                LightLanes16& seen = wave.packetLights[p * lights + l];
                seen.traced[k] = 1;
                seen.lit[k] = batch.occluded[q++] ? 0 : 1;
            }
    s.counts.shadow += count;
}

void TileKernel::recordShadowRays(TileScratch& s, std::size_t p) const {
    const TileWave::HitPacket& packet = s.wave.packets[p];
    const std::size_t lights = scene_.lights.size();
    // What a store tells the cache policy a hit spares counts these rays.
    if (s.caching.countTreeRays)
        for (int k = 0; k < packet.count; ++k) {
            std::uint32_t traced = 0;
            for (std::size_t l = 0; l < lights; ++l)
                traced += static_cast<std::uint32_t>(s.wave.packetLights[p * lights + l].traced[k]);
            s.wave.nodes[static_cast<std::size_t>(packet.node[k])].tracedRays += traced;
        }
    if (!s.caching.trackTrees) return;
    for (int k = 0; k < packet.count; ++k) {
        const auto node = static_cast<std::size_t>(packet.node[k]);
        if (!packet.hits.valid[k] || !s.wave.nodes[node].tracked) continue;
        // The hit's light depends on every light (even one below its
        // horizon, which may rise) and on what its shadow rays cross,
        // kept apart by their answers (cache/RayTreeBounds.h).
        RayTreeBounds& bounds = s.caching.nodeBounds[node];
        bounds.shaded = true;
        const Vec3 position{packet.surface.positionX[k], packet.surface.positionY[k], packet.surface.positionZ[k]};
        const Vec3 geometric{packet.surface.geometricX[k], packet.surface.geometricY[k], packet.surface.geometricZ[k]};
        const Vec3 origin = position + geometric * surfaceOffset(position);
        for (std::size_t l = 0; l < lights; ++l) {
            const LightLanes16& seen = s.wave.packetLights[p * lights + l];
            if (seen.traced[k]) bounds.addShadowRay(origin, static_cast<int>(l), seen.lit[k] != 0);
        }
    }
}

void TileKernel::packetDirect(TileScratch& s, std::size_t p) const {
    TileWave::HitPacket& packet = s.wave.packets[p];
    const std::size_t lights = scene_.lights.size();
    alignas(64) int remaining[kFloatLanes], selected[kFloatLanes];
    std::memcpy(remaining, packet.hits.valid, sizeof remaining);
    for (int id; (id = takeObjectLanes(packet.objectId, remaining, selected)) >= 0;)
        directLightLanes16(scene_.objects[static_cast<std::size_t>(id)].material, scene_.lights,
                           s.wave.packetLights.data() + p * lights, packet.surface, packet.rays.ray, selected,
                           packet.directR, packet.directG, packet.directB);
    for (int k = 0; k < packet.count; ++k)
        if (packet.hits.valid[k])
            s.wave.nodes[static_cast<std::size_t>(packet.node[k])].direct =
                Rgb{packet.directR[k], packet.directG[k], packet.directB[k]};
}

void TileKernel::recordFirstHitLight(TileScratch& s, std::size_t p) const {
    const TileWave::HitPacket& packet = s.wave.packets[p];
    const std::size_t lights = scene_.lights.size();
    // The lanes' shadow rays were LocalShading::shadowQueries' rays (render/HitLanes.h).
    const LightLanes16* const seen = s.wave.packetLights.data() + p * lights;
    alignas(64) int remaining[kFloatLanes], selected[kFloatLanes];
    for (int k = 0; k < kFloatLanes; ++k) remaining[k] = packet.hits.valid[k] && packet.depth[k] == 1 ? -1 : 0;
    alignas(64) float lightR[kFloatLanes], lightG[kFloatLanes], lightB[kFloatLanes];
    alignas(64) float whiteR[kFloatLanes], whiteG[kFloatLanes], whiteB[kFloatLanes];
    for (int id; (id = takeObjectLanes(packet.objectId, remaining, selected)) >= 0;) {
        const Material& material = scene_.objects[static_cast<std::size_t>(id)].material;
        viewIndependentLightLanes16(material, scene_.lights, seen, packet.surface, false, selected, lightR, lightG,
                                    lightB);
        // Only a texture varies the albedo within a primitive; the lighting
        // of untextured hits is never asked for.
        if (material.diffuseTexture)
            viewIndependentLightLanes16(material, scene_.lights, seen, packet.surface, true, selected, whiteR, whiteG,
                                        whiteB);
    }
    for (int k = 0; k < packet.count; ++k) {
        if (!packet.hits.valid[k] || packet.depth[k] != 1) continue;
        const auto node = static_cast<std::size_t>(packet.node[k]);
        std::uint64_t litMask = 0;
        for (std::size_t l = 0; l < lights; ++l)
            if (seen[l].lit[k]) litMask |= std::uint64_t{1} << l;
        s.renderCache.rootLitMask[node] = litMask;
        s.renderCache.rootViewIndependent[node] = Rgb{lightR[k], lightG[k], lightB[k]};
        if (scene_.objects[static_cast<std::size_t>(packet.objectId[k])].material.diffuseTexture)
            s.renderCache.rootLighting[node] = Rgb{whiteR[k], whiteG[k], whiteB[k]};
    }
}

void TileKernel::reshadePacket(TileScratch& s, std::size_t p) const {
    const TileWave::HitPacket& packet = s.wave.packets[p];
    const std::size_t lights = scene_.lights.size();
    // Each light's direction and strength at the new hits (the shadow rays
    // are not traced): lit where it reaches the surface and the sample's
    // kept lit mask says it was lit.
    std::vector<LightLanes16>& seen = s.renderCache.reshadeLights;
    seen.resize(lights);
    RayLanes16 unused;
    PacketLanes reaches;
    for (std::size_t l = 0; l < lights; ++l) {
        shadowRayLanes16(scene_.lights[l], shading_.spotCones()[l], packet.surface, packet.hits.valid, unused, reaches,
                         seen[l]);
        for (int k = 0; k < kFloatLanes; ++k) {
            const bool litBefore =
                k < packet.count && packet.hits.valid[k] &&
                (s.renderCache.reshade[static_cast<std::size_t>(packet.node[k])].litMask >> l & 1u) != 0;
            seen[l].lit[k] = reaches.valid[k] && litBefore ? 1 : 0;
        }
    }
    alignas(64) int remaining[kFloatLanes], selected[kFloatLanes];
    for (int k = 0; k < kFloatLanes; ++k) remaining[k] = packet.hits.valid[k] ? -1 : 0;
    alignas(64) float highR[kFloatLanes], highG[kFloatLanes], highB[kFloatLanes];
    for (int id; (id = takeObjectLanes(packet.objectId, remaining, selected)) >= 0;)
        highlightLanes16(scene_.objects[static_cast<std::size_t>(id)].material, scene_.lights, seen.data(),
                         packet.surface, packet.rays.ray, selected, highR, highG, highB);
    for (int k = 0; k < packet.count; ++k) {
        if (!packet.hits.valid[k]) continue;
        const auto node = static_cast<std::size_t>(packet.node[k]);
        s.wave.nodes[node].direct = s.renderCache.reshade[node].viewIndependent + Rgb{highR[k], highG[k], highB[k]};
    }
}

void TileKernel::packetSpawnLanes(const TileWave::HitPacket& packet, SecondaryRayLanes16& spawned, CacheWorker* cache,
                                  bool lookUpInLanes) const {
    // Hits whose path may go on (the rest are done: their light is all they bring).
    alignas(64) int remaining[kFloatLanes], selected[kFloatLanes];
    bool any = false;
    const int maxDepth = settings_.maxDepth;
    for (int k = 0; k < kFloatLanes; ++k) {
        remaining[k] = packet.hits.valid[k] & (packet.depth[k] < maxDepth ? -1 : 0);
        spawned.reflects[k] = spawned.refracts[k] = 0;
        spawned.reflectedTexel[k] = spawned.refractedTexel[k] = -1;
        spawned.reflectedAnswered[k] = spawned.refractedAnswered[k] = -1;
        any |= remaining[k] != 0;
    }
    spawned.any = false;
    if (!any) return;
    for (int id; (id = takeObjectLanes(packet.objectId, remaining, selected)) >= 0;) {
        const SceneObject& object = scene_.objects[static_cast<std::size_t>(id)];
        const Material& material = object.material;
        if (!material.reflects() && !material.refracts()) continue;
        spawned.any = true;
        secondaryRayLanes16(material, coneCurvature(object), settings_.minWeight, packet.surface, packet.rays.ray,
                            packet.pathWeight, packet.coneWidth, packet.coneSpread, selected, spawned);
        // The texels that rays leaving a CCT object address on its cube,
        // sixteen at a time (the lookup batch addresses one at a time).
        const int faceSize = cache ? cache_->laneAddressedFaceSize(id) : 0;
        if (faceSize == 0) continue;
        cubeTexelIndices16(spawned.reflectedX, spawned.reflectedY, spawned.reflectedZ, faceSize, selected,
                           spawned.reflectedTexel);
        if (material.refracts())
            cubeTexelIndices16(spawned.refractedX, spawned.refractedY, spawned.refractedZ, faceSize, selected,
                               spawned.refractedTexel);
        // Where a lookup reads one validity bit and one texel, packetEmit
        // asks it: the rays reflected off the outside and refracted out from
        // the inside leave the object. What they read is fetched meanwhile.
        if (!lookUpInLanes || !cache_->looksUpInLanes(id)) continue;
        for (int k = 0; k < kFloatLanes; ++k) {
            if (!selected[k]) continue;
            const bool front = packet.surface.frontFace[k] != 0;
            if (spawned.reflects[k] && front) {
                spawned.reflectedAnswered[k] = SecondaryRayLanes16::kAskedAtEmit;
                cache_->prefetchValidity(id, spawned.reflectedTexel[k]);
            }
            if (spawned.refracts[k] && !front) {
                spawned.refractedAnswered[k] = SecondaryRayLanes16::kAskedAtEmit;
                cache_->prefetchValidity(id, spawned.refractedTexel[k]);
            }
        }
    }
}

// Inlined into packetEmit, its one caller: a ray a cube answered in lanes
// takes only its first lines, and the call (a dozen arguments) cost more.
[[gnu::always_inline]] inline void TileKernel::emitSecondaryRay(TileScratch& s, CacheWorker* cache, int parent,
                                                                float parentPathWeight, int parentDepth, int objectId,
                                                                const Ray& ray, const RayCone& cone,
                                                                TileWave::Kind kind, const Rgb& weight,
                                                                bool leavesObject,
                                                                const SpawnedRayLookup& lookup) const {
    // Every secondary ray gets a node of its own, whether a cache answers it
    // or not, so caching never changes how the colours are summed.
    const int node = static_cast<int>(s.wave.nodes.size());
    const bool parentTracked = s.wave.nodes[static_cast<std::size_t>(parent)].tracked;
    TileWave::Node& added = s.wave.nodes.emplace_back();
    if (s.caching.trackTrees) {
        // A fresh record for the node, whether it ends up tracked or not (beginWaves).
        if (s.caching.nodeBounds.size() < s.wave.nodes.size())
            s.caching.nodeBounds.resize(s.wave.nodes.size());
        else
            s.caching.nodeBounds[static_cast<std::size_t>(node)] = RayTreeBounds{};
    }
    added.parent = parent;
    added.weightInParent = weight;
    const float pathWeight = parentPathWeight * weight.maxComponent();
    // A cube that stands aside this frame (cache/CachePolicy.h), or a ray
    // out of a sampling cube's sample, is not asked: such rays go straight
    // to tracing, as without a cache, and cost no lookup, no miss
    // bookkeeping and no store.
    const bool cached = leavesObject && cache && cache_->cachesObject(objectId);
    if (cached && lookup.answered >= 0) {
        // Looked up already, in lanes: what the lookup batch would have done.
        added.tracked = s.caching.trackTrees;
        if (lookup.answered) {
            added.direct = lookup.color;
            return;
        }
        queueMissedLeavingRay(s, objectId, lookup.texel, {ray, node, pathWeight, parentDepth + 1, kind, cone});
        return;
    }
    if (cached && cache_->admits(objectId, ray.direction, lookup.texel)) {
        s.caching.leaving.push_back({node, pathWeight, parentDepth + 1, kind, cone});
        // Field by field: a whole-struct assignment was built on the stack
        // with narrow stores and copied with wide loads, a store-forwarding
        // stall per query.
        RayCache::Query& q = s.caching.cacheQueries.emplace_back();
        q.objectId = objectId;
        q.origin = ray.origin;
        q.direction = ray.direction;
        q.spread = cone.spread;
        // A cube that sees past its object's surface would answer a ray that
        // meets that surface (a concave mirror seeing itself) with what lies
        // behind it: such a ray is traced.
        q.meetsOwnSurface = cache_->seesPastOwnSurface(objectId) && tracer_.meetsObject(objectId, ray);
        q.texel = lookup.texel;
        added.tracked = s.caching.trackTrees;
    } else {
        if (cached) {
            cache_->countBypassedRay(objectId, *cache);
            // Asked nothing, so traced: what the level record shows for it.
            if (s.levelRecord.on) noteRootLevel(s, node, pathWeight, CacheLevelImage::kTraced);
        }
        s.wave.pending.push_back({ray, node, pathWeight, parentDepth + 1, kind, cone});
        added.tracked = parentTracked;
    }
}

void TileKernel::packetEmit(TileScratch& s, const TileWave::HitPacket& packet, SecondaryRayLanes16& spawned,
                            CacheWorker* cache) const {
    if (!spawned.any) return;
    // Hit by hit, the reflected ray before the refracted one: nodes are
    // gathered last to first, so the refracted colour is added first, as
    // Whitted's sum has it.
    for (int k = 0; k < packet.count; ++k) {
        if (!spawned.reflects[k] && !spawned.refracts[k]) continue;
        const int objectId = packet.objectId[k];
        const RayCone cone{spawned.coneWidth[k], spawned.coneSpread[k]};
        const bool frontFace = packet.surface.frontFace[k] != 0;
        // The lookup packetSpawnLanes asked for (its texel prefetched), answered now.
        const auto lookupOf = [&](int texel, int answered) {
            SpawnedRayLookup lookup{texel, answered, {}};
            if (lookup.answered == SecondaryRayLanes16::kAskedAtEmit)
                lookup.answered = cache_->lookupAddressed(objectId, lookup.texel, lookup.color, *cache);
            return lookup;
        };
        if (spawned.reflects[k]) {
            const SpawnedRayLookup lookup = lookupOf(spawned.reflectedTexel[k], spawned.reflectedAnswered[k]);
            emitSecondaryRay(s, cache, packet.node[k], packet.pathWeight[k], packet.depth[k], objectId,
                             Ray{{spawned.aboveX[k], spawned.aboveY[k], spawned.aboveZ[k]},
                                 {spawned.reflectedX[k], spawned.reflectedY[k], spawned.reflectedZ[k]}},
                             cone, TileWave::Kind::Reflection,
                             Rgb{spawned.reflectR[k], spawned.reflectG[k], spawned.reflectB[k]}, frontFace, lookup);
        }
        if (spawned.refracts[k]) {
            const SpawnedRayLookup lookup = lookupOf(spawned.refractedTexel[k], spawned.refractedAnswered[k]);
            emitSecondaryRay(s, cache, packet.node[k], packet.pathWeight[k], packet.depth[k], objectId,
                             Ray{{spawned.belowX[k], spawned.belowY[k], spawned.belowZ[k]},
                                 {spawned.refractedX[k], spawned.refractedY[k], spawned.refractedZ[k]}},
                             cone, TileWave::Kind::Refraction,
                             Rgb{spawned.refractR[k], spawned.refractG[k], spawned.refractB[k]}, !frontFace, lookup);
        }
    }
}

}  // namespace raycache
