#include "trace/TraceScene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <limits>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "trace/EmbreeDeviceConfig.h"
#include "trace/SphereIntersection.h"
#include "trace/SphereLanes.h"

namespace raycache {

namespace {

void throwOnDeviceError(RTCDevice device, const char* what) {
    const RTCError err = rtcGetDeviceError(device);
    if (err != RTC_ERROR_NONE)
        throw RuntimeError(std::string("Embree failed while ") + what + " (error " +
                           std::to_string(static_cast<int>(err)) + ")");
}

// Spheres are Embree user geometry with our own intersection code: it beats
// Embree's built-in sphere points here (see docs/performance.md), and keeps
// the arithmetic in one readable place.
void sphereBounds(const RTCBoundsFunctionArguments* args) {
    const auto* sphere = static_cast<const Sphere*>(args->geometryUserPtr);
    args->bounds_o->lower_x = sphere->center.x - sphere->radius;
    args->bounds_o->lower_y = sphere->center.y - sphere->radius;
    args->bounds_o->lower_z = sphere->center.z - sphere->radius;
    args->bounds_o->upper_x = sphere->center.x + sphere->radius;
    args->bounds_o->upper_y = sphere->center.y + sphere->radius;
    args->bounds_o->upper_z = sphere->center.z + sphere->radius;
}

// A packet's rays as sphereRoots16 reads them (RTCRayN with N = 16 is an
// array of sixteen floats per field).
RayLanePointers rayLanes(RTCRayN* ray) {
    constexpr unsigned N = 16;
    return {&RTCRayN_org_x(ray, N, 0), &RTCRayN_org_y(ray, N, 0), &RTCRayN_org_z(ray, N, 0),
            &RTCRayN_dir_x(ray, N, 0), &RTCRayN_dir_y(ray, N, 0), &RTCRayN_dir_z(ray, N, 0),
            &RTCRayN_tnear(ray, N, 0), &RTCRayN_tfar(ray, N, 0)};
}

// The sphere's root for every valid lane of the call: sixteen lanes in one
// vector pass (trace/SphereLanes.h), any other width lane by lane; both
// give the same bits. A lane with no root gets a negative value.
void sphereRoots(const Sphere& sphere, RTCRayN* ray, unsigned N, const int* valid, float* t) {
    if (N == 16) {
        sphereRoots16(sphere, rayLanes(ray), valid, t);
        return;
    }
    for (unsigned i = 0; i < N; ++i)
        t[i] = valid[i] ? sphereRoot(sphere, RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i),
                                     RTCRayN_org_z(ray, N, i), RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i),
                                     RTCRayN_dir_z(ray, N, i), RTCRayN_tnear(ray, N, i), RTCRayN_tfar(ray, N, i))
                        : -1.0f;
}

void sphereIntersect(const RTCIntersectFunctionNArguments* args) {
    const auto* sphere = static_cast<const Sphere*>(args->geometryUserPtr);
    RTCRayHitN* rayhit = args->rayhit;
    RTCRayN* ray = RTCRayHitN_RayN(rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(rayhit, args->N);
    alignas(64) float roots[16];
    sphereRoots(*sphere, ray, args->N, args->valid, roots);
    for (unsigned i = 0; i < args->N; ++i) {
        const float t = roots[i];
        if (!(t >= 0.0f)) continue;
        RTCRayN_tfar(ray, args->N, i) = t;
        // Geometric normal (unnormalized), as Embree reports for its own primitives.
        RTCHitN_Ng_x(hit, args->N, i) = RTCRayN_org_x(ray, args->N, i) + t * RTCRayN_dir_x(ray, args->N, i) - sphere->center.x;
        RTCHitN_Ng_y(hit, args->N, i) = RTCRayN_org_y(ray, args->N, i) + t * RTCRayN_dir_y(ray, args->N, i) - sphere->center.y;
        RTCHitN_Ng_z(hit, args->N, i) = RTCRayN_org_z(ray, args->N, i) + t * RTCRayN_dir_z(ray, args->N, i) - sphere->center.z;
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
        RTCHitN_primID(hit, args->N, i) = args->primID;
        RTCHitN_u(hit, args->N, i) = 0.0f;
        RTCHitN_v(hit, args->N, i) = 0.0f;
        RTCHitN_instID(hit, args->N, i, 0) = RTC_INVALID_GEOMETRY_ID;
    }
}

void sphereOccluded(const RTCOccludedFunctionNArguments* args) {
    const auto* sphere = static_cast<const Sphere*>(args->geometryUserPtr);
    RTCRayN* ray = args->ray;
    alignas(64) float roots[16];
    sphereRoots(*sphere, ray, args->N, args->valid, roots);
    for (unsigned i = 0; i < args->N; ++i)
        if (roots[i] >= 0.0f) RTCRayN_tfar(ray, args->N, i) = -std::numeric_limits<float>::infinity();
}

RTCGeometry makeSphereGeometry(RTCDevice device, const Sphere& sphere) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    // `sphere` is the TraceScene's own copy, which lives as long as the geometry.
    rtcSetGeometryUserData(geom, const_cast<Sphere*>(&sphere));
    rtcSetGeometryBoundsFunction(geom, sphereBounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, sphereIntersect);
    rtcSetGeometryOccludedFunction(geom, sphereOccluded);
    return geom;
}

void copyVertices(const TriangleMesh& mesh, float* vertices) {
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        vertices[3 * i + 0] = mesh.positions[i].x;
        vertices[3 * i + 1] = mesh.positions[i].y;
        vertices[3 * i + 2] = mesh.positions[i].z;
    }
}

RTCGeometry makeMeshGeometry(RTCDevice device, const TriangleMesh& mesh) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // rtcSetNewGeometryBuffer pads the vertex buffer for Embree's 16-byte loads itself.
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    copyVertices(mesh, vertices);
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        std::copy(mesh.triangles[i].begin(), mesh.triangles[i].end(), indices + 3 * i);
    return geom;
}

void toEmbree(const Ray& ray, RTCRay& r) {
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.dir_x = ray.direction.x;
    r.dir_y = ray.direction.y;
    r.dir_z = ray.direction.z;
    r.tnear = ray.tNear;
    r.tfar = ray.tFar;
    r.time = 0.0f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
}

void toEmbree(const Ray& ray, RTCRayHit& rh) {
    toEmbree(ray, rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

TraceHit fromEmbree(const RTCRayHit& rh) {
    TraceHit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    h.t = rh.ray.tfar;
    // A moving mesh is an instance whose geometry id is its object's index.
    h.objectId = static_cast<int>(rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? rh.hit.instID[0] : rh.hit.geomID);
    h.primitiveId = static_cast<int>(rh.hit.primID);
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    return h;
}

// Coherent rays go to Embree as packets of this width: 16 matches the AVX-512
// kernels of this machine's Embree (docs/performance.md compares 8 and 16).
constexpr std::size_t kPacketWidth = 16;
using RayPacket = RTCRay16;
using RayHitPacket = RTCRayHit16;

// Loads up to kPacketWidth rays into a packet (RayLanes16 is RTCRay16
// under our names; the static_asserts below check it); lanes past
// rays.size() repeat the last ray and are masked off in `valid`.
void fillPacket(std::span<const Ray> rays, int* valid, RayPacket& packet) {
    const std::size_t count = rays.size();
    auto& lanes = reinterpret_cast<RayLanes16&>(packet);
    for (std::size_t k = 0; k < kPacketWidth; ++k) {
        valid[k] = k < count ? -1 : 0;
        setLaneRay(lanes, static_cast<int>(k), rays[std::min(k, count - 1)]);
    }
}


}  // namespace

// How an object is held, which decides how it follows the animation.
enum class Representation {
    Still,           // geometry in the top-level scene, never updated
    MovingSphere,    // user geometry whose sphere is rewritten
    RigidInstance,   // its rest mesh in a scene of its own, instanced with a transform
    DeformingMesh,   // triangles whose vertices are rewritten and whose hierarchy is refitted
};

struct TraceScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    // Sphere data read by the intersection callbacks; sized once, never moved.
    std::vector<Sphere> spheres;
    std::vector<Representation> representation;  // per object
    std::vector<RTCScene> instanced;             // per object: its own scene for RigidInstance
    std::vector<unsigned char> isSphere;         // per object
    std::vector<std::size_t> vertexCount;        // per object: a mesh geometry's vertices (rebuild())
    // Per object: a scene holding only the object's geometry (the top-level
    // scene's own, shared), for meetsObject; null until prepareOwnSurfaceTests.
    std::vector<RTCScene> alone;
    // Embree 3.13.5's coherent-packet occlusion never returned from a
    // scene holding both instances and user geometry (spheres); packets of
    // scenes with instances are traced without the coherence hint.
    bool coherentHint = true;
    Accelerator accelerator = Accelerator::Embree;
    std::unique_ptr<GridAccelerator> grids;  // with Accelerator::Grids
    // Per-frame counts, added to by concurrent batches.
    GridFrameStats gridBuild;
    std::atomic<std::uint64_t> primaryAnswered{0}, primaryRefused{0}, shadowAnswered{0}, shadowRefused{0};

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        for (RTCScene s : instanced)
            if (s) rtcReleaseScene(s);
        for (RTCScene s : alone)
            if (s) rtcReleaseScene(s);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

void setInstanceTransform(RTCGeometry instance, const Transform& placement) {
    const Transform::Rows& rows = placement.rows();
    float matrix[12];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) matrix[r * 4 + c] = rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, matrix);
}

Representation representationOf(const Scene& scene, std::size_t object) {
    const ObjectAnimation* animation = scene.animation.forObject(static_cast<int>(object));
    if (!animation) return Representation::Still;
    if (std::holds_alternative<Sphere>(scene.objects[object].shape)) return Representation::MovingSphere;
    return animation->deformation ? Representation::DeformingMesh : Representation::RigidInstance;
}

}  // namespace

TraceScene::TraceScene(const Scene& scene, const TraceOptions& options) : impl_(std::make_unique<Impl>()) {
    impl_->accelerator = options.accelerator;
    if (options.accelerator == Accelerator::Grids) impl_->grids = std::make_unique<GridAccelerator>(options.grids);
    const std::string config = embreeDeviceConfig(options.buildThreads);
    impl_->device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    if (!impl_->device) throw RuntimeError("Embree could not create a device");
    impl_->scene = rtcNewScene(impl_->device);
    // A still scene gets one high-quality hierarchy. An animated one asks for
    // Embree's two-level mode (scene quality LOW), in which every geometry
    // keeps a hierarchy of its own at its own quality and a commit rebuilds
    // only the changed ones and the small top level over them: still objects
    // HIGH, moving spheres and instances rebuilt at MEDIUM, deforming meshes
    // REFIT (their vertices move, their triangles stay). Measured in
    // docs/dynamic-scenes.md.
    const bool animated = !scene.animation.empty();
    const RTCBuildQuality stillQuality = options.stillSceneQuality == EmbreeBuildQuality::Low    ? RTC_BUILD_QUALITY_LOW
                                         : options.stillSceneQuality == EmbreeBuildQuality::Medium ? RTC_BUILD_QUALITY_MEDIUM
                                                                                                   : RTC_BUILD_QUALITY_HIGH;
    rtcSetSceneBuildQuality(impl_->scene, animated ? RTC_BUILD_QUALITY_LOW : stillQuality);
    // Without the dynamic flag Embree 3.13 (kernels/common/scene.cpp,
    // commit_task) makes a committed scene's structures immutable and builds
    // every geometry again at the next commit: the still meshes, and the
    // deforming ones despite REFIT (a refit is several times cheaper for the
    // 90k-triangle cloth; docs/dynamic-scenes.md).
    if (animated) rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_DYNAMIC);
    impl_->spheres.resize(scene.objects.size());
    impl_->instanced.assign(scene.objects.size(), nullptr);
    impl_->alone.assign(scene.objects.size(), nullptr);
    impl_->isSphere.assign(scene.objects.size(), 0);
    impl_->vertexCount.assign(scene.objects.size(), 0);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        const Representation representation = representationOf(scene, i);
        impl_->representation.push_back(representation);
        RTCGeometry geom = nullptr;
        if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
            impl_->spheres[i] = *sphere;
            impl_->isSphere[i] = 1;
            geom = makeSphereGeometry(impl_->device, impl_->spheres[i]);
        } else if (representation == Representation::RigidInstance) {
            // The instanced scene holds the rest mesh; the instance places it.
            const ObjectAnimation& animation = *scene.animation.forObject(static_cast<int>(i));
            RTCScene own = rtcNewScene(impl_->device);
            rtcSetSceneBuildQuality(own, RTC_BUILD_QUALITY_HIGH);
            RTCGeometry mesh = makeMeshGeometry(impl_->device, *std::get<MeshShape>(animation.restShape).mesh);
            rtcCommitGeometry(mesh);
            rtcAttachGeometry(own, mesh);
            rtcReleaseGeometry(mesh);
            rtcCommitScene(own);
            impl_->instanced[i] = own;
            impl_->coherentHint = false;
            geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(geom, own);
            setInstanceTransform(geom, object.placement);
        } else {
            geom = makeMeshGeometry(impl_->device, *std::get<MeshShape>(object.shape).mesh);
            impl_->vertexCount[i] = std::get<MeshShape>(object.shape).mesh->positions.size();
        }
        if (animated && representation != Representation::RigidInstance) {
            const bool refit = representation == Representation::DeformingMesh &&
                               options.deformingMeshes == DeformingMeshUpdate::Refit;
            rtcSetGeometryBuildQuality(geom, representation == Representation::Still ? RTC_BUILD_QUALITY_HIGH
                                             : refit                                  ? RTC_BUILD_QUALITY_REFIT
                                                                                      : RTC_BUILD_QUALITY_MEDIUM);
        }
        // Embree's fastest build is two-level with every geometry built at LOW (Morton codes).
        if (!animated && options.stillSceneQuality == EmbreeBuildQuality::Low)
            rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_LOW);
        rtcCommitGeometry(geom);
        // Geometry ids equal object indices, so hits name objects directly.
        rtcAttachGeometryByID(impl_->scene, geom, static_cast<unsigned>(i));
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(impl_->scene);
    throwOnDeviceError(impl_->device, "building the scene");
}

TraceScene::~TraceScene() = default;

void TraceScene::update(const Scene& posed, std::span<const int> changed) {
    if (changed.empty()) return;
    for (const int id : changed) {
        const auto i = static_cast<std::size_t>(id);
        RTCGeometry geom = rtcGetGeometry(impl_->scene, static_cast<unsigned>(id));
        switch (impl_->representation[i]) {
        case Representation::Still:
            throw RuntimeError("the tracer was asked to move object " + std::to_string(id) +
                               ", which its scene does not animate");
        case Representation::MovingSphere: impl_->spheres[i] = std::get<Sphere>(posed.objects[i].shape); break;
        case Representation::RigidInstance: setInstanceTransform(geom, posed.objects[i].placement); break;
        case Representation::DeformingMesh: {
            const TriangleMesh& mesh = *std::get<MeshShape>(posed.objects[i].shape).mesh;
            copyVertices(mesh, static_cast<float*>(rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0)));
            rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
            break;
        }
        }
        rtcCommitGeometry(geom);
        // The object's own scene shares the geometry: its hierarchy follows.
        if (impl_->alone[i]) rtcCommitScene(impl_->alone[i]);
    }
    rtcCommitScene(impl_->scene);
    throwOnDeviceError(impl_->device, "updating the scene");
}

void TraceScene::rebuild(const Scene& posed) {
    if (posed.objects.size() != impl_->representation.size())
        throw RuntimeError("the tracer was asked to rebuild " + std::to_string(posed.objects.size()) +
                           " objects; it holds " + std::to_string(impl_->representation.size()));
    for (std::size_t i = 0; i < posed.objects.size(); ++i) {
        if (impl_->representation[i] != Representation::Still)
            throw RuntimeError("the tracer was asked to rebuild object " + std::to_string(i) +
                               ", which its scene animates (update() moves it)");
        RTCGeometry geom = rtcGetGeometry(impl_->scene, static_cast<unsigned>(i));
        if (impl_->isSphere[i]) {
            impl_->spheres[i] = std::get<Sphere>(posed.objects[i].shape);
        } else {
            const TriangleMesh& mesh = *std::get<MeshShape>(posed.objects[i].shape).mesh;
            if (mesh.positions.size() != impl_->vertexCount[i])
                throw RuntimeError("the tracer was asked to rebuild object " + std::to_string(i) +
                                   " with another vertex count");
            copyVertices(mesh, static_cast<float*>(rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0)));
            rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
        }
        rtcCommitGeometry(geom);
    }
    // Not a dynamic scene: Embree builds every geometry's hierarchy and the
    // top level again at this commit (see the constructor).
    rtcCommitScene(impl_->scene);
    throwOnDeviceError(impl_->device, "rebuilding the scene");
}

void* TraceScene::embreeScene() const { return impl_->scene; }

void TraceScene::prepareOwnSurfaceTests(std::span<const int> objects) const {
    for (const int id : objects) {
        const auto i = static_cast<std::size_t>(id);
        if (i >= impl_->alone.size()) throw RuntimeError("no object " + std::to_string(id) + " in the tracer's scene");
        if (impl_->isSphere[i] || impl_->alone[i]) continue;
        RTCScene own = rtcNewScene(impl_->device);
        // A refitted deforming mesh keeps its own quality only in Embree's
        // two-level mode (scene quality LOW); one geometry needs no better.
        rtcSetSceneBuildQuality(own, impl_->representation[i] == Representation::DeformingMesh ? RTC_BUILD_QUALITY_LOW
                                                                                               : RTC_BUILD_QUALITY_MEDIUM);
        // Recommitted as the object moves: dynamic, or each commit rebuilds (see the constructor).
        if (impl_->representation[i] != Representation::Still) rtcSetSceneFlags(own, RTC_SCENE_FLAG_DYNAMIC);
        rtcAttachGeometry(own, rtcGetGeometry(impl_->scene, static_cast<unsigned>(id)));
        rtcCommitScene(own);
        impl_->alone[i] = own;
    }
    throwOnDeviceError(impl_->device, "building an object's own hierarchy");
}

bool TraceScene::meetsObject(int objectId, const Ray& ray) const {
    const auto i = static_cast<std::size_t>(objectId);
    if (impl_->isSphere[i])
        return sphereRoot(impl_->spheres[i], ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x,
                          ray.direction.y, ray.direction.z, ray.tNear, ray.tFar) >= 0.0f;
    if (!impl_->alone[i])
        throw RuntimeError("object " + std::to_string(objectId) + " was tested for its own surface before "
                           "prepareOwnSurfaceTests built its hierarchy");
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r;
    toEmbree(ray, r);
    rtcOccluded1(impl_->alone[i], &context, &r);
    return r.tfar < 0.0f;
}

TraceHit TraceScene::intersect(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    toEmbree(ray, rh);
    rtcIntersect1(impl_->scene, &context, &rh);
    return fromEmbree(rh);
}

bool TraceScene::occluded(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r;
    toEmbree(ray, r);
    rtcOccluded1(impl_->scene, &context, &r);
    // Embree marks an occluded ray by setting tfar to -inf.
    return r.tfar < 0.0f;
}

void TraceScene::intersectCoherent(std::span<const Ray> rays, std::span<TraceHit> hits) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (impl_->coherentHint) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) RayHitPacket packet;
    alignas(64) int valid[kPacketWidth];
    for (std::size_t base = 0; base < rays.size(); base += kPacketWidth) {
        const std::size_t count = std::min(kPacketWidth, rays.size() - base);
        fillPacket(rays.subspan(base, count), valid, packet.ray);
        for (std::size_t k = 0; k < kPacketWidth; ++k) {
            packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, impl_->scene, &context, &packet);
        for (std::size_t k = 0; k < count; ++k) {
            TraceHit& h = hits[base + k];
            h = TraceHit{};
            if (packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) continue;
            h.t = packet.ray.tfar[k];
            const unsigned instance = packet.hit.instID[0][k];
            h.objectId = static_cast<int>(instance != RTC_INVALID_GEOMETRY_ID ? instance : packet.hit.geomID[k]);
            h.primitiveId = static_cast<int>(packet.hit.primID[k]);
            h.u = packet.hit.u[k];
            h.v = packet.hit.v[k];
        }
    }
}

void TraceScene::occludedCoherent(std::span<const Ray> rays, std::span<unsigned char> occluded) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (impl_->coherentHint) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) RayPacket packet;
    alignas(64) int valid[kPacketWidth];
    for (std::size_t base = 0; base < rays.size(); base += kPacketWidth) {
        const std::size_t count = std::min(kPacketWidth, rays.size() - base);
        fillPacket(rays.subspan(base, count), valid, packet);
        rtcOccluded16(valid, impl_->scene, &context, &packet);
        // Embree marks an occluded ray by setting tfar to -inf.
        for (std::size_t k = 0; k < count; ++k) occluded[base + k] = packet.tfar[k] < 0.0f ? 1 : 0;
    }
}

// RayHitLanes16 is RTCRayHit16 under names of this project's own.
static_assert(sizeof(RayHitLanes16) == sizeof(RTCRayHit16) && alignof(RayHitLanes16) == alignof(RTCRayHit16));
static_assert(offsetof(RayHitLanes16, ray.tNear) == offsetof(RTCRayHit16, ray.tnear));
static_assert(offsetof(RayHitLanes16, ray.directionX) == offsetof(RTCRayHit16, ray.dir_x));
static_assert(offsetof(RayHitLanes16, ray.time) == offsetof(RTCRayHit16, ray.time));
static_assert(offsetof(RayHitLanes16, ray.tFar) == offsetof(RTCRayHit16, ray.tfar));
static_assert(offsetof(RayHitLanes16, ray.flags) == offsetof(RTCRayHit16, ray.flags));
static_assert(offsetof(RayHitLanes16, hit.u) == offsetof(RTCRayHit16, hit.u));
static_assert(offsetof(RayHitLanes16, hit.primitiveId) == offsetof(RTCRayHit16, hit.primID));
static_assert(offsetof(RayHitLanes16, hit.geometryId) == offsetof(RTCRayHit16, hit.geomID));
static_assert(offsetof(RayHitLanes16, hit.instanceId) == offsetof(RTCRayHit16, hit.instID));
static_assert(sizeof(RayLanes16) == sizeof(RTCRay16));

void TraceScene::intersectPacket(RayHitLanes16& packet, const PacketLanes& lanes, int* objectId) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (impl_->coherentHint) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (std::size_t k = 0; k < kPacketWidth; ++k) {
        packet.hit.geometryId[k] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instanceId[k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(lanes.valid, impl_->scene, &context, reinterpret_cast<RTCRayHit16*>(&packet));
    for (std::size_t k = 0; k < kPacketWidth; ++k) {
        const unsigned instance = packet.hit.instanceId[k];
        const unsigned geometry = packet.hit.geometryId[k];
        objectId[k] = geometry == RTC_INVALID_GEOMETRY_ID
                          ? -1
                          : static_cast<int>(instance != RTC_INVALID_GEOMETRY_ID ? instance : geometry);
    }
}

void TraceScene::occludedPacket(RayLanes16& packet, const PacketLanes& lanes, unsigned char* occluded) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (impl_->coherentHint) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcOccluded16(lanes.valid, impl_->scene, &context, reinterpret_cast<RTCRay16*>(&packet));
    // Embree marks an occluded ray by setting tfar to -inf.
    for (std::size_t k = 0; k < kPacketWidth; ++k) occluded[k] = lanes.valid[k] && packet.tFar[k] < 0.0f ? 1 : 0;
}

void TraceScene::occludedIncoherent(std::span<const Ray> rays, std::span<unsigned char> occluded) const {
    for (std::size_t i = 0; i < rays.size(); ++i) occluded[i] = this->occluded(rays[i]) ? 1 : 0;
}

Accelerator TraceScene::accelerator() const { return impl_->accelerator; }

void TraceScene::prepareFrame(const Scene& posed, const Camera& camera, int width, int height,
                              const Parallel& parallel) const {
    if (!impl_->grids) return;
    impl_->gridBuild = impl_->grids->buildFrame(posed, camera, width, height, parallel);
    impl_->primaryAnswered = 0;
    impl_->primaryRefused = 0;
    impl_->shadowAnswered = 0;
    impl_->shadowRefused = 0;
}

FrameTraceStats TraceScene::frameStats() const {
    FrameTraceStats stats;
    stats.build = impl_->gridBuild;
    stats.primaryAnswered = impl_->primaryAnswered.load();
    stats.primaryRefused = impl_->primaryRefused.load();
    stats.shadowAnswered = impl_->shadowAnswered.load();
    stats.shadowRefused = impl_->shadowRefused.load();
    return stats;
}

namespace {

// Per-thread buffers for the rays the grids refuse, reused across batches.
struct RefusedRays {
    std::vector<std::size_t> index;
    std::vector<Ray> rays;
    std::vector<TraceHit> hits;
    std::vector<unsigned char> occluded;
    std::vector<unsigned char> refusedFlags;
    std::vector<std::uint64_t> order;
    std::vector<Ray> sorted;
};

RefusedRays& refusedRays() {
    thread_local RefusedRays buffers;
    return buffers;
}

}  // namespace

void TraceScene::intersectPrimary(std::span<const Ray> rays, std::span<TraceHit> hits) const {
    const GridAccelerator* grids = impl_->grids.get();
    if (!grids || !grids->built()) {
        intersectCoherent(rays, hits);
        return;
    }
    RefusedRays& refused = refusedRays();
    refused.index.clear();
    refused.rays.clear();
    refused.refusedFlags.resize(rays.size());
    grids->intersectPrimaryBatch(rays, hits, refused.refusedFlags);
    for (std::size_t i = 0; i < rays.size(); ++i)
        if (refused.refusedFlags[i]) {
            refused.index.push_back(i);
            refused.rays.push_back(rays[i]);
        }
    impl_->primaryAnswered += rays.size() - refused.index.size();
    if (refused.index.empty()) return;
    impl_->primaryRefused += refused.index.size();
    refused.hits.resize(refused.rays.size());
    intersectCoherent(refused.rays, refused.hits);
    for (std::size_t r = 0; r < refused.index.size(); ++r) hits[refused.index[r]] = refused.hits[r];
}

void TraceScene::occludedPrimaryShadows(std::span<const Ray> rays, std::span<const int> lights,
                                        std::span<unsigned char> occluded) const {
    const GridAccelerator* grids = impl_->grids.get();
    if (!grids || !grids->built()) {
        occludedCoherent(rays, occluded);
        return;
    }
    RefusedRays& refused = refusedRays();
    // Each light's rays as one batch, in batch order: the rays of a tile lie
    // close together in a light's space too, and the grids gather those of
    // one light tile into packets (FrustumGrid::occludedBatch). With several
    // lights the rays are first put in light order.
    const std::size_t count = rays.size();
    const bool oneLight = std::all_of(lights.begin(), lights.end(), [&](int l) { return l == lights[0]; });
    refused.order.clear();
    std::span<const Ray> ordered = rays;
    if (!oneLight) {
        for (std::size_t i = 0; i < count; ++i)
            refused.order.push_back((static_cast<std::uint64_t>(lights[i]) << 32) | i);
        std::sort(refused.order.begin(), refused.order.end());
        refused.sorted.clear();
        for (const std::uint64_t key : refused.order) refused.sorted.push_back(rays[key & 0xffffffffu]);
        ordered = refused.sorted;
    }
    const auto indexOf = [&](std::size_t position) {
        return oneLight ? position : static_cast<std::size_t>(refused.order[position] & 0xffffffffu);
    };
    refused.occluded.resize(count);
    refused.refusedFlags.resize(count);
    for (std::size_t begin = 0; begin < count;) {
        const int light = lights[indexOf(begin)];
        std::size_t end = begin + 1;
        while (end < count && lights[indexOf(end)] == light) ++end;
        grids->occludedShadowBatch(ordered.subspan(begin, end - begin), light,
                                   std::span(refused.occluded).subspan(begin, end - begin),
                                   std::span(refused.refusedFlags).subspan(begin, end - begin));
        begin = end;
    }
    refused.index.clear();
    refused.rays.clear();
    for (std::size_t s = 0; s < count; ++s) {
        const std::size_t i = indexOf(s);
        if (!refused.refusedFlags[s]) {
            occluded[i] = refused.occluded[s];
        } else {
            refused.index.push_back(i);
            refused.rays.push_back(rays[i]);
        }
    }
    impl_->shadowAnswered += rays.size() - refused.index.size();
    if (refused.index.empty()) return;
    impl_->shadowRefused += refused.index.size();
    refused.occluded.resize(refused.rays.size());
    occludedCoherent(refused.rays, refused.occluded);
    for (std::size_t r = 0; r < refused.index.size(); ++r) occluded[refused.index[r]] = refused.occluded[r];
}

}  // namespace raycache
