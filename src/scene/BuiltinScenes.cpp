#include "scene/BuiltinScenes.h"

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "scene/BuiltinSceneParts.h"
#include "scene/ClothDrape.h"
#include "scene/MeshGenerators.h"
#include "scene/ScenePose.h"

namespace raycache {

// Inside builtin:: so that the parts (scene/BuiltinSceneParts.h) need no qualification.
namespace builtin {
namespace {

constexpr std::array<int, 7> kBehindCounts{0, 1, 2, 4, 8, 16, 32};
constexpr std::array<int, 6> kGridCounts{1, 2, 4, 8, 16, 32};

Scene behindScene(int n) {
    Scene s;
    s.name = "behind-" + std::to_string(n);
    s.objects.push_back(floorObject(200.0f));
    s.objects.push_back(sphere("main", {0, 2, 0}, 2.0f, mirror()));
    // A wall of up to 8 x 4 spheres behind the camera (z > 9) facing the main
    // sphere, so each one shows in its reflection and nowhere else.
    for (int i = 0; i < n; ++i) {
        const int row = i / 8, col = i % 8;
        const Vec3 c{(static_cast<float>(col) - 3.5f) * 3.2f, 1.5f + 3.2f * static_cast<float>(row), 14.0f};
        s.objects.push_back(sphere("behind" + std::to_string(i), c, 1.4f, mirror(paletteColor(i), 0.5f)));
    }
    s.lights.push_back(pointLight({6, 12, 6}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 2.5f, 9}, {0, 2, 0}, 40.0f);
    s.cameraPath = orbit({0, 2, 0}, 1.0f);
    s.defaultFrames = 30;
    return s;
}

// A wall of N mirror spheres facing the camera, cols x rows with cols a power
// of two >= rows (1, 2x1, 2x2, 4x2, 4x4, 8x4), nearly touching so they reflect
// one another. The camera is fixed: grid-32 fills the view, grid-1 a 32nd of it.
Scene gridScene(int n) {
    Scene s;
    s.name = "grid-" + std::to_string(n);
    s.objects.push_back(floorObject(200.0f, -5.0f));
    const int cols = 1 << ((static_cast<int>(std::log2(n)) + 1) / 2);
    const int rows = (n + cols - 1) / cols;
    constexpr float spacing = 2.2f;
    for (int i = 0; i < n; ++i) {
        const int row = i / cols, col = i % cols;
        const Vec3 c{(static_cast<float>(col) - 0.5f * static_cast<float>(cols - 1)) * spacing,
                     (0.5f * static_cast<float>(rows - 1) - static_cast<float>(row)) * spacing, 0.0f};
        s.objects.push_back(sphere("sphere" + std::to_string(i), c, 1.0f, mirror(paletteColor(i), 0.8f)));
    }
    s.lights.push_back(pointLight({6, 12, 16}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 1, 15}, {0, 0, 0}, 60.0f);
    s.cameraPath = orbit({0, 0, 0}, 1.0f);
    s.defaultFrames = 30;
    return s;
}

// 8 x 4 wall of spheres facing the camera, framed for 16:9.
Scene wallOf32(const std::string& name, bool allReflective) {
    Scene s;
    s.name = name;
    s.objects.push_back(floorObject(200.0f, -5.5f));
    for (int i = 0; i < 32; ++i) {
        const int row = i / 8, col = i % 8;
        const Vec3 c{(static_cast<float>(col) - 3.5f) * 2.6f, (1.5f - static_cast<float>(row)) * 2.6f, 0.0f};
        // In the diffuse variant only one sphere near the middle reflects.
        const bool reflective = allReflective || i == 11;
        s.objects.push_back(sphere("sphere" + std::to_string(i), c, 1.1f,
                                   reflective ? mirror(paletteColor(i), 0.7f) : matte(paletteColor(i))));
    }
    s.lights.push_back(pointLight({10, 15, 20}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 1, 17}, {0, 0, 0}, 45.0f);
    s.cameraPath = orbit({0, 0, 0}, 0.5f);
    s.defaultFrames = 30;
    return s;
}

Scene roomScene() {
    Scene s;
    s.name = "room";
    s.objects.push_back(floorObject(60.0f));
    s.objects.push_back(sphere("mirror-ball", {0, 1.5f, 0}, 1.5f, mirror()));
    // Ten diffuse objects on a ring of radius 5 around the mirror ball.
    const TriangleMesh box = makeBox(), cylinder = makeCylinder(), cone = makeCone(), torus = makeTorus();
    for (int i = 0; i < 10; ++i) {
        const float a = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / 10.0f;
        const Vec3 at{5.0f * std::cos(a), 0.0f, 5.0f * std::sin(a)};
        const Material m = matte(paletteColor(i));
        const std::string name = "object" + std::to_string(i);
        switch (i % 5) {
        case 0: s.objects.push_back(sphere(name, at + Vec3{0, 0.8f, 0}, 0.8f, m)); break;
        case 1: s.objects.push_back(meshObject(name, box, at + Vec3{0, 0.6f, 0}, Vec3{1.2f, 1.2f, 1.2f}, 25.0f, m)); break;
        case 2: s.objects.push_back(meshObject(name, cylinder, at + Vec3{0, 0.9f, 0}, Vec3{1.2f, 1.8f, 1.2f}, 0.0f, m)); break;
        case 3: s.objects.push_back(meshObject(name, cone, at + Vec3{0, 1.0f, 0}, Vec3{1.4f, 2.0f, 1.4f}, 0.0f, m)); break;
        default: s.objects.push_back(meshObject(name, torus, at + Vec3{0, 0.3f, 0}, Vec3{2.0f, 2.0f, 2.0f}, 0.0f, m)); break;
        }
    }
    s.lights.push_back(pointLight({4, 10, 6}, 0.8f));
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {-6, 8, 4};
    spot.direction = normalize(Vec3{0, 0, 0} - spot.position);
    spot.intensity = Rgb{0.5f, 0.45f, 0.35f};
    spot.coneAngleDeg = 35.0f;
    spot.falloffAngleDeg = 10.0f;
    s.lights.push_back(spot);
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 4, 12}, {0, 1.2f, 0}, 45.0f);
    s.cameraPath = orbit({0, 0, 0}, 1.5f);
    s.defaultFrames = 48;
    return s;
}

Scene parallaxScene() {
    Scene s;
    s.name = "parallax";
    s.objects.push_back(floorObject(100.0f));
    s.objects.push_back(sphere("left-mirror", {-2.5f, 1.5f, 0}, 1.5f, mirror(Rgb{0.1f}, 0.85f)));
    s.objects.push_back(sphere("right-mirror", {2.5f, 1.5f, 0}, 1.5f, mirror(Rgb{0.1f}, 0.85f)));
    s.objects.push_back(meshObject("near-box", makeBox(), {0, 0.5f, 2.5f}, {1, 1, 1}, 30.0f,
                                   matte(Rgb{0.85f, 0.3f, 0.2f})));
    s.objects.push_back(wallObject("far-wall", {0, 10, -15}, 40.0f,
                                   checker(Rgb{0.2f, 0.5f, 0.8f}, Rgb{0.9f, 0.9f, 0.8f}, 20.0f)));
    s.lights.push_back(pointLight({3, 10, 8}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({-4, 2.5f, 10}, {0, 1.5f, 0}, 45.0f);
    CameraPath path;
    path.kind = CameraPathKind::Keyframes;
    path.keyframes = {camera({-4, 2.5f, 10}, {0, 1.5f, 0}, 45.0f), camera({4, 2.5f, 10}, {0, 1.5f, 0}, 45.0f)};
    path.framesPerSegment = 24;
    s.cameraPath = path;
    s.defaultFrames = 25;
    return s;
}

Scene glassScene() {
    Scene s;
    s.name = "glass";
    s.objects.push_back(floorObject(100.0f));
    s.objects.push_back(sphere("glass-sphere", {-1.4f, 1.2f, 0}, 1.2f, glass()));
    s.objects.push_back(meshObject("glass-box", makeBox(), {1.6f, 1.01f, 0.3f}, {1.8f, 2.0f, 1.8f}, 30.0f, glass()));
    s.objects.push_back(wallObject("background", {0, 6, -5}, 24.0f,
                                   checker(Rgb{0.9f, 0.3f, 0.2f}, Rgb{0.95f, 0.9f, 0.6f}, 12.0f)));
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = normalize(Vec3{-0.4f, -1.0f, -0.5f});
    sun.intensity = Rgb{0.9f};
    s.lights.push_back(sun);
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 2.5f, 8}, {0, 1.2f, 0}, 45.0f);
    s.cameraPath = orbit({0, 1, 0}, 1.0f);
    s.defaultFrames = 30;
    return s;
}

Scene shapesScene() {
    Scene s;
    s.name = "shapes";
    s.objects.push_back(floorObject(100.0f));
    s.objects.push_back(meshObject("cone", makeCone(96), {-3, 1.25f, 0}, {2.0f, 2.5f, 2.0f}, 0.0f, mirror()));
    s.objects.push_back(meshObject("cylinder", makeCylinder(96), {0, 1.25f, -0.5f}, {2.0f, 2.5f, 2.0f}, 0.0f, mirror()));
    s.objects.push_back(meshObject("torus", makeTorus(0.35f, 0.15f, 96, 48), {3, 0.45f, 0}, {3, 3, 3}, 0.0f, mirror()));
    s.objects.push_back(sphere("red-ball", {0, 0.6f, 2.5f}, 0.6f, matte(paletteColor(0))));
    s.objects.push_back(sphere("blue-ball", {-1.8f, 0.5f, 3.0f}, 0.5f, matte(paletteColor(2))));
    s.lights.push_back(pointLight({4, 10, 8}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 4, 10}, {0, 1, 0}, 45.0f);
    s.cameraPath = orbit({0, 1, 0}, 1.5f);
    s.defaultFrames = 30;
    return s;
}

// Concave mirrors that see themselves: a mirror bowl tipped toward the
// camera with a ball inside, and a mirror torus whose inner ring faces
// itself. What a mirror shows of its own surface is what a cache built from
// its centre cannot hold (docs/caching.md, "The object's own surface").
Scene bowlScene() {
    Scene s;
    s.name = "bowl";
    s.objects.push_back(floorObject(100.0f));
    const Transform tipped = Transform::translate({-1.2f, 1.55f, 0}) * Transform::rotate({1, 0, 0}, 40.0f) *
                             Transform::scale({3.2f, 3.2f, 3.2f});
    s.objects.push_back(SceneObject{"bowl", MeshShape{std::make_shared<const TriangleMesh>(transformed(makeBowl(), tipped))},
                                    mirror(Rgb{0.1f}, 0.85f), Vec3{-1.2f, 1.55f, 0}});
    s.objects.push_back(sphere("ball-in-bowl", {-1.2f, 0.86f, -0.58f}, 0.45f, matte(paletteColor(0))));
    s.objects.push_back(meshObject("torus", makeTorus(0.35f, 0.15f, 96, 48), {2.4f, 0.45f, 0.6f}, {3, 3, 3}, 0.0f, mirror()));
    s.objects.push_back(sphere("yellow-ball", {2.4f, 0.5f, 0.6f}, 0.5f, matte(paletteColor(4))));
    s.objects.push_back(meshObject("box", makeBox(), {0.6f, 0.5f, -2.2f}, {1, 1, 1}, 20.0f, matte(paletteColor(2))));
    s.lights.push_back(pointLight({4, 10, 8}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 4.5f, 8.5f}, {0.4f, 1.0f, 0}, 45.0f);
    s.cameraPath = orbit({0.4f, 1.0f, 0}, 1.5f);
    s.defaultFrames = 30;
    return s;
}

// ---- animated scenes (scene/Animation.h) ----------------------------------

// Makes the last object added animated, its shape as built the rest shape.
ObjectAnimation& animateLast(Scene& s) {
    const auto index = static_cast<int>(s.objects.size()) - 1;
    const SceneObject& object = s.objects.back();
    s.animation.objects.push_back(ObjectAnimation{index, std::nullopt, nullptr, object.shape, object.origin});
    return s.animation.objects.back();
}

TransformKey moveKey(float time, const Vec3& translate, float yawDeg = 0.0f) {
    return TransformKey{time, translate, Quaternion::fromAxisAngle({0, 1, 0}, yawDeg), {1, 1, 1}};
}

// `room` with a ball bouncing left and right between the mirror ball and the camera.
Scene roomMovingScene() {
    Scene s = roomScene();
    s.name = "room-moving";
    s.objects.push_back(sphere("bouncing-ball", {-4.0f, 0.6f, 3.0f}, 0.6f, matte(Rgb{0.9f, 0.15f, 0.1f})));
    TransformTrack track;
    // Across in 2 s and back in 2 s, two bounces each way (|sin| arcs, 1 s each).
    constexpr int kKeys = 32;
    for (int k = 0; k <= kKeys; ++k) {
        const float t = 4.0f * static_cast<float>(k) / kKeys;
        const float across = t < 2.0f ? t / 2.0f : 2.0f - t / 2.0f;
        const float height = 2.0f * std::fabs(std::sin(std::numbers::pi_v<float> * t));
        track.keys.push_back(moveKey(t, {8.0f * across, height, 0.0f}));
    }
    animateLast(s).transform = track;
    s.cameraPath = CameraPath{};  // a still camera: what changes is the scene
    s.defaultFrames = 48;
    return s;
}

// Spheres circling a glass sphere at different heights, radii and speeds.
Scene orbitScene() {
    Scene s;
    s.name = "orbit";
    s.objects.push_back(floorObject(100.0f));
    s.objects.push_back(sphere("glass-core", {0, 1.3f, 0}, 1.2f, glass()));
    struct Orbiter {
        float radius, height, size, period;
        bool reflective;
    };
    const std::array<Orbiter, 4> orbiters{{{3.0f, 0.7f, 0.6f, 4.0f, true},
                                           {3.6f, 1.8f, 0.5f, 6.0f, false},
                                           {2.6f, 2.6f, 0.4f, 3.0f, false},
                                           {4.2f, 1.0f, 0.7f, 8.0f, true}}};
    for (std::size_t i = 0; i < orbiters.size(); ++i) {
        const Orbiter& o = orbiters[i];
        const Material m = o.reflective ? mirror(paletteColor(static_cast<int>(i)), 0.6f)
                                        : matte(paletteColor(static_cast<int>(i)));
        s.objects.push_back(sphere("orbiter" + std::to_string(i), {o.radius, o.height, 0}, o.size, m));
        // A turn about the y axis in keys 90° apart (slerp takes the shorter way).
        TransformTrack track;
        for (int k = 0; k <= 4; ++k)
            track.keys.push_back(moveKey(o.period * static_cast<float>(k) / 4.0f, {0, 0, 0}, 90.0f * static_cast<float>(k)));
        animateLast(s).transform = track;
    }
    s.lights.push_back(pointLight({4, 10, 6}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 4, 10}, {0, 1.2f, 0}, 45.0f);
    s.defaultFrames = 60;
    return s;
}

// A ~90k-triangle sheet folding over a sphere, a mirror ball beside it.
Scene clothScene() {
    Scene s;
    s.name = "cloth";
    s.objects.push_back(floorObject(100.0f));
    const ClothDrapeShape shape;
    s.objects.push_back(sphere("support", shape.sphereCenter, shape.sphereRadius, matte(Rgb{0.6f})));
    s.objects.push_back(sphere("mirror-ball", {3.4f, 1.3f, 1.0f}, 1.3f, mirror()));
    auto drape = std::make_shared<const ClothDrape>(shape);
    Material cloth = checker(Rgb{0.8f, 0.2f, 0.25f}, Rgb{0.95f, 0.9f, 0.8f}, 8.0f);
    s.objects.push_back(SceneObject{"cloth", MeshShape{std::make_shared<const TriangleMesh>(drape->restMesh())},
                                    cloth, shape.sphereCenter});
    animateLast(s).deformation = drape;
    s.lights.push_back(pointLight({4, 10, 6}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({-1.5f, 4.5f, 9.5f}, {0.8f, 1.0f, 0}, 45.0f);
    s.defaultFrames = 60;
    return s;
}

// `grid-8` lit by a light sweeping from left to right and back.
Scene lightSweepScene() {
    Scene s = gridScene(8);
    s.name = "light-sweep";
    LightTrack track;
    track.light = 0;
    const Light& light = s.lights[0];
    for (const auto& [t, x] : {std::pair{0.0f, -14.0f}, std::pair{2.0f, 14.0f}, std::pair{4.0f, -14.0f}})
        track.keys.push_back(LightKey{t, {x, light.position.y, light.position.z}, light.direction, light.intensity});
    track.interpolation = Interpolation::Smooth;
    s.animation.lights.push_back(track);
    s.cameraPath = CameraPath{};
    s.defaultFrames = 60;
    return s;
}

struct Entry {
    BuiltinSceneInfo info;
    std::function<Scene()> make;
};

// "1 mirror sphere", "0 mirror spheres", "32 mirror spheres".
std::string countOf(int n, const std::string& noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

std::vector<Entry> registry() {
    std::vector<Entry> entries;
    for (int n : kBehindCounts)
        entries.push_back({{"behind-" + std::to_string(n),
                            "mirror sphere facing the camera, " + countOf(n, "mirror sphere") +
                                " behind the camera (Table 5.1)"},
                           [n] { return behindScene(n); }});
    for (int n : kGridCounts)
        entries.push_back({{"grid-" + std::to_string(n),
                            countOf(n, "mirror sphere") + " in a grid in front of the camera (Table 5.2)"},
                           [n] { return gridScene(n); }});
    entries.push_back({{"diffuse-32", "1 mirror + 31 diffuse spheres, framed for 1920x1080 (Table 5.3)"},
                       [] { return wallOf32("diffuse-32", false); }});
    entries.push_back({{"reflective-32", "32 mirror spheres, framed for 1920x1080 (Table 5.3)"},
                       [] { return wallOf32("reflective-32", true); }});
    entries.push_back({{"room", "checkerboard floor, 10 diffuse objects around a mirror sphere (Fig 5.1)"},
                       roomScene});
    entries.push_back({{"parallax", "two facing mirror spheres, a near box and a far wall (Fig 3.5)"},
                       parallaxScene});
    entries.push_back({{"glass", "refractive sphere and box before a checkered wall"}, glassScene});
    entries.push_back({{"shapes", "mirror cone, cylinder and torus (concave) (Fig 5.10/5.11)"}, shapesScene});
    entries.push_back({{"bowl", "concave mirrors that see themselves: a tipped mirror bowl with a ball inside, a mirror torus"},
                       bowlScene});
    entries.push_back({{"room-moving", "animated: `room` with a ball bouncing past the mirror ball"}, roomMovingScene});
    entries.push_back({{"orbit", "animated: spheres circling a glass sphere"}, orbitScene});
    entries.push_back({{"cloth", "animated: a 90k-triangle sheet folding over a sphere beside a mirror ball"},
                       clothScene});
    entries.push_back({{"light-sweep", "animated: `grid-8` under a light sweeping across"}, lightSweepScene});
    return entries;
}

}  // namespace
}  // namespace builtin

std::vector<BuiltinSceneInfo> builtinScenes() {
    std::vector<BuiltinSceneInfo> infos;
    for (const builtin::Entry& e : builtin::registry()) infos.push_back(e.info);
    return infos;
}

std::optional<Scene> makeBuiltinScene(std::string_view name) {
    for (const builtin::Entry& e : builtin::registry()) {
        if (e.info.name != name) continue;
        Scene scene = e.make();
        poseScene(scene, 0.0f, scene);  // what a still render of an animated scene shows
        return scene;
    }
    return std::nullopt;
}

}  // namespace raycache
