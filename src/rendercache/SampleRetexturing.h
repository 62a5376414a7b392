#pragma once
// Texture re-fetch of the Render Cache: a reprojected
// sample sits up to half a pixel off its new pixel's centre, so on a
// texture it shows the texel of the wrong point, and a checkerboard's edges
// come out jagged and shifted. A textured sample keeps its colour taken
// apart (SampleTexturing: albedo * lighting + rest); its pixel's centre ray
// is met with the sample's own primitive (render/HitOnPrimitive), the
// albedo fetched there, and multiplied back. The lighting and the rest vary
// slowly over a surface and stay as traced (the rest is shaded again from
// the new eye anyway where reflections are reshaded).
#include <array>
#include <cmath>
#include <variant>
#include <vector>

#include "core/Ray.h"
#include "core/Rgb.h"
#include "render/HitOnPrimitive.h"
#include "render/SurfacePoint.h"
#include "rendercache/SamplePool.h"
#include "scene/SceneObject.h"

namespace raycache {

// Priority (rendercache/RequestMap.h: holes 1, samples 0.5 * age / max age)
// of a pixel whose centre ray misses its textured sample's primitive: the
// stored colour is shown, so it is worth a ray sooner than an old sample,
// but not sooner than a hole.
inline constexpr float kMissedPrimitivePriority = 0.75f;

// The colour a textured sample of `object` (index `objectId`), at distance
// `sampleDistance` from the eye, shows at the pixel whose centre ray is
// `centreRay`, written to `color`; false (and `color` untouched) where
// that ray misses the sample's primitive.
bool retexturedColor(const SceneObject& object, int objectId, const SampleTexturing& texturing, const Ray& centreRay,
                     float sampleDistance, Rgb& color);

// retexturedColor() for the pixels of one pass, one thread: the same
// colours bit for bit, at a third of the instructions on a mesh. Of the
// centre ray's hit on the sample's triangle and the albedo there,
// render/HitOnPrimitive and render/SurfacePoint's albedoAtHit compute per
// call what depends on the triangle alone (TriangleOnItsPlane; the corners'
// texture coordinates); neighbouring pixels mostly meet one triangle, so
// this keeps the last triangle's and does the rest with the same operations
// in the same order (tests/rendercache/RenderCacheTextureTest compares the two). A mesh hit
// needs no distance to the sample (HitOnPrimitive uses it for spheres
// only), so it is asked for only there.
class CentreRetexturing {
public:
    explicit CentreRetexturing(const std::vector<SceneObject>& objects) : objects_(objects) {}

    // retexturedColor(objects[objectId], objectId, texturing, centreRay,
    // sampleDistance(), color): `sampleDistance` is called for spheres only.
    template <typename Distance>
    bool color(int objectId, const SampleTexturing& texturing, const Ray& centreRay, const Distance& sampleDistance,
               Rgb& color) {
        const TriangleOnItsPlane* const triangle = meshTriangle(objectId, texturing.primitiveId);
        if (!triangle)
            return retexturedColor(objects_[static_cast<std::size_t>(objectId)], objectId, texturing, centreRay,
                                   sampleDistance(), color);
        float t, u, v;
        if (!triangle->valid || !triangle->meet(centreRay, t, u, v)) return false;
        color = colorAt(objectId, texturing, u, v);
        return true;
    }

    // The triangle `primitiveId` of object `objectId` (kept until another
    // is asked for), or null when the object is not a mesh.
    const TriangleOnItsPlane* meshTriangle(int objectId, int primitiveId) {
        const SceneObject& object = objects_[static_cast<std::size_t>(objectId)];
        if (!std::holds_alternative<MeshShape>(object.shape)) return nullptr;
        if (objectId != object_ || primitiveId != triangle_.primitive) prepare(object, objectId, primitiveId);
        return &triangle_.plane;
    }
    // The colour where the centre ray met the last meshTriangle() at
    // barycentrics (u, v): render/SurfacePoint's albedoAtHit() for a mesh
    // hit, the corners' texture coordinates kept with the triangle.
    Rgb colorAt(int objectId, const SampleTexturing& texturing, float u, float v) const {
        const SceneObject& object = objects_[static_cast<std::size_t>(objectId)];
        Rgb albedo = object.material.diffuse;
        if (object.material.diffuseTexture) {
            float texU = 0.0f, texV = 0.0f;
            if (triangle_.hasUvs) {
                const float w = 1.0f - u - v;
                const auto& uv = triangle_.uv;
                texU = uv[0][0] * w + uv[1][0] * u + uv[2][0] * v;
                texV = uv[0][1] * w + uv[1][1] * u + uv[2][1] * v;
            }
            albedo = object.material.diffuseTexture->sample(texU, texV);
        }
        return shaded(albedo, texturing);
    }
    // The colour of a textured sample whose albedo is `albedo` (retexturedColor's last step).
    static Rgb shaded(const Rgb& albedo, const SampleTexturing& texturing) {
        return albedo * texturing.lighting + texturing.rest;
    }
    // The corners' texture coordinates of the last meshTriangle(), or null
    // where its mesh has none.
    const std::array<std::array<float, 2>, 3>* cornerTextureCoordinates() const {
        return triangle_.hasUvs ? &triangle_.uv : nullptr;
    }

private:
    void prepare(const SceneObject& object, int objectId, int primitiveId);

    // The last triangle met, and its corners' texture coordinates.
    struct Triangle {
        int primitive = -1;
        TriangleOnItsPlane plane;
        bool hasUvs = false;
        std::array<std::array<float, 2>, 3> uv{};
    };

    const std::vector<SceneObject>& objects_;
    int object_ = -1;
    Triangle triangle_;
};

}  // namespace raycache
