#include "scene/SceneFile.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/DisplayTransform.h"
#include "core/Errors.h"
#include "core/TextFormat.h"
#include "core/Transform.h"
#include "scene/GltfScene.h"
#include "scene/ImageLoader.h"
#include "scene/JsonPositions.h"
#include "scene/MeshGenerators.h"
#include "scene/MeshLimits.h"
#include "scene/MeshLoader.h"
#include "scene/ScenePose.h"

namespace raycache {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;
using Keys = std::initializer_list<std::string_view>;

// Count limits: far beyond any real scene, low enough that a slipped digit is
// reported instead of costing minutes or gigabytes.
constexpr std::size_t kMaxObjects = 100000;
constexpr std::size_t kMaxMaterials = 10000;
constexpr std::size_t kMaxKeyframes = 10000;
constexpr std::size_t kMaxRotations = 64;
constexpr int kMaxFrames = 1000000;
constexpr int kMaxFramesPerSegment = 100000;
// Meshes and images live in their own files, so a scene file is small; a huge
// one is the wrong file.
constexpr std::uintmax_t kMaxSceneFileBytes = 64u << 20;

// A string as a JSON literal: quoted, and escaped so messages stay one line.
std::string quote(std::string_view s) {
    return json(std::string(s)).dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string describeType(const json& v) {
    switch (v.type()) {
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: return "a string";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::null: return "null";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "a number";
    default: return "an unsupported value";
    }
}

std::string join(const std::vector<std::string_view>& items) {
    std::string s;
    for (const auto& item : items) {
        if (!s.empty()) s += ", ";
        s += item;
    }
    return s;
}

// Case-insensitive Levenshtein distance, for "did you mean" suggestions.
std::size_t editDistance(std::string_view a, std::string_view b) {
    const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            const std::size_t substitute = diagonal + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1);
            row[j] = std::min({above + 1, row[j - 1] + 1, substitute});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// The candidate closest to `word` if it is close enough to be a likely typo.
std::optional<std::string_view> closest(std::string_view word, const std::vector<std::string_view>& candidates) {
    const std::size_t limit = std::max<std::size_t>(1, std::min<std::size_t>(3, word.size() / 3));
    std::optional<std::string_view> best;
    std::size_t bestDistance = limit + 1;
    for (const auto& c : candidates) {
        const std::size_t d = editDistance(word, c);
        if (d < bestDistance) {
            bestDistance = d;
            best = c;
        }
    }
    return best;
}

std::string didYouMean(std::string_view word, const std::vector<std::string_view>& candidates) {
    const auto best = closest(word, candidates);
    return best ? "did you mean " + quote(*best) + "?" : std::string();
}

bool contains(Keys keys, std::string_view key) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
}

template <class E>
struct Choice {
    std::string_view name;
    E value;
};

// The choices of `values` under the names `name` gives them, for tables
// whose names the command line shares (CameraPath.h, PipelineKind.h, ...).
template <class E, std::size_t N, class Name>
constexpr std::array<Choice<E>, N> choicesOf(const std::array<E, N>& values, Name name) {
    std::array<Choice<E>, N> choices{};
    for (std::size_t i = 0; i < N; ++i) choices[i] = {name(values[i]), values[i]};
    return choices;
}
constexpr auto kPathKinds = choicesOf(kCameraPathKinds, cameraPathKindName);
constexpr auto kPipelineChoices = choicesOf(kPipelineKinds, pipelineKindName);
constexpr auto kAcceleratorChoices = choicesOf(kAccelerators, acceleratorName);
constexpr auto kViewTransformChoices = choicesOf(kViewTransforms, viewTransformName);
constexpr auto kReflectionChoices = choicesOf(kReprojectedReflections, reprojectedReflectionsName);
constexpr std::array<Choice<Interpolation>, 2> kInterpolations{
    {{"linear", Interpolation::Linear}, {"smooth", Interpolation::Smooth}}};
constexpr std::array<Choice<Wrap>, 2> kWraps{{{"loop", Wrap::Loop}, {"clamp", Wrap::Clamp}}};
enum class EnvironmentKind { Color, Equirect, Cube };
constexpr std::array<Choice<EnvironmentKind>, 3> kEnvironmentKinds{{{"color", EnvironmentKind::Color},
                                                                    {"equirect", EnvironmentKind::Equirect},
                                                                    {"cube", EnvironmentKind::Cube}}};
constexpr std::array<Choice<LightType>, 3> kLightTypes{{{"point", LightType::Point},
                                                        {"directional", LightType::Directional},
                                                        {"spot", LightType::Spot}}};
enum class TextureKind { Image, Checker };
constexpr std::array<Choice<TextureKind>, 2> kTextureKinds{{{"image", TextureKind::Image},
                                                            {"checker", TextureKind::Checker}}};
constexpr auto kCacheTechniqueChoices = [] {
    std::array<Choice<CacheTechnique>, kCacheTechniques.size()> choices{};
    for (std::size_t i = 0; i < kCacheTechniques.size(); ++i)
        choices[i] = {kCacheTechniques[i].name, kCacheTechniques[i].technique};
    return choices;
}();
enum class ShapeKind { Sphere, Mesh, Plane, Box, Cylinder, Cone, Torus, Bowl };
constexpr std::array<Choice<ShapeKind>, 8> kShapeKinds{{{"sphere", ShapeKind::Sphere},
                                                        {"mesh", ShapeKind::Mesh},
                                                        {"plane", ShapeKind::Plane},
                                                        {"box", ShapeKind::Box},
                                                        {"cylinder", ShapeKind::Cylinder},
                                                        {"cone", ShapeKind::Cone},
                                                        {"torus", ShapeKind::Torus},
                                                        {"bowl", ShapeKind::Bowl}}};

// A value in the document and its JSON pointer. `value` is null when an
// optional member is absent.
struct Node {
    const json* value = nullptr;
    std::string ptr;

    explicit operator bool() const { return value != nullptr; }
    const json& operator*() const { return *value; }
    const json* operator->() const { return value; }
};

// Interval a number must lie in; unset ends are unbounded.
struct Range {
    std::optional<double> lo, hi;
    bool loInclusive = true, hiInclusive = true;

    bool contains(double v) const {
        if (lo && (loInclusive ? v < *lo : v <= *lo)) return false;
        if (hi && (hiInclusive ? v > *hi : v >= *hi)) return false;
        return true;
    }
    std::string describe() const {
        if (lo && hi && loInclusive && hiInclusive)
            return "must be between " + formatShortest(*lo) + " and " + formatShortest(*hi);
        std::string s = "must be";
        if (lo) s += std::string(loInclusive ? " >= " : " > ") + formatShortest(*lo);
        if (lo && hi) s += " and";
        if (hi) s += std::string(hiInclusive ? " <= " : " < ") + formatShortest(*hi);
        return s;
    }
};
Range positive() { return {0.0, std::nullopt, false, true}; }
Range nonNegative() { return {0.0, std::nullopt, true, true}; }
Range closed(double lo, double hi) { return {lo, hi, true, true}; }

// An object's world transform as written, kept apart so spheres can reject
// what they cannot represent.
struct ObjectTransform {
    Transform matrix;
    Vec3 translate{0.0f, 0.0f, 0.0f};
    Node rotate;  // absent when there is no rotation
    Node scale;   // absent when there is no scale
    Vec3 scaleFactors{1.0f, 1.0f, 1.0f};
    bool identity = true;
};

class SceneFileReader {
public:
    SceneFileReader(std::string fileLabel, fs::path baseDir, const JsonPositions& positions)
        : fileLabel_(std::move(fileLabel)), baseDir_(std::move(baseDir)), positions_(positions) {}

    Scene read(const json& root, const std::string& defaultName) {
        const Node r{&root, ""};
        expectObject(r, {"name", "include", "camera", "path", "frames", "fps", "environment", "lights", "materials",
                         "objects", "pipeline", "accel", "renderCache", "cacheBudget", "exposure", "viewTransform"});
        Scene scene;
        // An included glTF scene is where the scene starts; every key below changes it.
        const Node include = child(r, "include");
        if (include)
            scene = includedScene(include, {.camera = bool(child(r, "camera")), .lights = bool(child(r, "lights"))});
        scene.name = defaultName;
        if (const Node n = child(r, "name")) scene.name = nonEmptyString(n);
        // Keys the camera object leaves out keep the included (or default) camera's values.
        if (const Node n = child(r, "camera")) scene.camera = camera(n, scene.camera);

        int pathFrames = 1;
        if (const Node n = child(r, "path")) {
            scene.cameraPath = path(n, scene.camera, pathFrames);
            if (scene.cameraPath.kind == CameraPathKind::Keyframes) scene.camera = scene.cameraPath.keyframes.front();
        }
        scene.defaultFrames = pathFrames;
        if (const Node n = child(r, "frames")) scene.defaultFrames = integer(n, 1, kMaxFrames);
        if (const Node n = child(r, "pipeline")) scene.render.pipeline = oneOf(n, kPipelineChoices);
        if (const Node n = child(r, "accel")) scene.render.accel = oneOf(n, kAcceleratorChoices);
        if (const Node n = child(r, "cacheBudget")) scene.render.cacheBudgetMiB = number(n, {0.0, 1e9, false, true});
        if (const Node n = child(r, "renderCache")) renderCache(n, scene.render.renderCache);
        if (const Node n = child(r, "exposure"))
            scene.render.exposure = number(n, closed(-kMaxExposureStops, kMaxExposureStops));
        if (const Node n = child(r, "viewTransform")) scene.render.viewTransform = oneOf(n, kViewTransformChoices);

        if (const Node n = child(r, "environment")) scene.environment = environment(n);
        if (const Node n = child(r, "fps")) scene.fps = number(n, {0.0, 1000.0, false, true});
        if (const Node n = child(r, "lights")) {
            for (const Node& l : elements(n, 0, kMaxLights, "lights")) {
                scene.lights.push_back(light(l));
                if (const Node a = child(l, "animation")) {
                    LightTrack track = lightTrack(a, scene.lights.back());
                    track.light = static_cast<int>(scene.lights.size()) - 1;
                    scene.animation.lights.push_back(std::move(track));
                }
            }
        }
        if (const Node n = child(r, "materials")) materials(n);
        if (include && include->is_object())
            if (const Node n = child(include, "materials")) includedMaterials(n, scene);
        // An included scene brings objects of its own; without one, the list is required.
        if (const Node n = include ? child(r, "objects") : required(r, "objects")) objects(n, scene);
        poseScene(scene, 0.0f, scene);  // a still render shows time 0
        scene.notes = std::move(notes_);
        return scene;
    }

private:
    // ---- errors ---------------------------------------------------------

    [[noreturn]] void fail(const std::string& ptr, const std::string& what, bool atKey = false) const {
        const TextPosition p = atKey ? positions_.keyAt(ptr) : positions_.valueAt(ptr);
        std::string oneLine = what;
        std::replace(oneLine.begin(), oneLine.end(), '\n', ' ');
        throw InputError(InputLocation{.file = fileLabel_, .line = p.line, .column = p.column, .jsonPath = ptr},
                         oneLine);
    }
    [[noreturn]] void fail(const Node& n, const std::string& what) const { fail(n.ptr, what); }
    [[noreturn]] void failType(const Node& n, const std::string& expected) const {
        fail(n, "expected " + expected + ", got " + describeType(*n));
    }

    // ---- structure ------------------------------------------------------

    Node child(const Node& object, std::string_view key) const {
        const auto it = object->find(key);
        return {it == object->end() ? nullptr : &*it, appendJsonPointer(object.ptr, key)};
    }

    Node required(const Node& object, std::string_view key) const {
        Node n = child(object, key);
        if (!n) fail(object, "missing required key " + quote(key));
        return n;
    }

    // The first key of object `n`, in file order, that is not in `keys`.
    // (nlohmann::json keeps members sorted by name, not in file order.)
    std::optional<std::string> firstKeyNotIn(const Node& n, Keys keys) const {
        std::optional<std::string> first;
        std::pair<int, int> firstAt{std::numeric_limits<int>::max(), 0};
        for (const auto& item : n->items()) {
            if (contains(keys, item.key())) continue;
            const TextPosition p = positions_.keyAt(appendJsonPointer(n.ptr, item.key()));
            if (const std::pair<int, int> at{p.line, p.column}; !first || at < firstAt) {
                first = item.key();
                firstAt = at;
            }
        }
        return first;
    }

    // Checks `n` is an object whose keys are all in `known`.
    void expectObject(const Node& n, Keys known) const {
        if (!n->is_object()) failType(n, "an object");
        if (const auto key = firstKeyNotIn(n, known)) {
            const std::vector<std::string_view> valid(known);
            std::string hint = didYouMean(*key, valid);
            if (hint.empty()) hint = "valid keys: " + join(valid);
            fail(appendJsonPointer(n.ptr, *key), "unknown key " + quote(*key) + " (" + hint + ")", true);
        }
    }

    // Checks that every key of `n` (already checked by expectObject) is used by
    // its variant, e.g. no "image" in a "color" environment.
    void expectKeysApply(const Node& n, Keys used, const std::string& variant) const {
        if (const auto key = firstKeyNotIn(n, used))
            fail(appendJsonPointer(n.ptr, *key), "key " + quote(*key) + " does not apply to " + variant, true);
    }

    std::vector<Node> elements(const Node& n, std::size_t minCount, std::size_t maxCount, std::string_view what) const {
        if (!n->is_array()) failType(n, "an array");
        const std::size_t count = n->size();
        if (count < minCount)
            fail(n, "needs at least " + std::to_string(minCount) + " " + std::string(what) + " (got " +
                        std::to_string(count) + ")");
        if (count > maxCount)
            fail(n, "has " + std::to_string(count) + " " + std::string(what) + ", more than the limit of " +
                        std::to_string(maxCount));
        std::vector<Node> out;
        out.reserve(count);
        for (std::size_t i = 0; i < count; ++i) out.push_back({&(*n)[i], appendJsonPointer(n.ptr, std::to_string(i))});
        return out;
    }

    // ---- scalars --------------------------------------------------------

    double numberValue(const Node& n) const {
        if (!n->is_number()) failType(n, "a number");
        const double d = n->get<double>();
        if (!std::isfinite(d)) fail(n, "must be a finite number");
        return d;
    }

    float number(const Node& n, const Range& range = {}) const {
        const double d = numberValue(n);
        // Everything downstream is float: a double beyond float range would
        // silently become infinity.
        if (std::fabs(d) > static_cast<double>(std::numeric_limits<float>::max()))
            fail(n, "is too large to be represented (got " + formatShortest(d) + ")");
        if (!range.contains(d)) fail(n, range.describe() + " (got " + formatShortest(d) + ")");
        return static_cast<float>(d);
    }

    int integer(const Node& n, int lo, int hi) const {
        const double d = numberValue(n);
        if (d != std::floor(d)) fail(n, "must be a whole number (got " + formatShortest(d) + ")");
        const Range range = closed(lo, hi);
        if (!range.contains(d)) fail(n, range.describe() + " (got " + formatShortest(d) + ")");
        return static_cast<int>(d);
    }

    template <class E, std::size_t N>
    E oneOf(const Node& n, const std::array<Choice<E>, N>& choices) const {
        const std::string s = nonEmptyString(n);
        std::string list;
        for (const Choice<E>& c : choices) {
            if (s == c.name) return c.value;
            list += (list.empty() ? "" : ", ") + std::string(c.name);
        }
        fail(n, "must be one of " + list + " (got '" + s + "')");
    }

    void renderCache(const Node& n, RenderCacheOverrides& out) const {
        expectObject(n, {"budget", "targetFrameMs", "alpha", "predict", "maxAge", "reflections"});
        if (const Node v = child(n, "budget")) {
            out.budget = number(v, closed(0.0, 1.0));
            if (!(*out.budget > 0.0f)) fail(v, "must be a share of the pixels in (0, 1] (got 0)");
        }
        if (const Node v = child(n, "targetFrameMs")) out.targetFrameMs = number(v, closed(0.0, 60000.0));
        if (const Node v = child(n, "alpha")) out.alpha = number(v, closed(0.0, 1.0));
        if (const Node v = child(n, "predict")) out.predictShare = number(v, closed(0.0, 0.9));
        if (const Node v = child(n, "maxAge")) out.maxAge = integer(v, 1, 65000);
        if (const Node v = child(n, "reflections")) out.reflections = oneOf(v, kReflectionChoices);
    }

    std::string nonEmptyString(const Node& n) const {
        if (!n->is_string()) failType(n, "a string");
        std::string s = n->get<std::string>();
        if (s.empty()) fail(n, "must not be empty");
        return s;
    }

    template <class E, std::size_t N>
    E choice(const Node& n, std::string_view what, const std::array<Choice<E>, N>& choices) const {
        if (!n->is_string()) failType(n, "a string");
        const std::string s = n->get<std::string>();
        std::vector<std::string_view> names;
        for (const auto& c : choices) {
            if (c.name == s) return c.value;
            names.push_back(c.name);
        }
        std::string message = "unknown " + std::string(what) + " " + quote(s) + " (expected one of: " + join(names);
        if (const std::string hint = didYouMean(s, names); !hint.empty()) message += "; " + hint;
        fail(n, message + ")");
    }

    Vec3 vec3(const Node& n) const {
        if (!n->is_array() || n->size() != 3) {
            if (n->is_array()) fail(n, "expected 3 numbers [x, y, z], got " + std::to_string(n->size()));
            failType(n, "an array of 3 numbers [x, y, z]");
        }
        const auto e = elements(n, 3, 3, "numbers");
        return {number(e[0]), number(e[1]), number(e[2])};
    }

    Vec3 nonZeroVec3(const Node& n) const {
        const Vec3 v = vec3(n);
        if (!(length(v) > 0.0f)) fail(n, "must not be the zero vector");
        return v;
    }

    // [r, g, b] or one number for a gray; components are >= 0.
    Rgb rgb(const Node& n) const {
        if (n->is_number()) return Rgb(number(n, nonNegative()));
        if (!n->is_array()) failType(n, "a color ([r, g, b] or a number)");
        if (n->size() != 3) fail(n, "expected 3 numbers [r, g, b], got " + std::to_string(n->size()));
        const auto e = elements(n, 3, 3, "numbers");
        return {number(e[0], nonNegative()), number(e[1], nonNegative()), number(e[2], nonNegative())};
    }

    // ---- referenced files -----------------------------------------------

    // The file named by string `n`, resolved against the scene file's
    // directory; fails unless it is an existing regular file.
    fs::path referencedFile(const Node& n, std::string_view what) const {
        const std::string written = nonEmptyString(n);
        const fs::path resolved = baseDir_ / fs::path(written);
        std::error_code ec;
        const fs::file_status status = fs::status(resolved, ec);
        if (!fs::exists(status))
            fail(n, std::string(what) + " file not found: " + quote(written) + " (looked for " + resolved.string() + ")");
        if (!fs::is_regular_file(status))
            fail(n, std::string(what) + " file " + quote(written) + " is not a regular file");
        return resolved;
    }

    // Key identifying a file however it was spelled ("a/../m.obj" = "m.obj").
    static std::string fileKey(const fs::path& p) {
        std::error_code ec;
        const fs::path canonical = fs::weakly_canonical(p, ec);
        return ec ? p.lexically_normal().string() : canonical.string();
    }

    std::shared_ptr<const Image> image(const Node& n) {
        const fs::path file = referencedFile(n, "image");
        std::shared_ptr<const Image>& cached = images_[fileKey(file)];
        if (!cached) {
            try {
                cached = std::make_shared<const Image>(loadImageFile(file));
            } catch (const InputError& e) {
                fail(n, "cannot load image " + quote(n->get<std::string>()) + ": " + e.what());
            }
        }
        return cached;
    }

    std::shared_ptr<const TriangleMesh> meshFile(const Node& n) {
        const fs::path file = referencedFile(n, "mesh");
        std::shared_ptr<const TriangleMesh>& cached = meshFiles_[fileKey(file)];
        if (!cached) {
            LoadedMesh loaded;
            try {
                loaded = loadMeshFile(file);
            } catch (const InputError& e) {
                fail(n, "cannot load mesh " + quote(n->get<std::string>()) + ": " + e.what());
            }
            if (const std::string problem = validateMesh(loaded.mesh); !problem.empty())
                fail(n, "mesh " + quote(n->get<std::string>()) + " is unusable: " + problem);
            // Once per file, however often the scene uses it.
            if (!loaded.note.empty()) notes_.push_back(std::move(loaded.note));
            cached = std::make_shared<const TriangleMesh>(std::move(loaded.mesh));
        }
        return cached;
    }

    std::shared_ptr<const TriangleMesh> generatedMesh(ShapeKind kind) {
        std::shared_ptr<const TriangleMesh>& cached = generated_[kind];
        if (!cached) {
            switch (kind) {
            case ShapeKind::Plane: cached = std::make_shared<const TriangleMesh>(makePlane()); break;
            case ShapeKind::Box: cached = std::make_shared<const TriangleMesh>(makeBox()); break;
            case ShapeKind::Cylinder: cached = std::make_shared<const TriangleMesh>(makeCylinder()); break;
            case ShapeKind::Cone: cached = std::make_shared<const TriangleMesh>(makeCone()); break;
            case ShapeKind::Torus: cached = std::make_shared<const TriangleMesh>(makeTorus()); break;
            case ShapeKind::Bowl: cached = std::make_shared<const TriangleMesh>(makeBowl()); break;
            case ShapeKind::Sphere:
            case ShapeKind::Mesh: break;  // not generated
            }
        }
        return cached;
    }

    // ---- sections -------------------------------------------------------

    // "include": a glTF 2.0 file (or {"file", "materials"}) read as a scene
    // (scene/GltfScene.h), which the rest of the file changes. Its notes
    // come first.
    Scene includedScene(const Node& n, const GltfSceneOverrides& overrides) {
        if (n->is_object()) expectObject(n, {"file", "materials"});
        else if (!n->is_string()) failType(n, "a glTF file name or {\"file\", \"materials\"}");
        const Node file = n->is_object() ? required(n, "file") : n;
        const fs::path path = referencedFile(file, "included scene");
        if (!isGltfPath(path))
            fail(file, "the included file must be a glTF 2.0 scene (.gltf or .glb), got " +
                           quote(file->get<std::string>()));
        Scene scene;
        try {
            scene = loadGltfScene(path, overrides);
        } catch (const InputError& e) {
            fail(file, "cannot load included scene " + quote(file->get<std::string>()) + ": " + e.what());
        }
        notes_ = std::move(scene.notes);
        scene.notes.clear();
        includedObjects_ = scene.objects.size();
        return scene;
    }

    // "include": {"materials": {"<object name>": material}}: materials of the
    // included file's objects replaced by ours (a name or an inline material).
    void includedMaterials(const Node& n, Scene& scene) {
        if (!n->is_object()) failType(n, "an object mapping the included objects' names to materials");
        std::vector<std::string_view> names;
        for (std::size_t i = 0; i < includedObjects_; ++i) names.push_back(scene.objects[i].name);
        for (const auto& item : n->items()) {
            const Node m{&item.value(), appendJsonPointer(n.ptr, item.key())};
            const auto at = std::find(names.begin(), names.end(), item.key());
            if (at == names.end()) {
                std::string hint = didYouMean(item.key(), names);
                fail(m.ptr, "the included file has no object " + quote(item.key()) +
                                (hint.empty() ? std::string() : " (" + hint + ")"),
                     true);
            }
            scene.objects[static_cast<std::size_t>(at - names.begin())].material = objectMaterial(m);
        }
    }

    // A camera; members not given keep `defaults`.
    Camera camera(const Node& n, const Camera& defaults) const {
        expectObject(n, {"position", "lookAt", "up", "fov"});
        Camera c = defaults;
        const Node position = child(n, "position"), lookAt = child(n, "lookAt"), up = child(n, "up");
        if (position) c.position = vec3(position);
        if (lookAt) c.lookAt = vec3(lookAt);
        if (up) c.up = nonZeroVec3(up);
        if (const Node fov = child(n, "fov")) c.verticalFovDeg = number(fov, {0.0, 180.0, false, false});

        const Vec3 view = c.lookAt - c.position;
        if (!(length(view) > 0.0f)) fail(lookAt ? lookAt : position ? position : n, "the camera looks at its own position");
        const float sine = length(cross(normalize(view), normalize(c.up)));
        if (!(sine > 1e-4f))
            fail(up ? up : n, up ? "the up vector is parallel to the viewing direction"
                                 : "the up vector (default [0, 1, 0]) is parallel to the viewing direction; "
                                   "give \"up\"");
        return c;
    }

    CameraPath path(const Node& n, const Camera& base, int& frames) const {
        expectObject(n, {"type", "center", "degreesPerFrame", "keyframes", "framesPerSegment"});
        const Node type = required(n, "type");
        CameraPath p;
        p.kind = choice(type, "path type", kPathKinds);
        const std::string variant = "path type " + quote(type->get<std::string>());
        switch (p.kind) {
        case CameraPathKind::Static: expectKeysApply(n, {"type"}, variant); break;
        case CameraPathKind::Orbit: expectKeysApply(n, {"type", "center", "degreesPerFrame"}, variant); break;
        case CameraPathKind::Pan: expectKeysApply(n, {"type", "degreesPerFrame"}, variant); break;
        case CameraPathKind::Keyframes: expectKeysApply(n, {"type", "keyframes", "framesPerSegment"}, variant); break;
        }
        if (const Node c = child(n, "center")) p.center = vec3(c);
        if (const Node d = child(n, "degreesPerFrame")) {
            p.degreesPerFrame = number(d, closed(-360.0, 360.0));
            if (p.degreesPerFrame == 0.0f) fail(d, "must not be 0 (use a static path)");
        }
        if (const Node f = child(n, "framesPerSegment")) p.framesPerSegment = integer(f, 1, kMaxFramesPerSegment);
        frames = 1;
        if (p.kind == CameraPathKind::Orbit || p.kind == CameraPathKind::Pan) {
            // One full turn.
            frames = std::max(1, static_cast<int>(std::lround(360.0 / std::fabs(static_cast<double>(p.degreesPerFrame)))));
        }
        if (p.kind == CameraPathKind::Keyframes) {
            for (const Node& k : elements(required(n, "keyframes"), 2, kMaxKeyframes, "keyframes"))
                p.keyframes.push_back(camera(k, base));
            const long long length =
                static_cast<long long>(p.keyframes.size() - 1) * p.framesPerSegment + 1;
            if (length > kMaxFrames)
                fail(child(n, "framesPerSegment") ? child(n, "framesPerSegment") : n,
                     "makes the path " + std::to_string(length) + " frames long, more than the limit of " +
                         std::to_string(kMaxFrames));
            frames = static_cast<int>(length);
        }
        return p;
    }

    Environment environment(const Node& n) {
        expectObject(n, {"type", "color", "image", "faces"});
        const Node type = required(n, "type");
        const EnvironmentKind kind = choice(type, "environment type", kEnvironmentKinds);
        const std::string variant = "environment type " + quote(type->get<std::string>());
        switch (kind) {
        case EnvironmentKind::Color:
            expectKeysApply(n, {"type", "color"}, variant);
            if (const Node c = child(n, "color")) return Environment::constant(rgb(c));
            return Environment{};
        case EnvironmentKind::Equirect:
            expectKeysApply(n, {"type", "image"}, variant);
            return Environment::equirectangular(image(required(n, "image")));
        case EnvironmentKind::Cube: {
            expectKeysApply(n, {"type", "faces"}, variant);
            const Node faces = required(n, "faces");
            if (!faces->is_array()) failType(faces, "an array of 6 image files (+x, -x, +y, -y, +z, -z)");
            if (faces->size() != 6)
                fail(faces, "expected 6 image files (+x, -x, +y, -y, +z, -z), got " + std::to_string(faces->size()));
            std::array<std::shared_ptr<const Image>, 6> images;
            const auto e = elements(faces, 6, 6, "faces");
            for (std::size_t i = 0; i < 6; ++i) {
                images[i] = image(e[i]);
                const Image& img = *images[i];
                if (img.width() != img.height())
                    fail(e[i], "cube face must be square (got " + std::to_string(img.width()) + "x" +
                                   std::to_string(img.height()) + ")");
                if (img.width() != images[0]->width())
                    fail(e[i], "cube faces must all be the same size (this one is " + std::to_string(img.width()) +
                                   ", face 0 is " + std::to_string(images[0]->width()) + ")");
            }
            return Environment::cubeFaces(std::move(images));
        }
        }
        return Environment{};
    }

    Light light(const Node& n) const {
        expectObject(n, {"type", "position", "direction", "intensity", "cone", "falloff", "physical", "range", "animation"});
        const Node type = required(n, "type");
        Light l;
        l.type = choice(type, "light type", kLightTypes);
        const std::string variant = "light type " + quote(type->get<std::string>());
        switch (l.type) {
        case LightType::Point:
            expectKeysApply(n, {"type", "position", "intensity", "physical", "range", "animation"}, variant);
            break;
        case LightType::Directional:
            expectKeysApply(n, {"type", "direction", "intensity", "physical", "animation"}, variant);
            break;
        case LightType::Spot: break;  // uses every key
        }
        if (const Node p = child(n, "physical")) {
            if (!p->is_boolean()) failType(p, "true or false");
            l.physical = p->get<bool>();
        }
        if (const Node r = child(n, "range")) {
            if (!l.physical) fail(r, "\"range\" applies to physical lights only (set \"physical\": true)");
            l.range = number(r, {0.0, {}, true, true});
        }
        if (l.type != LightType::Directional) l.position = vec3(required(n, "position"));
        if (l.type != LightType::Point) l.direction = normalize(nonZeroVec3(required(n, "direction")));
        if (const Node i = child(n, "intensity")) l.intensity = rgb(i);
        if (l.type == LightType::Spot) {
            if (const Node c = child(n, "cone")) l.coneAngleDeg = number(c, {0.0, 90.0, false, true});
            l.falloffAngleDeg = std::min(l.falloffAngleDeg, l.coneAngleDeg);
            if (const Node f = child(n, "falloff"))
                l.falloffAngleDeg = number(f, closed(0.0, static_cast<double>(l.coneAngleDeg)));
        }
        return l;
    }

    // ---- animation (scene/Animation.h) ----------------------------------

    // "interpolation" and "wrap" of an animation object.
    void trackOptions(const Node& n, Interpolation& interpolation, Wrap& wrap) const {
        if (const Node v = child(n, "interpolation")) interpolation = oneOf(v, kInterpolations);
        if (const Node v = child(n, "wrap")) wrap = oneOf(v, kWraps);
    }

    // The "keys" array: at least one, times finite and strictly increasing.
    std::vector<Node> keyNodes(const Node& n, std::vector<float>& times) const {
        std::vector<Node> keys = elements(required(n, "keys"), 1, kMaxKeyframes, "keys");
        for (const Node& k : keys) {
            if (!k->is_object()) failType(k, "a key object");
            const Node t = required(k, "time");
            const float time = number(t, closed(-kMaxAnimationSeconds, kMaxAnimationSeconds));
            if (!times.empty() && !(time > times.back()))
                fail(t, "key times must increase (got " + formatShortest(time) + " after " + formatShortest(times.back()) + ")");
            times.push_back(time);
        }
        return keys;
    }

    // `restReach`: the farthest point of the object's rest shape from the
    // origin. Every key must keep the shape within ±kMaxWorldCoordinate;
    // interpolated poses then do too (translations and scales blend between
    // keys' values, rotations keep distances).
    TransformTrack transformTrack(const Node& n, bool sphere, double restReach) const {
        expectObject(n, {"keys", "interpolation", "wrap"});
        TransformTrack track;
        trackOptions(n, track.interpolation, track.wrap);
        std::vector<float> times;
        for (const Node& k : keyNodes(n, times)) {
            expectObject(k, {"time", "translate", "rotate", "scale"});
            TransformKey key;
            key.time = times[track.keys.size()];
            if (const Node v = child(k, "translate")) key.translate = vec3(v);
            if (const Node v = child(k, "rotate")) {
                if (v->is_array()) {
                    // Applied in the order listed: the first entry acts first.
                    for (const Node& r : elements(v, 0, kMaxRotations, "rotations")) key.rotation = rotation(r) * key.rotation;
                } else if (v->is_object()) {
                    key.rotation = rotation(v);
                } else {
                    failType(v, "a rotation {\"axis\", \"degrees\"} or an array of them");
                }
            }
            if (const Node v = child(k, "scale")) {
                if (v->is_number()) {
                    key.scale = Vec3(1.0f, 1.0f, 1.0f) * number(v, positive());
                } else if (v->is_array() && v->size() == 3) {
                    const auto e = elements(v, 3, 3, "numbers");
                    key.scale = {number(e[0], positive()), number(e[1], positive()), number(e[2], positive())};
                    if (sphere && !(key.scale.x == key.scale.y && key.scale.y == key.scale.z))
                        fail(v, "a sphere needs a uniform scale (a non-uniform one would make it an ellipsoid; use a mesh)");
                } else {
                    failType(v, "a number or an array of 3 numbers [x, y, z]");
                }
            }
            const double reach = static_cast<double>(length(key.translate)) +
                                 static_cast<double>(std::max({key.scale.x, key.scale.y, key.scale.z})) * restReach;
            if (!(reach <= kMaxWorldCoordinate))
                fail(k, "this key moves the object up to " + formatShortest(reach) + " from the origin, beyond the limit of " +
                            formatShortestFloat(kMaxWorldCoordinate) + " (floats are too coarse to trace beyond)");
            track.keys.push_back(key);
        }
        return track;
    }

    // The farthest point of a shape from the origin.
    static double reachOf(const std::variant<Sphere, MeshShape>& shape) {
        if (const auto* s = std::get_if<Sphere>(&shape)) return static_cast<double>(length(s->center) + s->radius);
        double reach = 0.0;
        for (const Vec3& p : std::get<MeshShape>(shape).mesh->positions)
            reach = std::max(reach, static_cast<double>(length(p)));
        return reach;
    }

    Quaternion rotation(const Node& n) const {
        expectObject(n, {"axis", "degrees"});
        const Vec3 axis = nonZeroVec3(required(n, "axis"));
        return Quaternion::fromAxisAngle(axis, number(required(n, "degrees")));
    }

    LightTrack lightTrack(const Node& n, const Light& light) const {
        expectObject(n, {"keys", "interpolation", "wrap"});
        LightTrack track;
        trackOptions(n, track.interpolation, track.wrap);
        std::vector<float> times;
        for (const Node& k : keyNodes(n, times)) {
            // A key sets what its light type uses; what it leaves out keeps the light's own value.
            switch (light.type) {
            case LightType::Point: expectObject(k, {"time", "position", "intensity"}); break;
            case LightType::Directional: expectObject(k, {"time", "direction", "intensity"}); break;
            case LightType::Spot: expectObject(k, {"time", "position", "direction", "intensity"}); break;
            }
            LightKey key{times[track.keys.size()], light.position, light.direction, light.intensity};
            if (const Node v = child(k, "position")) key.position = vec3(v);
            if (const Node v = child(k, "direction")) key.direction = normalize(nonZeroVec3(v));
            if (const Node v = child(k, "intensity")) key.intensity = rgb(v);
            track.keys.push_back(key);
        }
        return track;
    }

    // "frames": {"files": [...], "fps": f, "wrap": w}: one mesh file per
    // frame, each with the rest mesh's triangles, placed by `placement`.
    std::shared_ptr<const MeshDeformation> meshFrames(const Node& n, const TriangleMesh& rest, const Transform& placement) {
        expectObject(n, {"files", "fps", "wrap"});
        float fps = 24.0f;
        if (const Node v = child(n, "fps")) fps = number(v, {0.0, 1000.0, false, true});
        Wrap wrap = Wrap::Loop;
        if (const Node v = child(n, "wrap")) wrap = oneOf(v, kWraps);
        std::vector<std::vector<Vec3>> frames;
        framesReach_ = 0.0;
        for (const Node& f : elements(required(n, "files"), 1, kMaxKeyframes, "files")) {
            const std::shared_ptr<const TriangleMesh> mesh = meshFile(f);
            if (mesh->positions.size() != rest.positions.size())
                fail(f, "has " + std::to_string(mesh->positions.size()) + " vertices, the object's \"file\" has " +
                            std::to_string(rest.positions.size()) + " (every frame needs the same vertices)");
            if (mesh->triangles != rest.triangles)
                fail(f, "has other triangles than the object's \"file\" (every frame needs the same triangles)");
            std::vector<Vec3> positions;
            positions.reserve(mesh->positions.size());
            for (const Vec3& p : mesh->positions) positions.push_back(placement.applyToPoint(p));
            checkMeshBounds(TriangleMesh{positions, {}, {}, mesh->triangles}, f, "");
            for (const Vec3& p : positions) framesReach_ = std::max(framesReach_, static_cast<double>(length(p)));
            frames.push_back(std::move(positions));
        }
        return std::make_shared<const MeshSequence>(std::move(frames), fps, wrap);
    }

    Material material(const Node& n) {
        expectObject(n, {"ambient", "diffuse", "texture", "specular", "shininess", "kr", "kt", "ior", "cache"});
        Material m;
        if (const Node v = child(n, "ambient")) m.ambient = rgb(v);
        if (const Node v = child(n, "diffuse")) m.diffuse = rgb(v);
        if (const Node v = child(n, "texture")) m.diffuseTexture = texture(v);
        if (const Node v = child(n, "specular")) m.specular = rgb(v);
        if (const Node v = child(n, "shininess")) m.shininess = number(v, nonNegative());
        if (const Node v = child(n, "kr")) m.reflectivity = number(v, closed(0.0, 1.0));
        if (const Node v = child(n, "kt")) m.transmissivity = number(v, closed(0.0, 1.0));
        if (const Node v = child(n, "ior")) m.ior = number(v, positive());
        if (const Node v = child(n, "cache")) m.cache = cache(v);
        return m;
    }

    Texture texture(const Node& n) {
        expectObject(n, {"type", "file", "even", "odd", "scale"});
        const Node type = required(n, "type");
        const TextureKind kind = choice(type, "texture type", kTextureKinds);
        const std::string variant = "texture type " + quote(type->get<std::string>());
        if (kind == TextureKind::Image) {
            expectKeysApply(n, {"type", "file"}, variant);
            return Texture::image(image(required(n, "file")));
        }
        expectKeysApply(n, {"type", "even", "odd", "scale"}, variant);
        Checkerboard c;
        if (const Node v = child(n, "even")) c.even = rgb(v);
        if (const Node v = child(n, "odd")) c.odd = rgb(v);
        if (const Node v = child(n, "scale")) c.squaresPerUnit = number(v, positive());
        return Texture::checkerboard(c);
    }

    CacheSettings cache(const Node& n) const {
        expectObject(n, {"technique", "resolution", "step", "epsilon", "maxDepth", "tolerance"});
        CacheSettings c;
        if (const Node v = child(n, "technique")) c.technique = choice(v, "cache technique", kCacheTechniqueChoices);
        if (const Node v = child(n, "resolution")) c.faceResolution = integer(v, CacheSettings::kMinFaceResolution, CacheSettings::kMaxFaceResolution);
        // CDCT search parameters; RayCache::validate checks the step count.
        if (const Node v = child(n, "step")) c.cdct.step = number(v, positive());
        if (const Node v = child(n, "epsilon")) c.cdct.epsilon = number(v, positive());
        if (const Node v = child(n, "maxDepth")) c.cdct.maxDepth = number(v, positive());
        if (const Node v = child(n, "tolerance")) c.cdct.tolerance = number(v, positive());
        if (!(c.cdct.epsilon < c.cdct.step))
            fail(child(n, "epsilon") ? child(n, "epsilon") : n, "cache epsilon must be smaller than step");
        return c;
    }

    void materials(const Node& n) {
        if (!n->is_object()) failType(n, "an object mapping material names to materials");
        if (n->size() > kMaxMaterials)
            fail(n, "has " + std::to_string(n->size()) + " materials, more than the limit of " +
                        std::to_string(kMaxMaterials));
        for (const auto& item : n->items()) {
            const Node m{&item.value(), appendJsonPointer(n.ptr, item.key())};
            if (item.key().empty()) fail(m.ptr, "material names must not be empty", true);
            namedMaterials_.emplace(item.key(), material(m));
        }
    }

    Material objectMaterial(const Node& n) {
        if (n->is_object()) return material(n);
        if (!n->is_string()) failType(n, "a material name or a material object");
        const std::string name = n->get<std::string>();
        const auto it = namedMaterials_.find(name);
        if (it != namedMaterials_.end()) return it->second;
        if (namedMaterials_.empty()) fail(n, "unknown material " + quote(name) + " (the file defines no materials)");
        std::vector<std::string_view> names;
        for (const auto& [k, v] : namedMaterials_) names.push_back(k);
        std::string hint = didYouMean(name, names);
        if (hint.empty()) hint = "defined: " + join(names);
        fail(n, "unknown material " + quote(name) + " (" + hint + ")");
    }

    ObjectTransform transform(const Node& n) const {
        expectObject(n, {"translate", "rotate", "scale"});
        ObjectTransform t;
        Transform rotation;
        if (const Node v = child(n, "translate")) t.translate = vec3(v);
        if (const Node v = child(n, "rotate")) {
            t.rotate = v;
            if (v->is_array()) {
                // Applied in the order listed: the first entry acts first.
                for (const Node& r : elements(v, 0, kMaxRotations, "rotations")) rotation = rotate(r) * rotation;
            } else if (v->is_object()) {
                rotation = rotate(v);
            } else {
                failType(v, "a rotation {\"axis\", \"degrees\"} or an array of them");
            }
        }
        if (const Node v = child(n, "scale")) {
            t.scale = v;
            if (v->is_number()) {
                t.scaleFactors = Vec3(1.0f, 1.0f, 1.0f) * number(v, positive());
            } else if (v->is_array() && v->size() == 3) {
                const auto e = elements(v, 3, 3, "numbers");
                t.scaleFactors = {number(e[0], positive()), number(e[1], positive()), number(e[2], positive())};
            } else {
                failType(v, "a number or an array of 3 numbers [x, y, z]");
            }
        }
        t.matrix = Transform::translate(t.translate) * rotation * Transform::scale(t.scaleFactors);
        t.identity = !t.rotate && t.translate == Vec3{} && t.scaleFactors == Vec3(1.0f, 1.0f, 1.0f);
        return t;
    }

    Transform rotate(const Node& n) const {
        expectObject(n, {"axis", "degrees"});
        const Vec3 axis = nonZeroVec3(required(n, "axis"));
        return Transform::rotate(axis, number(required(n, "degrees")));
    }

    void objects(const Node& n, Scene& scene) {
        std::unordered_map<std::string, std::string> names;  // name -> pointer of its first use
        for (const SceneObject& o : scene.objects) names.emplace(o.name, "/include, an object of the included file");
        for (const Node& o : elements(n, 0, kMaxObjects, "objects")) {
            expectObject(o, {"name", "shape", "center", "radius", "file", "transform", "material", "animation", "frames"});
            const Node shape = required(o, "shape");
            const ShapeKind kind = choice(shape, "shape", kShapeKinds);
            const std::string variant = "shape " + quote(shape->get<std::string>());
            switch (kind) {
            case ShapeKind::Sphere:
                expectKeysApply(o, {"name", "shape", "center", "radius", "transform", "material", "animation"}, variant);
                break;
            case ShapeKind::Mesh:
                expectKeysApply(o, {"name", "shape", "file", "transform", "material", "animation", "frames"}, variant);
                break;
            default: expectKeysApply(o, {"name", "shape", "transform", "material", "animation"}, variant); break;
            }

            SceneObject object;
            const Node name = child(o, "name");
            // Unnamed objects get a name no hand-written one is likely to clash with.
            object.name = name ? nonEmptyString(name)
                               : shape->get<std::string>() + "#" + std::to_string(scene.objects.size());
            const auto [it, isNew] = names.emplace(object.name, name ? name.ptr : o.ptr);
            if (!isNew)
                fail(name ? name : o, "duplicate object name " + quote(object.name) + " (also used by " + it->second + ")");

            ObjectTransform t;
            if (const Node v = child(o, "transform")) t = transform(v);

            if (kind == ShapeKind::Sphere) {
                if (t.rotate) fail(t.rotate, "a sphere cannot be rotated (only translate and a uniform scale apply)");
                const Vec3& s = t.scaleFactors;
                if (t.scale && !(s.x == s.y && s.y == s.z))
                    fail(t.scale, "a sphere needs a uniform scale (got [" + formatShortest(s.x) + ", " +
                                      formatShortest(s.y) + ", " + formatShortest(s.z) + "])");
                Sphere sphere;
                if (const Node v = child(o, "center")) sphere.center = vec3(v);
                if (const Node v = child(o, "radius")) sphere.radius = number(v, positive());
                sphere.center = t.matrix.applyToPoint(sphere.center);
                sphere.radius *= s.x;
                checkSphereBounds(sphere, o);
                object.shape = sphere;
                object.origin = sphere.center;
            } else {
                std::shared_ptr<const TriangleMesh> mesh =
                    kind == ShapeKind::Mesh ? meshFile(required(o, "file")) : generatedMesh(kind);
                // Instances share the untransformed mesh when they can.
                if (!t.identity) mesh = std::make_shared<const TriangleMesh>(transformed(*mesh, t.matrix));
                const Node transformNode = child(o, "transform");
                checkMeshBounds(*mesh, t.identity ? (kind == ShapeKind::Mesh ? required(o, "file") : o) : transformNode,
                                t.identity ? "" : "its transform makes ");
                object.shape = MeshShape{std::move(mesh)};
                object.origin = t.translate;
            }
            if (const Node v = child(o, "material")) object.material = objectMaterial(v);
            const Node animation = child(o, "animation");
            const Node frames = child(o, "frames");
            if (animation || frames) {
                ObjectAnimation a{static_cast<int>(scene.objects.size()), std::nullopt, nullptr, object.shape, object.origin};
                double reach = reachOf(object.shape);
                if (frames) {
                    a.deformation = meshFrames(frames, *std::get<MeshShape>(object.shape).mesh, t.matrix);
                    // The keys move every frame of the sequence, not only the rest mesh.
                    reach = std::max(reach, framesReach_);
                }
                if (animation) a.transform = transformTrack(animation, kind == ShapeKind::Sphere, reach);
                scene.animation.objects.push_back(std::move(a));
            }
            scene.objects.push_back(std::move(object));
        }
    }

    // Spheres and meshes must stay within ±kMaxWorldCoordinate: a radius of
    // 3e38 is a finite float whose bounds are not, and renders nothing.
    void checkSphereBounds(const Sphere& sphere, const Node& o) const {
        // Blame the radius when it alone is too large, otherwise what placed the centre.
        const Node radius = child(o, "radius"), center = child(o, "center"), transform = child(o, "transform");
        const Node where = radius && !(std::fabs(double(sphere.radius)) <= kMaxWorldCoordinate) ? radius
                           : center                                                             ? center
                           : transform                                                          ? transform
                                                                                                : o;
        const double reach = std::max({std::fabs(double(sphere.center.x)), std::fabs(double(sphere.center.y)),
                                       std::fabs(double(sphere.center.z))}) +
                             double(sphere.radius);
        if (!isFinite(sphere.center) || !std::isfinite(sphere.radius) || !(reach <= kMaxWorldCoordinate))
            fail(where, "the sphere (world centre [" + formatShortestFloat(sphere.center.x) + ", " +
                            formatShortestFloat(sphere.center.y) + ", " + formatShortestFloat(sphere.center.z) + "], radius " +
                            formatShortestFloat(sphere.radius) + ") reaches " +
                            (reach <= std::numeric_limits<float>::max() ? formatShortestFloat(static_cast<float>(reach))
                                                                        : formatShortest(reach)) +
                            ", beyond the limit of ±" + formatShortestFloat(kMaxWorldCoordinate) +
                            " on some axis (floats are too coarse to trace beyond)");
    }

    // `prefix` names what moved the vertices ("its transform makes "), empty for the file's own.
    void checkMeshBounds(const TriangleMesh& mesh, const Node& where, const std::string& prefix) const {
        std::size_t nonFinite = 0, outside = 0;
        for (const Vec3& p : mesh.positions) {
            if (!isFinite(p))
                ++nonFinite;
            else if (std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) > kMaxWorldCoordinate)
                ++outside;
        }
        if (nonFinite > 0)
            fail(where, prefix + std::to_string(nonFinite) + " of the mesh's " + std::to_string(mesh.positions.size()) +
                            " vertices non-finite (infinite or NaN)");
        if (outside > 0)
            fail(where, (prefix.empty() ? "" : prefix) + std::to_string(outside) + " of the mesh's " +
                            std::to_string(mesh.positions.size()) + " vertices lie beyond ±" +
                            formatShortestFloat(kMaxWorldCoordinate) + " on some axis (floats are too coarse to trace beyond)");
        if (const std::string problem = validateMesh(mesh); !problem.empty()) fail(where, problem);
    }

    std::size_t includedObjects_ = 0;  // the first objects of the scene, from "include"
    double framesReach_ = 0.0;  // farthest vertex of the last object's mesh frames from the origin
    std::vector<std::string> notes_;  // Scene::notes, as the files are loaded
    std::string fileLabel_;
    fs::path baseDir_;
    const JsonPositions& positions_;
    std::map<std::string, Material> namedMaterials_;  // ordered: suggestions list names stably
    std::unordered_map<std::string, std::shared_ptr<const Image>> images_;
    std::unordered_map<std::string, std::shared_ptr<const TriangleMesh>> meshFiles_;
    std::map<ShapeKind, std::shared_ptr<const TriangleMesh>> generated_;
};

std::string readSceneText(const fs::path& path) {
    const InputLocation where{.file = path.string()};
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw InputError(where, "scene file not found");
    if (!fs::is_regular_file(status)) throw InputError(where, "scene file is not a regular file");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > kMaxSceneFileBytes)
        throw InputError(where, "scene file is " + std::to_string(size) + " bytes, more than the limit of " +
                                    std::to_string(kMaxSceneFileBytes));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(where, "cannot open scene file");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw InputError(where, "cannot read scene file");
    return std::move(text).str();
}

}  // namespace

Scene loadSceneFile(const fs::path& path) {
    const std::string text = readSceneText(path);
    const JsonPositions positions(text);
    if (const auto& e = positions.syntaxError())
        throw InputError(InputLocation{.file = path.string(), .line = e->position.line,
                                       .column = e->position.column, .jsonPath = e->pointer},
                         e->message);
    const json root = json::parse(text);  // cannot fail: the same text was just indexed
    SceneFileReader reader(path.string(), path.parent_path(), positions);
    return reader.read(root, path.stem().string());
}

}  // namespace raycache
