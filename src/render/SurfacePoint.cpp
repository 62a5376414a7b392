#include "render/SurfacePoint.h"

#include <cmath>
#include <numbers>

#include "render/MeshShading.h"

namespace raycache {

namespace {

// A triangle's unit geometric normal, on the side of the shading normal `ns`
// when the mesh has vertex normals: files disagree on winding, so the vertex
// normals are trusted for which side is outside.
Vec3 triangleNormal(const TriangleMesh& mesh, int primitiveId, const Vec3& ns, bool hasShadingNormal) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(primitiveId)];
    const Vec3 ng = unitTriangleNormal(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
    return hasShadingNormal && dot(ng, ns) < 0.0f ? -ng : ng;
}

// Turns both normals toward the side `rayDirection` came from.
void faceToward(SurfacePoint& sp, const Vec3& rayDirection) {
    sp.frontFace = dot(rayDirection, sp.geometricNormal) < 0.0f;
    if (!sp.frontFace) {
        sp.normal = -sp.normal;
        sp.geometricNormal = -sp.geometricNormal;
    }
}

// A sphere's texture coordinates at outward unit normal n.
void sphereUv(const Vec3& n, float& u, float& v) {
    constexpr float pi = std::numbers::pi_v<float>;
    u = 0.5f + std::atan2(n.z, n.x) / (2.0f * pi);
    v = 0.5f + std::asin(std::fmax(-1.0f, std::fmin(1.0f, n.y))) / pi;
}

void sphereSurface(const Sphere& sphere, SurfacePoint& sp, bool needUv) {
    const Vec3 n = (sp.position - sphere.center) * (1.0f / sphere.radius);
    sp.normal = sp.geometricNormal = n;
    if (needUv) sphereUv(n, sp.u, sp.v);
}

// A triangle's interpolated texture coordinates (left alone when the mesh has none).
void meshUv(const TriangleMesh& mesh, const TraceHit& hit, float& u, float& v) {
    if (mesh.uvs.empty()) return;
    const auto& tri = mesh.triangles[static_cast<std::size_t>(hit.primitiveId)];
    const float w = 1.0f - hit.u - hit.v;
    u = mesh.uvs[tri[0]][0] * w + mesh.uvs[tri[1]][0] * hit.u + mesh.uvs[tri[2]][0] * hit.v;
    v = mesh.uvs[tri[0]][1] * w + mesh.uvs[tri[1]][1] * hit.u + mesh.uvs[tri[2]][1] * hit.v;
}

void meshSurface(const TriangleMesh& mesh, const TraceHit& hit, SurfacePoint& sp) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(hit.primitiveId)];
    const float w = 1.0f - hit.u - hit.v;
    Vec3 ns;
    bool hasShadingNormal = false;
    if (!mesh.normals.empty()) {
        const Vec3 interpolated =
            mesh.normals[tri[0]] * w + mesh.normals[tri[1]] * hit.u + mesh.normals[tri[2]] * hit.v;
        const float len = length(interpolated);
        if (len > 0.0f) {
            ns = interpolated / len;
            hasShadingNormal = true;
        }
    }
    sp.geometricNormal = triangleNormal(mesh, hit.primitiveId, ns, hasShadingNormal);
    sp.normal = hasShadingNormal ? ns : sp.geometricNormal;
    meshUv(mesh, hit, sp.u, sp.v);
}

}  // namespace

SurfacePoint surfacePointAt(const SceneObject& object, const Ray& ray, const TraceHit& hit, bool needUv) {
    SurfacePoint sp;
    sp.position = ray.origin + ray.direction * hit.t;
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) sphereSurface(*sphere, sp, needUv);
    else meshSurface(*std::get<MeshShape>(object.shape).mesh, hit, sp);
    faceToward(sp, ray.direction);
    return sp;
}

Rgb albedoAtHit(const SceneObject& object, const Ray& ray, const TraceHit& hit) {
    if (!object.material.diffuseTexture) return object.material.diffuse;
    float u = 0.0f, v = 0.0f;
    if (const auto* sphere = std::get_if<Sphere>(&object.shape))
        sphereUv((ray.origin + ray.direction * hit.t - sphere->center) * (1.0f / sphere->radius), u, v);
    else
        meshUv(*std::get<MeshShape>(object.shape).mesh, hit, u, v);
    return object.material.diffuseTexture->sample(u, v);
}

SurfacePoint surfacePointFromGBuffer(const Scene& scene, const GBufferView& gbuffer, std::size_t i,
                                     const Vec3& rayDirection) {
    SurfacePoint sp;
    sp.position = gbuffer.position(i);
    sp.normal = gbuffer.normalAt(i);
    const SceneObject& object = scene.objects[static_cast<std::size_t>(gbuffer.objectId(i))];
    if (const auto* shape = std::get_if<MeshShape>(&object.shape)) {
        const TriangleMesh& mesh = *shape->mesh;
        const bool hasShadingNormal = !mesh.normals.empty() && dot(sp.normal, sp.normal) != 0.0f;
        sp.geometricNormal = triangleNormal(mesh, gbuffer.primitiveId(i), sp.normal, hasShadingNormal);
        if (!hasShadingNormal) sp.normal = sp.geometricNormal;
    } else {
        sp.geometricNormal = sp.normal;
    }
    faceToward(sp, rayDirection);
    return sp;
}

}  // namespace raycache
