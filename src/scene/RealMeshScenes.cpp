#include "scene/RealMeshScenes.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <memory>

#include "core/Box3.h"
#include "core/Errors.h"
#include "scene/BuiltinSceneParts.h"
#include "scene/MeshGenerators.h"
#include "scene/MeshLoader.h"

namespace raycache {

// Inside builtin:: so that the parts (scene/BuiltinSceneParts.h) need no qualification.
namespace builtin {
namespace {

const std::string kBunnyFile = "bunny.obj";
const std::string kTeapotFile = "teapot.obj";
const std::string kDragonFile = "dragon_vrip.ply";

// Reads the scene's mesh files, keeping each file's repair note for the scene.
class MeshFiles {
public:
    MeshFiles(std::string sceneName, const MeshSearchPath& searchPath, std::vector<std::string>& notes)
        : sceneName_(std::move(sceneName)), searchPath_(searchPath), notes_(notes) {}

    TriangleMesh load(const std::string& fileName) {
        const std::optional<std::filesystem::path> path = searchPath_.find(fileName);
        if (!path)
            throw InputError("built-in scene '" + sceneName_ + "': " +
                             missingFileLine(fileName, searchPath_));
        try {
            LoadedMesh loaded = loadMeshFile(*path);
            if (!loaded.note.empty()) notes_.push_back(std::move(loaded.note));
            requireHeight(loaded.mesh, *path);
            return std::move(loaded.mesh);
        } catch (const InputError& e) {
            // The loader names the file and what is wrong; say which scene wanted it.
            throw InputError("built-in scene '" + sceneName_ + "': " + e.what());
        }
    }

    static std::string missingFileLine(const std::string& fileName, const MeshSearchPath& searchPath) {
        return fileName + " is in none of " + searchPath.describe() +
               ": run scripts/install-deps.sh (it fetches the meshes that are not committed) or set "
               "RAYCACHE_MESH_PATH to a directory holding it";
    }

private:
    // standing() scales a mesh to a height: one (nearly) flat in y would
    // become infinite or enormous. Turning about y keeps the height, so the
    // file's own box decides.
    static void requireHeight(const TriangleMesh& mesh, const std::filesystem::path& path) {
        Box3 box;
        for (const Vec3& p : mesh.positions) box.add(p);
        const float size = std::max({std::fabs(box.lo.x), std::fabs(box.lo.y), std::fabs(box.lo.z),
                                     std::fabs(box.hi.x), std::fabs(box.hi.y), std::fabs(box.hi.z), 1e-30f});
        if (!(box.hi.y - box.lo.y > 1e-6f * size))
            failFile(path.string(), "is flat in y (height " + std::to_string(box.hi.y - box.lo.y) +
                                        "): a built-in scene stands its mesh up to a height");
    }

    std::string sceneName_;
    const MeshSearchPath& searchPath_;
    std::vector<std::string>& notes_;
};

// `mesh` turned by `yawDeg` about y, scaled uniformly to `height` and set on
// the ground at `foot` (its box's bottom centre there). The caching cube's
// centre, the object's origin, is the middle of its box.
SceneObject standing(std::string name, const TriangleMesh& mesh, const Vec3& foot, float height, float yawDeg,
                     Material material) {
    const Transform turn = Transform::rotate({0, 1, 0}, yawDeg);
    Box3 box;
    for (const Vec3& p : transformed(mesh, turn).positions) box.add(p);
    const float scale = height / (box.hi.y - box.lo.y);
    const Vec3 bottomCentre{0.5f * (box.lo.x + box.hi.x), box.lo.y, 0.5f * (box.lo.z + box.hi.z)};
    const Transform place = Transform::translate(foot - bottomCentre * scale) *
                            Transform::scale({scale, scale, scale}) * turn;
    return SceneObject{std::move(name), MeshShape{std::make_shared<const TriangleMesh>(transformed(mesh, place))},
                       std::move(material), foot + Vec3{0, 0.5f * height, 0}};
}

// Glazed ceramic: a matte color with a strong, tight highlight.
Material glazed(const Rgb& color) {
    Material m = matte(color);
    m.specular = Rgb{0.6f};
    m.shininess = 80.0f;
    return m;
}

// The bunny in glass before a checkered wall, with a mirror ball and two
// matte balls to refract. Seen through its thin ears and flanks, rays meet
// the inside of the surface beyond the critical angle (41.8° at ior 1.5) and
// reflect back in: the bright and dark patches that outline the bunny.
Scene bunnyGlassScene(const MeshSearchPath& searchPath) {
    Scene s;
    s.name = "bunny-glass";
    MeshFiles files(s.name, searchPath, s.notes);
    s.objects.push_back(floorObject(100.0f));
    s.objects.push_back(standing("glass-bunny", files.load(kBunnyFile), {0, 0, 0}, 3.2f, 20.0f, glass()));
    s.objects.push_back(wallObject("background", {0, 6, -5}, 24.0f,
                                   checker(Rgb{0.2f, 0.5f, 0.8f}, Rgb{0.95f, 0.9f, 0.8f}, 12.0f)));
    s.objects.push_back(sphere("mirror-ball", {2.7f, 0.9f, -1.4f}, 0.9f, mirror()));
    s.objects.push_back(sphere("red-ball", {-2.5f, 0.6f, 0.6f}, 0.6f, matte(paletteColor(0))));
    s.objects.push_back(sphere("yellow-ball", {1.8f, 0.45f, 1.7f}, 0.45f, matte(paletteColor(3))));
    s.lights.push_back(pointLight({4, 10, 6}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 2.6f, 8.5f}, {0, 1.4f, 0}, 45.0f);
    s.cameraPath = orbit({0, 1.4f, 0}, 1.5f);
    s.defaultFrames = 48;
    return s;
}

// The teapot on a ring of six spheres: five tinted mirrors and one glass.
Scene teapotMirrorsScene(const MeshSearchPath& searchPath) {
    Scene s;
    s.name = "teapot-mirrors";
    MeshFiles files(s.name, searchPath, s.notes);
    s.objects.push_back(floorObject(100.0f));
    s.objects.push_back(standing("teapot", files.load(kTeapotFile), {0, 0, 0}, 2.0f, -30.0f,
                                 glazed(Rgb{0.8f, 0.15f, 0.1f})));
    // 60° apart from +x, leaving the front (+z, toward the camera) open.
    for (int i = 0; i < 6; ++i) {
        const float a = 60.0f * static_cast<float>(i) * std::numbers::pi_v<float> / 180.0f;
        const float r = i % 2 == 0 ? 0.9f : 0.75f;
        const Vec3 c{3.4f * std::cos(a), r, 3.4f * std::sin(a)};
        if (i == 2) s.objects.push_back(sphere("glass-sphere", c, r, glass()));
        else s.objects.push_back(sphere("mirror" + std::to_string(i), c, r, mirror(paletteColor(i), 0.8f)));
    }
    s.lights.push_back(pointLight({5, 10, 7}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 4, 9}, {0, 0.9f, 0}, 45.0f);
    s.cameraPath = orbit({0, 0.9f, 0}, 1.5f);
    s.defaultFrames = 48;
    return s;
}

// The dragon in jade, 3.2 high, standing at the origin: both dragon scenes'.
SceneObject jadeDragon(MeshFiles& files) {
    Material jade = matte(Rgb{0.35f, 0.6f, 0.42f});
    jade.specular = Rgb{0.35f};
    jade.shininess = 48.0f;
    return standing("dragon", files.load(kDragonFile), {0, 0, 0}, 3.2f, 0.0f, jade);
}

// The dragon in a hall of mirrors: two rows of mirror balls on pedestals
// down both sides, a large mirror ball behind it and a glass ball in front.
// Balls rather than tall mirror columns: a column's cube, one direction per
// texel for the whole height, would give every height the reflection of one
// (the documents' "conflicting rays"), and the columns turned to noise.
Scene dragonHallScene(const MeshSearchPath& searchPath) {
    Scene s;
    s.name = "dragon-hall";
    MeshFiles files(s.name, searchPath, s.notes);
    s.objects.push_back(floorObject(100.0f));
    s.objects.push_back(jadeDragon(files));
    const TriangleMesh pedestal = makeCylinder(48);
    for (int side = 0; side < 2; ++side) {
        for (int k = 0; k < 4; ++k) {
            const int i = side * 4 + k;
            const float x = side == 0 ? -3.6f : 3.6f, z = -7.5f + 3.0f * static_cast<float>(k);
            s.objects.push_back(meshObject("pedestal" + std::to_string(i), pedestal, {x, 0.8f, z},
                                           {1.0f, 1.6f, 1.0f}, 0.0f, matte(Rgb{0.8f, 0.78f, 0.72f})));
            s.objects.push_back(sphere("mirror" + std::to_string(i), {x, 2.5f, z}, 0.9f,
                                       mirror(paletteColor(i), 0.75f)));
        }
    }
    s.objects.push_back(sphere("mirror-ball", {0, 2.0f, -6.0f}, 2.0f, mirror(Rgb{0.1f}, 0.85f)));
    s.objects.push_back(sphere("glass-ball", {1.8f, 0.7f, 2.6f}, 0.7f, glass()));
    s.objects.push_back(wallObject("back-wall", {0, 6, -10}, 30.0f,
                                   checker(Rgb{0.75f, 0.35f, 0.25f}, Rgb{0.95f, 0.88f, 0.7f}, 15.0f)));
    s.lights.push_back(pointLight({4, 12, 8}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 4.5f, 12}, {0, 1.8f, -1}, 45.0f);
    s.cameraPath = orbit({0, 1.8f, -1}, 1.0f);
    s.defaultFrames = 40;
    return s;
}

// The dragon among large mirrors: three mirror balls behind and beside it
// and a glass ball before it, together a third or more of the view, so that
// most cached trees meet the dragon's 871k triangles. Where the hall keeps
// its mirrors small and far, this one asks whether
// caching pays on a real mesh when mirrors and glass fill the view
// (docs/caching.md, "When caching pays").
Scene dragonMirrorsScene(const MeshSearchPath& searchPath) {
    Scene s;
    s.name = "dragon-mirrors";
    MeshFiles files(s.name, searchPath, s.notes);
    s.objects.push_back(floorObject(100.0f));
    s.objects.push_back(jadeDragon(files));
    s.objects.push_back(sphere("mirror-back", {0, 2.4f, -4.2f}, 2.4f, mirror(Rgb{0.1f}, 0.85f)));
    s.objects.push_back(sphere("mirror-left", {-4.0f, 2.0f, -0.6f}, 2.0f, mirror(paletteColor(1), 0.8f)));
    s.objects.push_back(sphere("mirror-right", {4.0f, 2.0f, -0.6f}, 2.0f, mirror(paletteColor(4), 0.8f)));
    s.objects.push_back(sphere("glass-ball", {2.1f, 0.9f, 2.4f}, 0.9f, glass()));
    s.lights.push_back(pointLight({4, 12, 8}));
    s.environment = Environment::constant(kSky);
    s.camera = camera({0, 3.2f, 9.0f}, {0, 1.6f, -1}, 45.0f);
    s.cameraPath = orbit({0, 1.6f, -1}, 1.0f);
    s.defaultFrames = 40;
    return s;
}

struct RealMeshEntry {
    RealMeshSceneInfo info;
    std::function<Scene(const MeshSearchPath&)> make;
};

std::vector<RealMeshEntry> realMeshRegistry() {
    return {
        {{"bunny-glass", "the Stanford bunny in glass (total internal reflection) beside a mirror ball", {kBunnyFile}},
         bunnyGlassScene},
        {{"teapot-mirrors", "the Utah teapot on a ring of five mirror spheres and a glass one", {kTeapotFile}},
         teapotMirrorsScene},
        {{"dragon-hall", "the Stanford dragon (871k triangles) between rows of mirror balls on pedestals", {kDragonFile}},
         dragonHallScene},
        {{"dragon-mirrors", "the Stanford dragon among three large mirror balls and a glass one (a third of the view)",
          {kDragonFile}},
         dragonMirrorsScene},
    };
}

}  // namespace
}  // namespace builtin

std::vector<RealMeshSceneInfo> realMeshScenes() {
    std::vector<RealMeshSceneInfo> infos;
    for (const builtin::RealMeshEntry& e : builtin::realMeshRegistry()) infos.push_back(e.info);
    return infos;
}

std::string missingMeshFiles(const RealMeshSceneInfo& scene, const MeshSearchPath& searchPath) {
    for (const std::string& file : scene.meshFiles)
        if (!searchPath.find(file)) return builtin::MeshFiles::missingFileLine(file, searchPath);
    return {};
}

std::optional<Scene> makeRealMeshScene(std::string_view name, const MeshSearchPath& searchPath) {
    for (const builtin::RealMeshEntry& e : builtin::realMeshRegistry())
        if (e.info.name == name) return e.make(searchPath);
    return std::nullopt;
}

}  // namespace raycache
