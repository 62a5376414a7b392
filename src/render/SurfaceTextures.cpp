#include "render/SurfaceTextures.h"

#include <cmath>

namespace raycache {

namespace {

// Below this |du1 dv2 - du2 dv1| a triangle's texture coordinates span no
// area: its tangent frame is undefined.
constexpr float kMinUvArea = 1e-12f;

}  // namespace

void materialFactorLane(const Material& material, int k, SurfaceLanes16& surfaces) {
    float metallic = material.metallic, roughness = material.roughness;
    if (material.metallicRoughnessTexture) {
        const Rgb texel = material.metallicRoughnessTexture->sample(surfaces.u[k], surfaces.v[k]);
        metallic *= texel.b;
        roughness *= texel.g;
    }
    surfaces.metallic[k] = metallic;
    surfaces.roughness[k] = roughness;
}

void materialFactorLanes(const Material& material, const int* lanes, SurfaceLanes16& surfaces) {
    for (int k = 0; k < 16; ++k)
        if (lanes[k]) materialFactorLane(material, k, surfaces);
}

Vec3 normalFromTexture(const Material& material, const TriangleMesh& mesh, int primitiveId, const SurfacePoint& sp) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(primitiveId)];
    const auto& uv0 = mesh.uvs[tri[0]];
    const auto& uv1 = mesh.uvs[tri[1]];
    const auto& uv2 = mesh.uvs[tri[2]];
    const float du1 = uv1[0] - uv0[0], dv1 = uv1[1] - uv0[1];
    const float du2 = uv2[0] - uv0[0], dv2 = uv2[1] - uv0[1];
    const float area = du1 * dv2 - du2 * dv1;
    if (!(std::fabs(area) > kMinUvArea)) return sp.normal;
    const Vec3 e1 = mesh.positions[tri[1]] - mesh.positions[tri[0]];
    const Vec3 e2 = mesh.positions[tri[2]] - mesh.positions[tri[0]];
    // dP = tangent du + bitangent dv across the triangle.
    const Vec3 tangent = (e1 * dv2 - e2 * dv1) / area;
    const Vec3 bitangent = (e2 * du1 - e1 * du2) / area;
    // The frame of the outside: a back-face hit's normal was turned toward
    // the ray, and the texture's normal is turned with it below.
    const Vec3 n = sp.frontFace ? sp.normal : -sp.normal;
    const Vec3 along = tangent - n * dot(n, tangent);
    const float alongLength = length(along);
    if (!(alongLength > 0.0f)) return sp.normal;
    const Vec3 t = along / alongLength;
    // The bitangent's side: texture coordinates may be mirrored.
    const Vec3 b = dot(cross(n, t), bitangent) < 0.0f ? -cross(n, t) : cross(n, t);
    const Rgb texel = material.normalTexture->sample(sp.u, sp.v);
    const float x = (2.0f * texel.r - 1.0f) * material.normalScale;
    const float y = (2.0f * texel.g - 1.0f) * material.normalScale;
    const float z = 2.0f * texel.b - 1.0f;
    const Vec3 mapped = t * x + b * y + n * z;
    const float mappedLength = length(mapped);
    if (!(mappedLength > 0.0f)) return sp.normal;
    const Vec3 outside = mapped / mappedLength;
    return sp.frontFace ? outside : -outside;
}

void normalTextureLanes(const Material& material, const TriangleMesh& mesh, const std::uint32_t* primitiveIds,
                        const int* lanes, SurfaceLanes16& surfaces) {
    for (int k = 0; k < 16; ++k) {
        if (!lanes[k]) continue;
        const Vec3 n = normalFromTexture(material, mesh, static_cast<int>(primitiveIds[k]), laneSurface(surfaces, k));
        surfaces.normalX[k] = n.x, surfaces.normalY[k] = n.y, surfaces.normalZ[k] = n.z;
    }
}

void triangleUvAt(const TriangleMesh& mesh, int primitiveId, const Vec3& position, float& u, float& v) {
    const auto& tri = mesh.triangles[static_cast<std::size_t>(primitiveId)];
    const Vec3 p0 = mesh.positions[tri[0]];
    const Vec3 e1 = mesh.positions[tri[1]] - p0, e2 = mesh.positions[tri[2]] - p0, d = position - p0;
    // Barycentrics by least squares in the triangle's plane.
    const float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
    const float d1 = dot(d, e1), d2 = dot(d, e2);
    const float denominator = d11 * d22 - d12 * d12;
    const float b1 = denominator != 0.0f ? (d22 * d1 - d12 * d2) / denominator : 0.0f;
    const float b2 = denominator != 0.0f ? (d11 * d2 - d12 * d1) / denominator : 0.0f;
    const float b0 = 1.0f - b1 - b2;
    u = mesh.uvs[tri[0]][0] * b0 + mesh.uvs[tri[1]][0] * b1 + mesh.uvs[tri[2]][0] * b2;
    v = mesh.uvs[tri[0]][1] * b0 + mesh.uvs[tri[1]][1] * b1 + mesh.uvs[tri[2]][1] * b2;
}

}  // namespace raycache
