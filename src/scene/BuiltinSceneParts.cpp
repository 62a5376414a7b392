#include "scene/BuiltinSceneParts.h"

#include <array>
#include <memory>

#include "scene/MeshGenerators.h"

namespace raycache::builtin {

namespace {

const CacheSettings kCached{CacheTechnique::Cct, 512};

}  // namespace

Rgb paletteColor(int i) {
    static constexpr std::array<Rgb, 8> palette{Rgb{0.85f, 0.2f, 0.2f}, Rgb{0.2f, 0.7f, 0.25f},
                                                Rgb{0.2f, 0.35f, 0.85f}, Rgb{0.9f, 0.75f, 0.2f},
                                                Rgb{0.7f, 0.25f, 0.8f}, Rgb{0.2f, 0.75f, 0.8f},
                                                Rgb{0.95f, 0.5f, 0.15f}, Rgb{0.6f, 0.6f, 0.6f}};
    return palette[static_cast<std::size_t>(i) % palette.size()];
}

Material mirror(const Rgb& tint, float kr) {
    Material m;
    m.ambient = Rgb{0.1f};
    m.diffuse = tint;
    m.specular = Rgb{0.8f};
    m.shininess = 96.0f;
    m.reflectivity = kr;
    m.cache = kCached;
    return m;
}

Material glass() {
    Material m;
    m.ambient = Rgb{0.0f};
    m.diffuse = Rgb{0.0f};
    m.specular = Rgb{0.9f};
    m.shininess = 128.0f;
    m.reflectivity = 0.1f;
    m.transmissivity = 0.9f;
    m.ior = 1.5f;
    m.cache = kCached;
    return m;
}

Material matte(const Rgb& color) {
    Material m;
    m.ambient = Rgb{0.15f};
    m.diffuse = color;
    m.specular = Rgb{0.2f};
    m.shininess = 24.0f;
    return m;
}

Material checker(const Rgb& even, const Rgb& odd, float squaresPerUnit) {
    Material m = matte(Rgb{1.0f});
    m.specular = Rgb{0.0f};
    m.diffuseTexture = Texture::checkerboard({even, odd, squaresPerUnit});
    return m;
}

SceneObject sphere(std::string name, const Vec3& center, float radius, Material material) {
    return SceneObject{std::move(name), Sphere{center, radius}, std::move(material), center};
}

SceneObject meshObject(std::string name, const TriangleMesh& mesh, const Vec3& at, const Vec3& scale, float yawDeg,
                       Material material) {
    const Transform t = Transform::translate(at) * Transform::rotate({0, 1, 0}, yawDeg) * Transform::scale(scale);
    return SceneObject{std::move(name), MeshShape{std::make_shared<const TriangleMesh>(transformed(mesh, t))},
                       std::move(material), at};
}

SceneObject floorObject(float size, float y) {
    // The plane's uv spans [0,1] over its side, so `size` squares per uv unit gives 1-unit squares.
    return meshObject("floor", makePlane(), {0, y, 0}, {size, 1, size}, 0.0f,
                      checker(Rgb{0.85f}, Rgb{0.12f}, size));
}

SceneObject wallObject(std::string name, const Vec3& center, float size, Material material) {
    // The plane is built in xz with normal +y; turning it 90 degrees about x makes the normal +z.
    const Transform t = Transform::translate(center) * Transform::rotate({1, 0, 0}, 90.0f) *
                        Transform::scale({size, 1, size});
    return SceneObject{std::move(name), MeshShape{std::make_shared<const TriangleMesh>(transformed(makePlane(), t))},
                       std::move(material), center};
}

Light pointLight(const Vec3& position, float intensity) {
    Light l;
    l.type = LightType::Point;
    l.position = position;
    l.intensity = Rgb{intensity};
    return l;
}

Camera camera(const Vec3& position, const Vec3& lookAt, float fov) {
    return Camera{position, lookAt, {0, 1, 0}, fov};
}

CameraPath orbit(const Vec3& center, float degreesPerFrame) {
    CameraPath p;
    p.kind = CameraPathKind::Orbit;
    p.center = center;
    p.degreesPerFrame = degreesPerFrame;
    return p;
}

}  // namespace raycache::builtin
