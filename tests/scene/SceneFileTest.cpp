#include "scene/SceneFile.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

#include "core/Errors.h"
#include "scene/ScenePose.h"

namespace raycache {
namespace {

namespace fs = std::filesystem;

const fs::path kExampleScene = fs::path(RAYCACHE_TEST_DATA_DIR) / ".." / ".." / "examples" / "scenes" / "example.json";

// A unit tetrahedron, enough for the mesh loader.
constexpr const char* kTetrahedronObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

void writeFile(const fs::path& path, const std::string& contents) {
    fs::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary);
    out << contents;
    ASSERT_TRUE(out.good()) << path;
}

// Uncompressed 24-bit TGA of one gray level, the simplest image the loader reads.
std::string tgaImage(int width, int height, unsigned char gray = 128) {
    std::string s(18, '\0');
    s[2] = 2;  // uncompressed true-color
    s[12] = static_cast<char>(width & 0xFF);
    s[13] = static_cast<char>(width >> 8);
    s[14] = static_cast<char>(height & 0xFF);
    s[15] = static_cast<char>(height >> 8);
    s[16] = 24;
    s.append(static_cast<std::size_t>(width * height * 3), static_cast<char>(gray));
    return s;
}

class SceneFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::path(::testing::TempDir()) / "raycache_scene_file" / info->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }

    fs::path write(const std::string& relative, const std::string& contents) {
        writeFile(dir_ / relative, contents);
        return dir_ / relative;
    }

    // Writes `jsonWithMarker` as scene.json with the single '@' removed and
    // expects loading to fail with "<file>:<line>:<col>: <pointer>: <what...>"
    // where line:col is where the '@' was. Returns the message.
    std::string expectError(const std::string& jsonWithMarker, const std::string& pointer,
                            const std::string& whatFragment) {
        const auto at = jsonWithMarker.find('@');
        EXPECT_NE(at, std::string::npos) << "test JSON needs an '@' marker";
        EXPECT_EQ(jsonWithMarker.find('@', at + 1), std::string::npos) << "only one '@' marker";
        int line = 1, column = 1;
        for (std::size_t i = 0; i < at; ++i) {
            if (jsonWithMarker[i] == '\n') {
                ++line;
                column = 1;
            } else if ((static_cast<unsigned char>(jsonWithMarker[i]) & 0xC0) != 0x80) {
                ++column;
            }
        }
        std::string json = jsonWithMarker;
        json.erase(at, 1);
        const fs::path file = write("scene.json", json);
        const std::string expectedPrefix = file.string() + ":" + std::to_string(line) + ":" +
                                           std::to_string(column) + ": " +
                                           (pointer.empty() ? "" : pointer + ": ");
        try {
            loadSceneFile(file);
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(expectedPrefix, 0), 0u) << "expected prefix: " << expectedPrefix
                                                            << "\nactual message:  " << message;
            EXPECT_NE(message.find(whatFragment), std::string::npos) << "expected to contain: " << whatFragment
                                                                      << "\nactual message: " << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << "message must be one line";
            EXPECT_EQ(e.where().jsonPath, pointer);
            EXPECT_EQ(e.where().line, line);
            EXPECT_EQ(e.where().column, column);
            return message;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "expected InputError, got: " << e.what();
            return {};
        }
        ADD_FAILURE() << "expected InputError for:\n" << json;
        return {};
    }

    Scene load(const std::string& json) { return loadSceneFile(write("scene.json", json)); }

    fs::path dir_;
};

// ---- syntax ---------------------------------------------------------------

TEST_F(SceneFileTest, SyntaxErrorReportsLineAndColumnOfTheBadToken) {
    expectError("{\n  \"objects\": [\n    {\"shape\": \"sphere\"},\n  @]\n}\n", "/objects/1",
                "syntax error while parsing value - unexpected ']'");
}

TEST_F(SceneFileTest, SyntaxErrorMissingCommaPointsAtTheNextMember) {
    expectError("{\n  \"frames\": 3\n  @\"objects\": []\n}\n", "",
                "unexpected string literal; expected '}'");
}

TEST_F(SceneFileTest, SyntaxErrorBadLiteralPointsAtItsStart) {
    expectError("{\"objects\": [{\"shape\": @tru}]}", "/objects/0/shape", "invalid literal");
}

TEST_F(SceneFileTest, SyntaxErrorUnterminatedDocumentPointsAtTheEnd) {
    expectError("{\"objects\": [\n@", "/objects/0", "unexpected end of input");
}

TEST_F(SceneFileTest, SyntaxErrorColumnsCountCharactersNotBytes) {
    expectError("{\"name\": \"caf\xC3\xA9 \xE2\x98\x95\", @x}", "", "invalid literal");
}

TEST_F(SceneFileTest, DuplicateJsonMemberIsRejected) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"radius\": 1,\n  @\"radius\": 2}]}",
                "/objects/0/radius", "duplicate member name \"radius\" (first at line 1, column 34)");
}

TEST_F(SceneFileTest, EmptyFileIsASyntaxError) {
    expectError("@", "", "unexpected end of input");
}

TEST_F(SceneFileTest, RootMustBeAnObject) {
    expectError("@[1, 2]", "", "expected an object, got an array");
}

// ---- unknown keys -----------------------------------------------------------

TEST_F(SceneFileTest, UnknownKeySuggestsTheClosestValidKey) {
    const std::string m = expectError("{\"objects\": [\n  {\"shape\": \"sphere\", @\"radiu\": 2}\n]}",
                                      "/objects/0/radiu", "unknown key \"radiu\" (did you mean \"radius\"?)");
    EXPECT_EQ(m, dir_.string() + "/scene.json:2:23: /objects/0/radiu: unknown key \"radiu\" (did you mean \"radius\"?)");
}

TEST_F(SceneFileTest, UnknownKeySuggestionIgnoresCase) {
    expectError("{\"camera\": {@\"lookat\": [0, 0, 0]}, \"objects\": []}", "/camera/lookat",
                "did you mean \"lookAt\"?");
}

TEST_F(SceneFileTest, UnknownKeyWithoutCloseMatchListsValidKeys) {
    expectError("{@\"wibble\": 1, \"objects\": []}", "/wibble",
                "unknown key \"wibble\" (valid keys: name, include, camera, path, frames, fps, environment, lights, "
                "materials, objects, pipeline, accel, renderCache, cacheBudget, exposure, viewTransform)");
}

TEST_F(SceneFileTest, RenderCacheKeysAreReadAndChecked) {
    const Scene scene = load(R"({"pipeline": "render-cache", "renderCache": {"budget": 0.1, "alpha": 0.5,
        "maxAge": 8, "predict": 0.3, "targetFrameMs": 20, "reflections": "reproject"}, "objects": []})");
    ASSERT_TRUE(scene.render.pipeline);
    EXPECT_EQ(*scene.render.pipeline, PipelineKind::RenderCache);
    EXPECT_EQ(scene.render.renderCache.budget, 0.1f);
    EXPECT_EQ(scene.render.renderCache.alpha, 0.5f);
    EXPECT_EQ(scene.render.renderCache.maxAge, 8);
    EXPECT_EQ(scene.render.renderCache.predictShare, 0.3f);
    EXPECT_EQ(scene.render.renderCache.targetFrameMs, 20.0f);
    EXPECT_EQ(scene.render.renderCache.reflections, ReprojectedReflections::Reproject);
    expectError("{\"pipeline\": @\"raster\", \"objects\": []}", "/pipeline",
                "must be one of ray, hybrid, render-cache (got 'raster')");
    expectError("{\"renderCache\": {\"budget\": @0}, \"objects\": []}", "/renderCache/budget", "(0, 1]");
    expectError("{\"renderCache\": {\"alpha\": @1.5}, \"objects\": []}", "/renderCache/alpha", "between 0 and 1");
    expectError("{\"renderCache\": {@\"gamma\": 1}, \"objects\": []}", "/renderCache/gamma", "unknown key");
}

TEST_F(SceneFileTest, AccelKeyIsReadAndChecked) {
    const Scene scene = load(R"({"accel": "grids", "objects": []})");
    EXPECT_EQ(scene.render.accel, Accelerator::Grids);
    EXPECT_FALSE(load(R"({"objects": []})").render.accel);
    expectError("{\"objects\": [],\n \"accel\": @\"bvh\"}", "/accel", "must be one of embree, grids (got 'bvh')");
}

TEST_F(SceneFileTest, CacheBudgetKeyIsReadAndChecked) {
    EXPECT_EQ(load(R"({"cacheBudget": 256, "objects": []})").render.cacheBudgetMiB, std::optional<double>(256.0));
    EXPECT_FALSE(load(R"({"objects": []})").render.cacheBudgetMiB);
    expectError("{\"objects\": [],\n \"cacheBudget\": @0}", "/cacheBudget", "(got 0)");
    expectError("{\"objects\": [],\n \"cacheBudget\": @\"big\"}", "/cacheBudget", "a number");
    expectError("{\"objects\": [],\n \"cacheBudget\": @2e9}", "/cacheBudget", "(got 2000000000)");
}

TEST_F(SceneFileTest, ExposureAndViewTransformKeysAreReadAndChecked) {
    const Scene scene = load(R"({"exposure": -9.4, "viewTransform": "khronos-pbr-neutral", "objects": []})");
    EXPECT_EQ(scene.render.exposure, std::optional<float>(-9.4f));
    EXPECT_EQ(scene.render.viewTransform, ViewTransform::KhronosPbrNeutral);
    EXPECT_FALSE(load(R"({"objects": []})").render.exposure);
    EXPECT_FALSE(load(R"({"objects": []})").render.viewTransform);
    expectError("{\"objects\": [],\n \"exposure\": @70}", "/exposure", "(got 70)");
    expectError("{\"objects\": [],\n \"exposure\": @\"bright\"}", "/exposure", "a number");
    expectError("{\"objects\": [],\n \"viewTransform\": @\"Filmic\"}", "/viewTransform",
                "must be one of standard, filmic, agx, khronos-pbr-neutral (got 'Filmic')");
}

TEST_F(SceneFileTest, FirstUnknownKeyInFileOrderIsReported) {
    expectError("{\"objects\": [], @\"zebra\": 1, \"aardvark\": 2}", "/zebra", "unknown key \"zebra\"");
}

TEST_F(SceneFileTest, KeyOfAnotherVariantIsRejected) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", @\"file\": \"a.obj\"}]}", "/objects/0/file",
                "key \"file\" does not apply to shape \"sphere\"");
}

// ---- types ----------------------------------------------------------------

TEST_F(SceneFileTest, WrongTypeNamesExpectedAndActual) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"radius\": @\"big\"}]}", "/objects/0/radius",
                "expected a number, got a string");
}

TEST_F(SceneFileTest, WrongVectorLength) {
    expectError("{\"camera\": {\"position\": @[1, 2]}, \"objects\": []}", "/camera/position",
                "expected 3 numbers [x, y, z], got 2");
}

TEST_F(SceneFileTest, WrongTypeInsideVector) {
    expectError("{\"camera\": {\"position\": [1, @true, 3]}, \"objects\": []}", "/camera/position/1",
                "expected a number, got a boolean");
}

TEST_F(SceneFileTest, FramesMustBeWhole) {
    expectError("{\"frames\": @2.5, \"objects\": []}", "/frames", "must be a whole number (got 2.5)");
}

// ---- required ---------------------------------------------------------------

TEST_F(SceneFileTest, MissingRequiredKeyPointsAtItsObject) {
    expectError("{\"objects\": [\n  @{\"radius\": 1}\n]}", "/objects/0", "missing required key \"shape\"");
}

TEST_F(SceneFileTest, MissingObjectsAtTopLevel) {
    expectError("@{\"name\": \"x\"}", "", "missing required key \"objects\"");
}

TEST_F(SceneFileTest, MissingLightPosition) {
    expectError("{\"lights\": [@{\"type\": \"spot\", \"direction\": [0, -1, 0]}], \"objects\": []}", "/lights/0",
                "missing required key \"position\"");
}

TEST_F(SceneFileTest, MissingMeshFileKey) {
    expectError("{\"objects\": [@{\"shape\": \"mesh\"}]}", "/objects/0", "missing required key \"file\"");
}

// ---- non-finite numbers ---------------------------------------------------

TEST_F(SceneFileTest, NumberOverflowingDoubleIsRejected) {
    expectError("{\"objects\": [{\"shape\": \"sphere\",\n \"radius\": @1e999}]}", "/objects/0/radius",
                "number 1e999 is out of range");
}

TEST_F(SceneFileTest, NumberOverflowingFloatIsRejected) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"center\": [0, @-1e39, 0]}]}", "/objects/0/center/1",
                "is too large to be represented (got -1e+39)");
}

// ---- sizes and ranges -------------------------------------------------------

TEST_F(SceneFileTest, NegativeRadius) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"radius\": @-1}]}", "/objects/0/radius",
                "must be > 0 (got -1)");
}

TEST_F(SceneFileTest, ZeroRadius) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"radius\": @0}]}", "/objects/0/radius",
                "must be > 0 (got 0)");
}

TEST_F(SceneFileTest, ZeroScaleComponent) {
    expectError("{\"objects\": [{\"shape\": \"box\", \"transform\": {\"scale\": [1, @0, 1]}}]}",
                "/objects/0/transform/scale/1", "must be > 0 (got 0)");
}

TEST_F(SceneFileTest, NegativeUniformScale) {
    expectError("{\"objects\": [{\"shape\": \"box\", \"transform\": {\"scale\": @-2}}]}",
                "/objects/0/transform/scale", "must be > 0 (got -2)");
}

TEST_F(SceneFileTest, NonUniformScaleOnSphere) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"transform\": {\"scale\": @[1, 2, 1]}}]}",
                "/objects/0/transform/scale", "a sphere needs a uniform scale (got [1, 2, 1])");
}

TEST_F(SceneFileTest, RotationOnSphere) {
    expectError(
        "{\"objects\": [{\"shape\": \"sphere\", \"transform\": {\"rotate\": @{\"axis\": [0, 1, 0], \"degrees\": 9}}}]}",
        "/objects/0/transform/rotate", "a sphere cannot be rotated");
}

TEST_F(SceneFileTest, IorMustBePositive) {
    // The example from the error format's specification, reproduced exactly.
    const std::string json =
        "{\n"
        "  \"objects\": [\n"
        "    {\"shape\": \"sphere\"},\n"
        "    {\"shape\": \"sphere\"},\n"
        "    {\"shape\": \"sphere\"},\n"
        "    {\n"
        "      \"shape\": \"sphere\",\n"
        "      \"center\": [0, 1, 0],\n"
        "      \"radius\": 0.5,\n"
        "      \"material\": {\n"
        "        \"diffuse\": [1, 1, 1],\n"
        "        \"kr\": 0.1,\n"
        "        \"kt\": 0.9,\n"
        "        \"ior\": @-1\n"
        "      }\n"
        "    }\n"
        "  ]\n"
        "}\n";
    const std::string m = expectError(json, "/objects/3/material/ior", "must be > 0 (got -1)");
    EXPECT_EQ(m, dir_.string() + "/scene.json:14:16: /objects/3/material/ior: must be > 0 (got -1)");
}

TEST_F(SceneFileTest, IorZero) {
    expectError("{\"materials\": {\"glass\": {\"ior\": @0}}, \"objects\": []}", "/materials/glass/ior",
                "must be > 0 (got 0)");
}

TEST_F(SceneFileTest, ReflectivityAboveOne) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"material\": {\"kr\": @1.5}}]}",
                "/objects/0/material/kr", "must be between 0 and 1 (got 1.5)");
}

TEST_F(SceneFileTest, TransmissivityBelowZero) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"material\": {\"kt\": @-0.25}}]}",
                "/objects/0/material/kt", "must be between 0 and 1 (got -0.25)");
}

TEST_F(SceneFileTest, CacheResolutionTooSmall) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"material\": {\"cache\": "
                "{\"technique\": \"cct\", \"resolution\": @8}}}]}",
                "/objects/0/material/cache/resolution", "must be between 16 and 2048 (got 8)");
}

TEST_F(SceneFileTest, CacheResolutionTooLarge) {
    expectError("{\"materials\": {\"m\": {\"cache\": {\"resolution\": @4096}}}, \"objects\": []}",
                "/materials/m/cache/resolution", "must be between 16 and 2048 (got 4096)");
}

TEST_F(SceneFileTest, CdctSearchParameters) {
    const Scene scene = load(R"({"objects": [{"shape": "sphere", "material": {"kr": 0.5,
        "cache": {"technique": "cdct-parity", "step": 2, "epsilon": 0.2, "maxDepth": 50, "tolerance": 3}}}]})");
    EXPECT_EQ(scene.objects[0].material.cache.technique, CacheTechnique::CdctParity);
    const CdctParameters& p = scene.objects[0].material.cache.cdct;
    EXPECT_EQ(p.tolerance, 3.0f);
    EXPECT_EQ(p.step, 2.0f);
    EXPECT_EQ(p.epsilon, 0.2f);
    EXPECT_EQ(p.maxDepth, 50.0f);
    EXPECT_EQ(load(R"({"objects": [{"shape": "sphere"}]})").objects[0].material.cache.cdct.step, 0.4f);
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"material\": {\"cache\": {\"maxDepth\": @0}}}]}",
                "/objects/0/material/cache/maxDepth", "must be > 0 (got 0)");
    expectError(
        "{\"objects\": [{\"shape\": \"sphere\", \"material\": {\"cache\": "
        "{\"step\": 0.1, \"epsilon\": @0.5}}}]}",
        "/objects/0/material/cache/epsilon", "cache epsilon must be smaller than step");
}

TEST_F(SceneFileTest, FovOfZero) {
    expectError("{\"camera\": {\"fov\": @0}, \"objects\": []}", "/camera/fov", "must be > 0 and < 180 (got 0)");
}

TEST_F(SceneFileTest, FovOf180) {
    expectError("{\"camera\": {\"fov\": @180}, \"objects\": []}", "/camera/fov", "must be > 0 and < 180 (got 180)");
}

TEST_F(SceneFileTest, NegativeColorComponent) {
    expectError("{\"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"intensity\": [1, @-1, 1]}], "
                "\"objects\": []}",
                "/lights/0/intensity/1", "must be >= 0 (got -1)");
}

TEST_F(SceneFileTest, SpotFalloffWiderThanCone) {
    expectError("{\"lights\": [{\"type\": \"spot\", \"position\": [0, 1, 0], \"direction\": [0, -1, 0], "
                "\"cone\": 10, \"falloff\": @20}], \"objects\": []}",
                "/lights/0/falloff", "must be between 0 and 10 (got 20)");
}

TEST_F(SceneFileTest, RangeNeedsAPhysicalLight) {
    expectError("{\"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"range\": @5}], \"objects\": []}",
                "/lights/0/range", "applies to physical lights only");
}

TEST_F(SceneFileTest, PhysicalMustBeABoolean) {
    expectError("{\"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"physical\": @1}], \"objects\": []}",
                "/lights/0/physical", "true or false");
}

TEST_F(SceneFileTest, PhysicalLightKeysAreRead) {
    const Scene scene = loadSceneFile(write("physical.json",
        "{\"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"physical\": true, \"range\": 5},"
        " {\"type\": \"directional\", \"direction\": [0, -1, 0]}], \"objects\": []}"));
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_TRUE(scene.lights[0].physical);
    EXPECT_EQ(scene.lights[0].range, 5.0f);
    EXPECT_FALSE(scene.lights[1].physical);  // the default: classic Whitted lights
}

TEST_F(SceneFileTest, CameraUpParallelToView) {
    expectError("{\"camera\": {\"position\": [0, 5, 0], \"lookAt\": [0, 0, 0], \"up\": @[0, 1, 0]}, \"objects\": []}",
                "/camera/up", "parallel to the viewing direction");
}

TEST_F(SceneFileTest, ZeroLightDirection) {
    expectError("{\"lights\": [{\"type\": \"directional\", \"direction\": @[0, 0, 0]}], \"objects\": []}",
                "/lights/0/direction", "must not be the zero vector");
}

// ---- enums ------------------------------------------------------------------

TEST_F(SceneFileTest, UnknownShapeListsTheValidOnes) {
    expectError("{\"objects\": [{\"shape\": @\"sphre\"}]}", "/objects/0/shape",
                "unknown shape \"sphre\" (expected one of: sphere, mesh, plane, box, cylinder, cone, torus, bowl; "
                "did you mean \"sphere\"?)");
}

TEST_F(SceneFileTest, UnknownCacheTechnique) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"material\": {\"cache\": {\"technique\": @\"fast\"}}}]}",
                "/objects/0/material/cache/technique",
                "unknown cache technique \"fast\" (expected one of: none, cct, cdct, cdct-parity)");
}

TEST_F(SceneFileTest, UnknownPathType) {
    expectError("{\"path\": {\"type\": @\"spiral\"}, \"objects\": []}", "/path/type",
                "unknown path type \"spiral\" (expected one of: static, orbit, pan, keyframes)");
}

TEST_F(SceneFileTest, UnknownEnvironmentType) {
    expectError("{\"environment\": {\"type\": @\"sky\"}, \"objects\": []}", "/environment/type",
                "(expected one of: color, equirect, cube)");
}

TEST_F(SceneFileTest, UnknownLightType) {
    expectError("{\"lights\": [{\"type\": @\"area\"}], \"objects\": []}", "/lights/0/type",
                "(expected one of: point, directional, spot)");
}

// ---- counts -----------------------------------------------------------------

TEST_F(SceneFileTest, AbsurdFrameCount) {
    expectError("{\"frames\": @1000000000, \"objects\": []}", "/frames", "must be between 1 and 1000000 (got 1000000000)");
}

TEST_F(SceneFileTest, AbsurdLightCount) {
    std::string lights;
    for (int i = 0; i < 65; ++i) lights += std::string(i ? ", " : "") + "{\"type\": \"point\", \"position\": [0, 1, 0]}";
    expectError("{\"lights\": @[" + lights + "], \"objects\": []}", "/lights",
                "has 65 lights, more than the limit of 64");
}

TEST_F(SceneFileTest, TooFewKeyframes) {
    expectError("{\"path\": {\"type\": \"keyframes\", \"keyframes\": @[{}]}, \"objects\": []}", "/path/keyframes",
                "needs at least 2 keyframes (got 1)");
}

// ---- referenced files -------------------------------------------------------

TEST_F(SceneFileTest, MissingMeshFileNamesThePathAsWritten) {
    const std::string m = expectError("{\"objects\": [{\"shape\": \"mesh\", \"file\": @\"meshes/nope.obj\"}]}",
                                      "/objects/0/file", "mesh file not found: \"meshes/nope.obj\"");
    EXPECT_NE(m.find((dir_ / "meshes/nope.obj").string()), std::string::npos) << m;
}

TEST_F(SceneFileTest, MissingTextureImage) {
    expectError("{\"objects\": [{\"shape\": \"box\", \"material\": {\"texture\": "
                "{\"type\": \"image\", \"file\": @\"wood.png\"}}}]}",
                "/objects/0/material/texture/file", "image file not found: \"wood.png\"");
}

TEST_F(SceneFileTest, MissingCubeFace) {
    for (const char* face : {"px", "nx", "py", "ny", "pz"}) write(std::string(face) + ".tga", tgaImage(2, 2));
    expectError("{\"environment\": {\"type\": \"cube\", \"faces\": [\"px.tga\", \"nx.tga\", \"py.tga\", "
                "\"ny.tga\", \"pz.tga\", @\"nz.tga\"]}, \"objects\": []}",
                "/environment/faces/5", "image file not found: \"nz.tga\"");
}

TEST_F(SceneFileTest, UnreadableMeshIsReportedWithItsPointer) {
    write("broken.obj", "this is not an OBJ file\n");
    const std::string m = expectError("{\"objects\": [{\"shape\": \"mesh\", \"file\": @\"broken.obj\"}]}",
                                      "/objects/0/file", "cannot load mesh \"broken.obj\"");
    // Once, followed by the mesh file's own position and the problem.
    EXPECT_EQ(m.find("cannot load mesh"), m.rfind("cannot load mesh")) << m;
    EXPECT_NE(m.find("broken.obj:1:1: unknown OBJ statement \"this\""), std::string::npos) << m;
}

TEST_F(SceneFileTest, NonSquareCubeFace) {
    for (const char* face : {"px", "nx", "py", "ny", "pz"}) write(std::string(face) + ".tga", tgaImage(2, 2));
    write("nz.tga", tgaImage(4, 2));
    expectError("{\"environment\": {\"type\": \"cube\", \"faces\": [\"px.tga\", \"nx.tga\", \"py.tga\", "
                "\"ny.tga\", \"pz.tga\", @\"nz.tga\"]}, \"objects\": []}",
                "/environment/faces/5", "cube face must be square (got 4x2)");
}

// ---- names ------------------------------------------------------------------

TEST_F(SceneFileTest, UnknownMaterialNameSuggestsADefinedOne) {
    expectError("{\"materials\": {\"chrome\": {\"kr\": 0.9}, \"glass\": {\"kt\": 0.9}},\n"
                " \"objects\": [{\"shape\": \"sphere\", \"material\": @\"chrom\"}]}",
                "/objects/0/material", "unknown material \"chrom\" (did you mean \"chrome\"?)");
}

TEST_F(SceneFileTest, UnknownMaterialNameWithoutMaterials) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"material\": @\"gold\"}]}", "/objects/0/material",
                "unknown material \"gold\" (the file defines no materials)");
}

TEST_F(SceneFileTest, DuplicateObjectNames) {
    expectError("{\"objects\": [\n  {\"name\": \"ball\", \"shape\": \"sphere\"},\n"
                "  {\"name\": @\"ball\", \"shape\": \"box\"}\n]}",
                "/objects/1/name", "duplicate object name \"ball\" (also used by /objects/0/name)");
}

TEST_F(SceneFileTest, MaterialNamesAreEscapedInPointers) {
    expectError("{\"materials\": {\"a/b~c\": {\"kr\": @2}}, \"objects\": []}", "/materials/a~1b~0c/kr",
                "must be between 0 and 1 (got 2)");
}

// ---- the scene file itself --------------------------------------------------

TEST_F(SceneFileTest, MissingSceneFileIsNamed) {
    const fs::path missing = dir_ / "nowhere.json";
    try {
        loadSceneFile(missing);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), missing.string() + ": scene file not found");
    }
}

TEST_F(SceneFileTest, DirectoryIsNotASceneFile) {
    EXPECT_THROW(loadSceneFile(dir_), InputError);
}

// ---- successful loads -------------------------------------------------------

TEST_F(SceneFileTest, ExampleSceneLoads) {
    const Scene scene = loadSceneFile(kExampleScene);
    EXPECT_EQ(scene.name, "Example: caching showcase");
    EXPECT_EQ(scene.objects.size(), 10u);
    EXPECT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.cameraPath.kind, CameraPathKind::Orbit);
    EXPECT_EQ(scene.defaultFrames, 180);
    int spheres = 0, meshes = 0, cached = 0;
    for (const SceneObject& o : scene.objects) {
        if (std::holds_alternative<Sphere>(o.shape)) ++spheres;
        if (const auto* m = std::get_if<MeshShape>(&o.shape)) {
            ++meshes;
            ASSERT_TRUE(m->mesh);
            EXPECT_TRUE(validateMesh(*m->mesh).empty()) << o.name;
        }
        if (o.material.cache.technique != CacheTechnique::None) ++cached;
    }
    EXPECT_EQ(spheres, 3);
    EXPECT_EQ(meshes, 7);
    EXPECT_EQ(cached, 3);
}

TEST_F(SceneFileTest, DefaultsAreApplied) {
    const Scene scene = load("{\"objects\": [{\"shape\": \"sphere\"}]}");
    const Camera defaultCamera;
    EXPECT_EQ(scene.name, "scene");  // the file's stem
    EXPECT_EQ(scene.camera.position, defaultCamera.position);
    EXPECT_EQ(scene.camera.lookAt, defaultCamera.lookAt);
    EXPECT_EQ(scene.camera.up, defaultCamera.up);
    EXPECT_EQ(scene.camera.verticalFovDeg, defaultCamera.verticalFovDeg);
    EXPECT_EQ(scene.cameraPath.kind, CameraPathKind::Static);
    EXPECT_EQ(scene.defaultFrames, 1);
    EXPECT_TRUE(scene.lights.empty());
    EXPECT_EQ(scene.environment.lookup({0, 1, 0}), Rgb(0.0f));
    ASSERT_EQ(scene.objects.size(), 1u);
    const SceneObject& o = scene.objects[0];
    EXPECT_EQ(o.name, "sphere#0");
    const auto& sphere = std::get<Sphere>(o.shape);
    EXPECT_EQ(sphere.center, Vec3(0, 0, 0));
    EXPECT_EQ(sphere.radius, 1.0f);
    EXPECT_EQ(o.origin, Vec3(0, 0, 0));
    const Material defaultMaterial;
    EXPECT_EQ(o.material.ambient, defaultMaterial.ambient);
    EXPECT_EQ(o.material.diffuse, defaultMaterial.diffuse);
    EXPECT_FALSE(o.material.diffuseTexture.has_value());
    EXPECT_EQ(o.material.ior, defaultMaterial.ior);
    EXPECT_EQ(o.material.reflectivity, 0.0f);
    EXPECT_EQ(o.material.cache.technique, CacheTechnique::None);
    EXPECT_EQ(o.material.cache.faceResolution, 512);
}

TEST_F(SceneFileTest, LightDefaults) {
    const Scene scene = load(R"({"lights": [
        {"type": "point", "position": [1, 2, 3]},
        {"type": "directional", "direction": [0, 0, -2], "intensity": 0.5},
        {"type": "spot", "position": [0, 4, 0], "direction": [0, -1, 0], "cone": 3}
      ], "objects": []})");
    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.lights[0].type, LightType::Point);
    EXPECT_EQ(scene.lights[0].position, Vec3(1, 2, 3));
    EXPECT_EQ(scene.lights[0].intensity, Rgb(1.0f));
    EXPECT_EQ(scene.lights[1].direction, Vec3(0, 0, -1));  // normalized
    EXPECT_EQ(scene.lights[1].intensity, Rgb(0.5f));
    EXPECT_EQ(scene.lights[2].coneAngleDeg, 3.0f);
    EXPECT_EQ(scene.lights[2].falloffAngleDeg, 3.0f);  // default 5, limited to the cone
}

TEST_F(SceneFileTest, NamedAndInlineMaterials) {
    const Scene scene = load(R"({
      "materials": {
        "chrome": {"diffuse": [0.1, 0.1, 0.1], "specular": 1, "shininess": 200, "kr": 0.9,
                   "cache": {"technique": "cdct", "resolution": 256}},
        "floor": {"texture": {"type": "checker", "even": [1, 1, 1], "odd": 0, "scale": 4}}
      },
      "objects": [
        {"name": "a", "shape": "sphere", "material": "chrome"},
        {"name": "b", "shape": "plane", "material": "floor"},
        {"name": "c", "shape": "sphere", "material": {"kt": 0.8, "ior": 1.33}}
      ]})");
    ASSERT_EQ(scene.objects.size(), 3u);
    const Material& chrome = scene.objects[0].material;
    EXPECT_EQ(chrome.diffuse, Rgb(0.1f));
    EXPECT_EQ(chrome.specular, Rgb(1.0f));
    EXPECT_EQ(chrome.shininess, 200.0f);
    EXPECT_EQ(chrome.reflectivity, 0.9f);
    EXPECT_EQ(chrome.cache.technique, CacheTechnique::Cdct);
    EXPECT_EQ(chrome.cache.faceResolution, 256);
    const Material& floor = scene.objects[1].material;
    ASSERT_TRUE(floor.diffuseTexture.has_value());
    EXPECT_EQ(floor.albedo(0.1f, 0.1f), Rgb(1.0f));
    EXPECT_EQ(floor.albedo(0.3f, 0.1f), Rgb(0.0f));
    const Material& water = scene.objects[2].material;
    EXPECT_EQ(water.transmissivity, 0.8f);
    EXPECT_EQ(water.ior, 1.33f);
}

TEST_F(SceneFileTest, MeshPathsAreRelativeToTheSceneFile) {
    write("level/meshes/tet.obj", kTetrahedronObj);
    const fs::path scene = write("level/scene.json", R"({"objects": [
        {"name": "plain", "shape": "mesh", "file": "meshes/tet.obj"},
        {"name": "again", "shape": "mesh", "file": "meshes/../meshes/tet.obj"},
        {"name": "moved", "shape": "mesh", "file": "meshes/tet.obj",
         "transform": {"translate": [10, 0, 0], "scale": 2}}
      ]})");
    // Load from an unrelated working directory: resolution must not depend on it.
    const fs::path previous = fs::current_path();
    fs::current_path(dir_);
    Scene s;
    EXPECT_NO_THROW(s = loadSceneFile(fs::relative(scene, dir_)));
    fs::current_path(previous);
    ASSERT_EQ(s.objects.size(), 3u);
    const auto& plain = std::get<MeshShape>(s.objects[0].shape).mesh;
    const auto& again = std::get<MeshShape>(s.objects[1].shape).mesh;
    const auto& moved = std::get<MeshShape>(s.objects[2].shape).mesh;
    EXPECT_EQ(plain.get(), again.get()) << "one file, loaded once, shared by untransformed instances";
    ASSERT_EQ(plain->positions.size(), moved->positions.size());
    for (std::size_t i = 0; i < plain->positions.size(); ++i)
        EXPECT_EQ(moved->positions[i], plain->positions[i] * 2.0f + Vec3(10, 0, 0));
    EXPECT_EQ(s.objects[2].origin, Vec3(10, 0, 0));
    EXPECT_EQ(s.objects[0].origin, Vec3(0, 0, 0));
}

TEST_F(SceneFileTest, SphereTransformMovesAndScales) {
    const Scene scene = load(R"({"objects": [
        {"shape": "sphere", "center": [1, 0, 0], "radius": 0.5,
         "transform": {"translate": [0, 2, 0], "scale": [3, 3, 3]}}]})");
    const auto& sphere = std::get<Sphere>(scene.objects[0].shape);
    EXPECT_EQ(sphere.center, Vec3(3, 2, 0));
    EXPECT_EQ(sphere.radius, 1.5f);
    EXPECT_EQ(scene.objects[0].origin, Vec3(3, 2, 0));
}

TEST_F(SceneFileTest, RotationsApplyInListedOrder) {
    const Scene scene = load(R"({"objects": [{"shape": "plane", "transform": {"rotate": [
        {"axis": [0, 0, 1], "degrees": 90}, {"axis": [1, 0, 0], "degrees": 90}]}}]})");
    const auto& mesh = std::get<MeshShape>(scene.objects[0].shape).mesh;
    ASSERT_FALSE(mesh->normals.empty());
    // The plane's normal +y: about z by 90 -> -x, then about x -> still -x.
    // The other order would give +z.
    for (const Vec3& n : mesh->normals) {
        EXPECT_NEAR(n.x, -1.0f, 1e-5f);
        EXPECT_NEAR(n.y, 0.0f, 1e-5f);
        EXPECT_NEAR(n.z, 0.0f, 1e-5f);
    }
}

TEST_F(SceneFileTest, PathDefaultsToOneTurnOrAllKeyframes) {
    Scene orbit = load(R"({"path": {"type": "orbit", "degreesPerFrame": 4}, "objects": []})");
    EXPECT_EQ(orbit.cameraPath.kind, CameraPathKind::Orbit);
    EXPECT_EQ(orbit.defaultFrames, 90);

    Scene keys = load(R"({"camera": {"fov": 30},
        "path": {"type": "keyframes", "framesPerSegment": 5, "keyframes": [
          {"position": [0, 0, 5]}, {"position": [5, 0, 0]}, {"position": [0, 0, -5], "fov": 60}]},
        "objects": []})");
    EXPECT_EQ(keys.defaultFrames, 11);
    ASSERT_EQ(keys.cameraPath.keyframes.size(), 3u);
    EXPECT_EQ(keys.cameraPath.keyframes[1].verticalFovDeg, 30.0f) << "keyframes default to the camera";
    EXPECT_EQ(keys.cameraPath.keyframes[2].verticalFovDeg, 60.0f);
    EXPECT_EQ(keys.camera.position, Vec3(0, 0, 5)) << "frame 0 is the first keyframe";

    Scene explicitFrames = load(R"({"path": {"type": "pan"}, "frames": 7, "objects": []})");
    EXPECT_EQ(explicitFrames.defaultFrames, 7);
}

TEST_F(SceneFileTest, ImageEnvironmentsAndTextures) {
    for (const char* face : {"px", "nx", "py", "ny", "pz", "nz"}) write(std::string("sky/") + face + ".tga", tgaImage(2, 2));
    write("tex.tga", tgaImage(4, 4, 255));
    const Scene scene = load(R"({
      "environment": {"type": "cube", "faces": ["sky/px.tga", "sky/nx.tga", "sky/py.tga",
                                                "sky/ny.tga", "sky/pz.tga", "sky/nz.tga"]},
      "objects": [{"shape": "box", "material": {"texture": {"type": "image", "file": "tex.tga"}}}]})");
    const Rgb sky = scene.environment.lookup({0, 0, -1});
    EXPECT_GT(sky.r, 0.1f);
    EXPECT_LT(sky.r, 0.5f);  // sRGB 128 is about 0.22 linear
    ASSERT_TRUE(scene.objects[0].material.diffuseTexture.has_value());
    EXPECT_NEAR(scene.objects[0].material.albedo(0.5f, 0.5f).r, 1.0f, 1e-4f);
}

// ---- input limits -------------------------------------------------------------

TEST_F(SceneFileTest, DeeplyNestedArraysAreRejectedAtTheDepthLimit) {
    // 200 kB of '[': before the limit, indexing it took 21 s and gigabytes.
    std::string pointer;
    for (int i = 0; i < 64; ++i) pointer += "/0";
    expectError(std::string(64, '[') + "@" + std::string(200000 - 64, '['), pointer, "nested more than 64 levels deep");
}

TEST_F(SceneFileTest, DeeplyNestedObjectsAreRejectedAtTheDepthLimit) {
    std::string json, pointer;
    for (int i = 0; i < 64; ++i) {
        json += "{\n\"a\": ";
        pointer += "/a";
    }
    expectError(json + "@{\"a\": 1}", pointer, "nested more than 64 levels deep");
}

TEST_F(SceneFileTest, NestingUpToTheLimitIsNotANestingError) {
    // Root object + 63 arrays = 64 levels: past the limit check, refused for its type instead.
    const std::string m = expectError(
        "{\"objects\": [], \"frames\": @" + std::string(63, '[') + std::string(63, ']') + "}", "/frames", "");
    EXPECT_EQ(m.find("nested"), std::string::npos) << m;
}

TEST_F(SceneFileTest, OverlongStringIsRejected) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"name\": @\"" + std::string(70000, 'x') + "\"}]}",
                "/objects/0/name", "string of 70000 bytes, more than the limit of 65536");
}

// ---- absurd geometry ------------------------------------------------------------

TEST_F(SceneFileTest, SphereRadiusBeyondTheWorldLimitIsRejected) {
    // 3e38 is a finite float, but its bounds are not: it used to render nothing, silently.
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"radius\": @3e38}]}", "/objects/0/radius",
                "reaches 3e+38, beyond the limit of ±10000000");
}

TEST_F(SceneFileTest, SphereCentreBeyondTheWorldLimitIsRejected) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"center\": @[0, 2e7, 0], \"radius\": 1}]}",
                "/objects/0/center", "beyond the limit of ±10000000");
}

TEST_F(SceneFileTest, SphereScaledBeyondTheWorldLimitIsRejected) {
    expectError("{\"objects\": [{\"shape\": \"sphere\", \"transform\": @{\"scale\": 1e30}}]}", "/objects/0/transform",
                "beyond the limit");
}

TEST_F(SceneFileTest, LargeSphereWithinTheLimitLoads) {
    // The classic "ground sphere" of radius 1e5 is fine.
    const Scene scene = load(R"({"objects": [{"shape": "sphere", "center": [0, -100001, 0], "radius": 100000}]})");
    EXPECT_EQ(std::get<Sphere>(scene.objects.at(0).shape).radius, 100000.0f);
}

TEST_F(SceneFileTest, MeshTransformMakingVerticesInfiniteIsRejected) {
    write("far.obj", "v 0 0 0\nv 10 0 0\nv 0 10 0\nf 1 2 3\n");
    expectError("{\"objects\": [{\"shape\": \"mesh\", \"file\": \"far.obj\", \"transform\": @{\"scale\": 1e38}}]}",
                "/objects/0/transform", "its transform makes 2 of the mesh's 3 vertices non-finite");
}

TEST_F(SceneFileTest, MeshTransformBeyondTheWorldLimitIsRejected) {
    expectError("{\"objects\": [{\"shape\": \"box\", \"transform\": @{\"translate\": [3e7, 0, 0]}}]}",
                "/objects/0/transform", "vertices lie beyond ±10000000");
}

TEST_F(SceneFileTest, MeshFileBeyondTheWorldLimitIsRejected) {
    write("huge.obj", "v 0 0 0\nv 1e9 0 0\nv 0 1 0\nf 1 2 3\n");
    expectError("{\"objects\": [{\"shape\": \"mesh\", \"file\": @\"huge.obj\"}]}", "/objects/0/file",
                "1 of the mesh's 3 vertices lie beyond ±10000000");
}

// ---- animation ------------------------------------------------------------

TEST_F(SceneFileTest, ObjectAndLightAnimationsLoadAndTheSceneStartsAtTimeZero) {
    const Scene scene = load(R"({"fps": 24,
        "lights": [{"type": "point", "position": [0, 10, 0],
                    "animation": {"keys": [{"time": 0, "position": [-5, 10, 0]}, {"time": 2, "position": [5, 10, 0]}],
                                  "interpolation": "smooth", "wrap": "clamp"}}],
        "objects": [{"shape": "sphere", "center": [3, 1, 0], "radius": 0.5,
                     "animation": {"keys": [{"time": 0, "translate": [0, 1, 0]},
                                            {"time": 1, "rotate": {"axis": [0, 1, 0], "degrees": 90}, "scale": 2}],
                                   "wrap": "clamp"}},
                    {"shape": "box"}]})");
    EXPECT_EQ(scene.fps, 24.0f);
    ASSERT_EQ(scene.animation.objects.size(), 1u);
    ASSERT_EQ(scene.animation.lights.size(), 1u);
    EXPECT_EQ(scene.animation.lights[0].interpolation, Interpolation::Smooth);
    EXPECT_EQ(scene.animation.lights[0].wrap, Wrap::Clamp);
    // Posed at time 0: the first key applies (the sphere lifted by 1, the light at its first position).
    EXPECT_EQ(std::get<Sphere>(scene.objects[0].shape).center, (Vec3{3, 2, 0}));
    EXPECT_EQ(scene.objects[0].origin, (Vec3{3, 2, 0}));
    EXPECT_EQ(scene.lights[0].position, (Vec3{-5, 10, 0}));
    // At 1 s the key scales by 2 and turns a quarter about y, both about
    // the world's origin, like an object's transform: (3, 1, 0) -> (0, 2, -6).
    Scene posed = scene;
    poseScene(scene, 1.0f, posed);
    const Sphere& s = std::get<Sphere>(posed.objects[0].shape);
    EXPECT_NEAR(s.center.x, 0.0f, 1e-5f);
    EXPECT_NEAR(s.center.y, 2.0f, 1e-5f);
    EXPECT_NEAR(s.center.z, -6.0f, 1e-5f);
    EXPECT_NEAR(s.radius, 1.0f, 1e-5f);
}

TEST_F(SceneFileTest, AnimationKeyTimesMustIncrease) {
    expectError(R"({"objects": [{"shape": "sphere", "animation": {"keys": [{"time": 1}, {"time": @1}]}}]})",
                "/objects/0/animation/keys/1/time", "key times must increase (got 1 after 1)");
}

TEST_F(SceneFileTest, AnimationNeedsKeys) {
    expectError(R"({"objects": [{"shape": "sphere", "animation": {"keys": @[]}}]})", "/objects/0/animation/keys",
                "needs at least 1 keys");
}

TEST_F(SceneFileTest, AnimatedSphereRejectsNonUniformScale) {
    expectError(R"({"objects": [{"shape": "sphere", "animation": {"keys": [{"time": 0, "scale": @[1, 2, 1]}]}}]})",
                "/objects/0/animation/keys/0/scale", "a sphere needs a uniform scale");
}

TEST_F(SceneFileTest, AnimationKeyRejectsUnknownKeysAndBadValues) {
    expectError(R"({"objects": [{"shape": "box", "animation": {"keys": [{"time": 0, @"translation": [1, 2, 3]}]}}]})",
                "/objects/0/animation/keys/0/translation", "unknown key \"translation\"");
    expectError(R"({"objects": [{"shape": "box", "animation": {"keys": [{"time": 0}], "wrap": @"bounce"}}]})",
                "/objects/0/animation/wrap", "must be one of loop, clamp");
    expectError(R"({"objects": [{"shape": "box", "animation": {"keys": [{"time": @"soon"}]}}]})",
                "/objects/0/animation/keys/0/time", "expected a number");
}

TEST_F(SceneFileTest, AnimationKeyMovingTheObjectBeyondTheWorldLimitIsRejected) {
    expectError(R"({"objects": [{"shape": "sphere", "animation": {"keys": [{"time": 0},
                   @{"time": 1, "translate": [3e38, 0, 0]}]}}]})",
                "/objects/0/animation/keys/1", "beyond the limit of 10000000");
    expectError(R"({"objects": [{"shape": "box", "transform": {"translate": [5, 0, 0]},
                   "animation": {"keys": [@{"time": 0, "scale": 1e7}]}}]})",
                "/objects/0/animation/keys/0", "beyond the limit");
}

TEST_F(SceneFileTest, LightKeyTakesOnlyWhatItsTypeUses) {
    expectError(R"({"lights": [{"type": "point", "position": [0, 1, 0],
                   "animation": {"keys": [{"time": 0, @"direction": [0, -1, 0]}]}}], "objects": []})",
                "/lights/0/animation/keys/0/direction", "unknown key \"direction\"");
}

TEST_F(SceneFileTest, FpsMustBePositive) {
    expectError(R"({"fps": @0, "objects": []})", "/fps", "must be");
}

TEST_F(SceneFileTest, MeshFramesNeedTheRestMeshsVertices) {
    write("rest.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write("f1.obj", "v 0 0 1\nv 1 0 1\nv 0 1 1\nf 1 2 3\n");
    write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    const Scene scene = load(R"({"objects": [{"shape": "mesh", "file": "rest.obj",
                                 "frames": {"files": ["rest.obj", "f1.obj"], "fps": 2}}]})");
    Scene posed = scene;
    poseScene(scene, 0.25f, posed);  // halfway from frame 0 to frame 1
    EXPECT_NEAR(std::get<MeshShape>(posed.objects[0].shape).mesh->positions[0].z, 0.5f, 1e-6f);
    expectError(R"({"objects": [{"shape": "mesh", "file": "rest.obj", "frames": {"files": [@"bad.obj"]}}]})",
                "/objects/0/frames/files/0", "has 4 vertices, the object's \"file\" has 3");
}

}  // namespace
}  // namespace raycache
