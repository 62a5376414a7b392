// The limits a glTF file's JSON must keep before Assimp reads it
// (scene/GltfLimits.h, scene/GltfNodeGraph.h; docs/scene-format.md,
// "Limits"): each limit refused just above its value and kept at it, the node
// graph's cycles, second parents and bad indices refused, all one error line
// naming the file and the field, as a scene and as a mesh of a JSON scene.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "GltfTestFile.h"
#include "TempDir.h"
#include "core/Errors.h"
#include "scene/GltfLimits.h"
#include "scene/GltfScene.h"
#include "scene/MeshGenerators.h"
#include "scene/MeshLoader.h"

namespace raycache {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<unsigned char> base64Decoded(const std::string& text) {
    std::vector<unsigned char> out;
    std::uint32_t bits = 0;
    int count = 0;
    for (const char c : text) {
        int digit = -1;
        if (c >= 'A' && c <= 'Z') digit = c - 'A';
        if (c >= 'a' && c <= 'z') digit = c - 'a' + 26;
        if (c >= '0' && c <= '9') digit = c - '0' + 52;
        if (c == '+') digit = 62;
        if (c == '/') digit = 63;
        if (digit < 0) continue;
        bits = bits << 6 | static_cast<std::uint32_t>(digit);
        if ((count += 6) >= 8) {
            count -= 8;
            out.push_back(static_cast<unsigned char>(bits >> count & 0xff));
        }
    }
    return out;
}

void appendWord(std::string& out, std::uint32_t word) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>(word >> (8 * i) & 0xff);
}

// The same document as a binary glTF: its one buffer, a data: URI in a
// GltfTestFile, moved into the BIN chunk.
void writeGlb(const fs::path& path, json document) {
    const std::string uri = document["buffers"][0]["uri"].get<std::string>();
    std::vector<unsigned char> bin = base64Decoded(uri.substr(uri.find(',') + 1));
    document["buffers"][0].erase("uri");
    while (bin.size() % 4 != 0) bin.push_back(0);
    std::string text = document.dump();
    while (text.size() % 4 != 0) text += ' ';
    std::string glb = "glTF";
    appendWord(glb, 2);
    appendWord(glb, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    appendWord(glb, static_cast<std::uint32_t>(text.size()));
    glb += "JSON" + text;
    appendWord(glb, static_cast<std::uint32_t>(bin.size()));
    glb += std::string("BIN") + '\0';
    glb.append(bin.begin(), bin.end());
    std::ofstream(path, std::ios::binary) << glb;
}

json readJson(const fs::path& path) {
    std::ifstream in(path);
    return json::parse(in);
}

void writeJson(const fs::path& path, const json& document) {
    std::ofstream(path, std::ios::binary) << document.dump();
}

class GltfLimitsTest : public ::testing::Test {
protected:
    fs::path path(const std::string& name) const { return dir_.path() / name; }

    // A box placed by the last node of a chain of `depth` nodes, node 0 the root.
    json chain(std::size_t depth) const {
        GltfTestFile file;
        const int mesh = file.addMesh(makeBox());
        file.addNode(json::object());
        json& nodes = file.document()["nodes"];
        for (std::size_t i = 1; i < depth; ++i) {
            nodes[i - 1]["children"] = {i};
            nodes.push_back(json::object());
        }
        nodes[depth - 1]["mesh"] = mesh;
        const fs::path scratch = path("chain-scratch.gltf");
        file.write(scratch);
        return readJson(scratch);
    }

    // A valid file of one box, as a document to edit.
    json box() const {
        GltfTestFile file;
        file.addNode({{"mesh", file.addMesh(makeBox())}});
        const fs::path scratch = path("box-scratch.gltf");
        file.write(scratch);
        return readJson(scratch);
    }

    // Writes `document` as `name` and expects loading it as a scene and as a
    // mesh to give one InputError naming the file and holding `words`.
    void expectRefused(const std::string& name, const json& document, const std::string& words) const {
        const fs::path file = path(name);
        if (file.extension() == ".glb")
            writeGlb(file, document);
        else
            writeJson(file, document);
        expectRefusedFile(file, words);
    }

    static void expectRefusedFile(const fs::path& file, const std::string& words) {
        for (const bool asScene : {true, false}) {
            SCOPED_TRACE(asScene ? "as a scene" : "as a mesh");
            try {
                if (asScene)
                    (void)loadGltfScene(file);
                else
                    (void)loadMeshFile(file);
                ADD_FAILURE() << file << " loaded";
            } catch (const InputError& e) {
                const std::string what = e.what();
                EXPECT_EQ(e.where().file, file.string());
                EXPECT_NE(what.find(words), std::string::npos) << what;
                EXPECT_EQ(what.find('\n'), std::string::npos) << what;
            }
        }
    }

    void expectLoads(const std::string& name, const json& document) const {
        const fs::path file = path(name);
        if (file.extension() == ".glb")
            writeGlb(file, document);
        else
            writeJson(file, document);
        try {
            EXPECT_FALSE(loadGltfScene(file).objects.empty());
            EXPECT_FALSE(loadMeshFile(file).mesh.triangles.empty());
        } catch (const InputError& e) {
            ADD_FAILURE() << e.what();
        }
    }

    TempDir dir_;
};

// Assimp 5.2's glTF reader recursed once per level and overflowed the stack
// (a crash, exit 139) on a 20 000-deep chain.
TEST_F(GltfLimitsTest, DeepNodeChainIsOneErrorNotACrash) {
    const json deep = chain(20000);
    const std::string words = "/nodes/1023/children: the node graph is 20000 levels deep, more than the limit of 1024";
    expectRefused("deep.gltf", deep, words);
    expectRefused("deep.glb", deep, words);
}

TEST_F(GltfLimitsTest, NodeDepthIsKeptAtItsLimitAndRefusedAbove) {
    expectLoads("at.gltf", chain(kMaxGltfNodeDepth));
    expectLoads("at.glb", chain(kMaxGltfNodeDepth));
    expectRefused("above.gltf", chain(kMaxGltfNodeDepth + 1),
                  "/nodes/1023/children: the node graph is 1025 levels deep, more than the limit of 1024");
}

TEST_F(GltfLimitsTest, CyclesAreRefusedNamingTheLinkThatClosesThem) {
    json two = box();
    two["nodes"].push_back({{"children", {2}}});
    two["nodes"].push_back({{"children", {1}}});
    expectRefused("two.gltf", two, "/nodes/1/children/0: the node graph has a cycle: node 1 -> node 2 -> node 1");

    json itself = box();
    itself["nodes"][0]["children"] = {0};
    expectRefused("itself.gltf", itself, "/nodes/0/children/0: node 0 lists itself as its child");

    // A long cycle is named by its first nodes and its length.
    json ring = box();
    for (int i = 1; i <= 20; ++i) ring["nodes"].push_back({{"children", {i == 20 ? 1 : i + 1}}});
    expectRefused("ring.glb", ring,
                  "/nodes/1/children/0: the node graph has a cycle: node 1 -> node 2 -> node 3 -> node 4 -> node 5 -> "
                  "node 6 -> ... (20 nodes) -> node 1");
}

TEST_F(GltfLimitsTest, ANodeWithTwoParentsIsRefused) {
    json shared = box();
    shared["nodes"].push_back({{"children", {0}}});
    shared["nodes"].push_back({{"children", {0}}});
    shared["scenes"][0]["nodes"] = {1, 2};
    expectRefused("shared.gltf", shared,
                  "/nodes/2/children/0: node 0 is already a child of node 1 (a glTF node has at most one parent)");

    // Listed twice by the same parent: Assimp would place it twice.
    json twice = box();
    twice["nodes"].push_back({{"children", {0, 0}}});
    twice["scenes"][0]["nodes"] = {1};
    expectRefused("twice.glb", twice, "/nodes/1/children/1: node 0 is already a child of node 1");
}

TEST_F(GltfLimitsTest, IndicesOfTheNodeGraphMustNameNodes) {
    json child = box();
    child["nodes"][0]["children"] = {5};
    expectRefused("child.gltf", child, "/nodes/0/children/0: node 5 does not exist (the file has 1 nodes)");
    json text = box();
    text["nodes"][0]["children"] = {"one"};
    expectRefused("text.gltf", text, "/nodes/0/children/0: not a node index");
    json root = box();
    root["scenes"][0]["nodes"] = {0, 3};
    expectRefused("root.gltf", root, "/scenes/0/nodes/1: node 3 does not exist");
    json inner = box();
    inner["nodes"].push_back({{"children", {0}}});
    inner["scenes"][0]["nodes"] = {1, 0};
    expectRefused("inner.gltf", inner, "/scenes/0/nodes/1: node 0 is a child of node 1, not a root node");
    json repeated = box();
    repeated["scenes"][0]["nodes"] = {0, 0};
    expectRefused("repeated.gltf", repeated, "/scenes/0/nodes/1: node 0 is listed twice (also at /scenes/0/nodes/0)");
}

// Entries nothing refers to fill each array to its limit, then one more: the
// check itself on the parsed document (a file of a million entries costs
// seconds to parse, twice), and one count through the loaders. The fillers
// are nulls where the other checks let them be, which cost no allocation.
TEST_F(GltfLimitsTest, CountsAreKeptAtTheirLimitsAndRefusedAbove) {
    struct Case {
        const char* key;
        std::size_t limit;
        json filler;
    };
    const std::vector<Case> cases = {
        {"nodes", kMaxGltfNodes, nullptr},
        {"meshes", kMaxGltfMeshes, nullptr},
        {"accessors", kMaxGltfAccessors, nullptr},
        {"bufferViews", kMaxGltfBufferViews, json::object({{"buffer", 0}})},
        {"buffers", kMaxGltfBuffers, nullptr},
        {"images", kMaxGltfImages, json::object()},
    };
    const fs::path file = path("counted.gltf");
    for (const Case& c : cases) {
        SCOPED_TRACE(c.key);
        json document = box();
        json& entries = document[c.key];
        if (!entries.is_array()) entries = json::array();
        entries.get_ref<json::array_t&>().resize(c.limit, c.filler);
        try {
            checkGltfLimits(file, document, {});
        } catch (const InputError& e) {
            ADD_FAILURE() << e.what();
        }
        entries.push_back(c.filler);
        const std::string words = "/" + std::string(c.key) + ": has " + std::to_string(c.limit + 1) + " " + c.key +
                                  ", more than the limit of " + std::to_string(c.limit);
        try {
            checkGltfLimits(file, document, {});
            ADD_FAILURE() << "not refused";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()), file.string() + ": " + words);
        }
        if (std::string(c.key) == "images") {
            expectRefused("images-above.gltf", document, words);
            entries.erase(entries.size() - 1);
            expectLoads("images-at.gltf", document);
        }
    }
}

TEST_F(GltfLimitsTest, BufferLengthsMustFitTheirDataAndTheLimit) {
    const json good = box();
    const std::uint64_t bytes = good["buffers"][0]["byteLength"].get<std::uint64_t>();
    json data = good;
    data["buffers"][0]["byteLength"] = bytes + 4;
    expectRefused("data.gltf", data,
                  "/buffers/0/byteLength: " + std::to_string(bytes + 4) + " bytes, more than the " +
                      std::to_string(bytes) + " bytes of its data: URI");
    expectRefused("chunk.glb", data,
                  "/buffers/0/byteLength: " + std::to_string(bytes + 4) + " bytes, more than the " +
                      std::to_string(bytes) + " bytes of the file's binary chunk");

    // A buffer in a file beside it, one byte short.
    const std::string uri = good["buffers"][0]["uri"].get<std::string>();
    const std::vector<unsigned char> bin = base64Decoded(uri.substr(uri.find(',') + 1));
    std::ofstream(path("short data.bin"), std::ios::binary)
        .write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size() - 1));
    json beside = good;
    beside["buffers"][0]["uri"] = "short%20data.bin";
    expectRefused("beside.gltf", beside,
                  "/buffers/0/byteLength: " + std::to_string(bytes) + " bytes, more than the " +
                      std::to_string(bytes - 1) + " bytes of \"short%20data.bin\"");

    // All buffers together: at the limit the data's own length is what is
    // wrong; one byte more and the limit is.
    json total = good;
    total["buffers"].push_back({{"byteLength", kMaxGltfBufferBytes - bytes}, {"uri", "data:;base64,AAAA"}});
    expectRefused("at-limit.gltf", total, "/buffers/1/byteLength: " + std::to_string(kMaxGltfBufferBytes - bytes) +
                                              " bytes, more than the 3 bytes of its data: URI");
    total["buffers"][1]["byteLength"] = kMaxGltfBufferBytes - bytes + 1;
    expectRefused("above-limit.gltf", total,
                  "/buffers/1/byteLength: the buffers hold " + std::to_string(kMaxGltfBufferBytes + 1) +
                      " bytes up to this one, more than the limit of 1073741824 for all together");
}

TEST_F(GltfLimitsTest, BufferViewsAndAccessorsMustLieWithinWhatHoldsThem) {
    const json good = box();
    const std::uint64_t bytes = good["buffers"][0]["byteLength"].get<std::uint64_t>();
    json view = good;
    // Offset and length that wrap around 2^64 when added.
    view["bufferViews"][0]["byteOffset"] = std::uint64_t{0xfffffffffffffff0u};
    view["bufferViews"][0]["byteLength"] = 32;
    expectRefused("view.gltf", view,
                  "/bufferViews/0: bytes 18446744073709551600 to 18446744073709551615 lie beyond the " +
                      std::to_string(bytes) + " bytes of buffer 0");
    json noBuffer = good;
    noBuffer["bufferViews"][0]["buffer"] = 1;
    expectRefused("nobuffer.gltf", noBuffer, "/bufferViews/0/buffer: names no buffer (the file has 1)");

    // A stride that Assimp's own check (count times the element's size) missed.
    json stride = good;
    const std::uint64_t viewBytes = stride["bufferViews"][0]["byteLength"].get<std::uint64_t>();
    stride["bufferViews"][0]["byteStride"] = 16;
    const std::uint64_t count = stride["accessors"][0]["count"].get<std::uint64_t>();
    expectRefused("stride.glb", stride,
                  "/accessors/0: " + std::to_string(count) + " elements of 12 bytes, 16 bytes apart from byte 0, end at byte " +
                      std::to_string((count - 1) * 16 + 12) + ", beyond the " + std::to_string(viewBytes) +
                      " bytes of buffer view 0");

    json many = good;
    many["accessors"].push_back({{"count", kMaxGltfAccessorElements}, {"type", "SCALAR"}, {"componentType", 5121}});
    expectLoads("count-at.gltf", many);
    many["accessors"].back()["count"] = kMaxGltfAccessorElements + 1;
    expectRefused("count-above.gltf", many, "/count: 60000001 elements, more than the limit of 60000000");
    many["accessors"].back() = {{"count", kMaxGltfAccessorElements}, {"type", "MAT4"}, {"componentType", 5126}};
    expectRefused("zeros.gltf", many,
                  "/count: 60000000 elements of 64 bytes without a buffer view (zeros), more than the limit of "
                  "1073741824 bytes");
}

// Assimp 5.2 reads as many sparse indices and values as the sparse count
// says, and follows the indices' buffer view without looking whether there is one.
TEST_F(GltfLimitsTest, SparseAccessorsMustLieWithinTheirViews) {
    json sparse = box();
    const std::uint64_t count = sparse["accessors"][0]["count"].get<std::uint64_t>();
    // Two vertex indices of the box's triangles say which positions are replaced.
    const json& indices = sparse["accessors"][sparse["meshes"][0]["primitives"][0]["indices"].get<std::size_t>()];
    const json indexView = indices["bufferView"];
    sparse["accessors"][0]["sparse"] = {{"count", 2},
                                        {"indices", {{"bufferView", indexView}, {"componentType", 5125}}},
                                        {"values", {{"bufferView", 0}}}};
    expectLoads("sparse.gltf", sparse);
    sparse["accessors"][0]["sparse"]["count"] = count + 1;
    expectRefused("more.gltf", sparse,
                  "/accessors/0/sparse/count: " + std::to_string(count + 1) + " elements, more than the accessor's " +
                      std::to_string(count));
    sparse["accessors"][0]["sparse"]["count"] = 2;
    sparse["accessors"][0]["sparse"]["indices"].erase("bufferView");
    expectRefused("noview.gltf", sparse, "/accessors/0/sparse/indices/bufferView: missing");
    sparse["accessors"][0]["sparse"].erase("indices");
    expectRefused("noindices.gltf", sparse, "/accessors/0/sparse/indices: missing");
}

// Found by fuzzing: a number beyond a double's range escaped the JSON
// reader as another exception than a parse error (tests/fuzz/findings/).
TEST_F(GltfLimitsTest, NumberBeyondADoubleIsOneError) {
    json document = box();
    document["nodes"][0]["translation"] = {0, 0, 0};
    std::string text = document.dump();
    text.replace(text.find("[0,0,0]"), 7, "[0,1e391,0]");
    std::ofstream(path("huge.gltf"), std::ios::binary) << text;
    try {
        (void)loadGltfScene(path("huge.gltf"));
        ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not valid glTF JSON: number overflow parsing '1e391'"), std::string::npos)
            << e.what();
    }
    // As a mesh it is left to Assimp's reader, which refuses it too.
    EXPECT_THROW((void)loadMeshFile(path("huge.gltf")), InputError);
}

// Found by fuzzing: Assimp 5.2 read past the '/' an embedded image's MIME
// type did not have (a crash).
TEST_F(GltfLimitsTest, EmbeddedImagesNeedAMimeType) {
    const std::string png = "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAIAAAD91JpzAAAAEklEQVR4nGP4z8DAAMIM/4EAAB/uBfsL2WiLAAAAAElFTkSuQmCC";
    json document = box();
    document["images"] = {{{"uri", "data:imagepng;base64," + png}}};
    document["textures"] = {{{"source", 0}}};
    document["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    document["meshes"][0]["primitives"][0]["material"] = 0;
    expectRefused("uri.gltf", document,
                  "/images/0/uri: the data: URI's media type \"imagepng\" is not a MIME type (type/subtype, e.g. "
                  "image/png)");
    document["images"][0]["uri"] = "data:image/png;base64," + png;
    expectLoads("png.gltf", document);
    document["images"][0] = {{"bufferView", 0}, {"mimeType", "png"}};
    expectRefused("view.gltf", document, "/images/0/mimeType: \"png\" is not a MIME type");
}

// glTF 1.0 files still load as meshes; Assimp's 1.0 reader recursed too.
TEST_F(GltfLimitsTest, Version1NodeGraphIsCheckedForMeshes) {
    const fs::path twoBoxes = "/usr/share/assimp/models/glTF/TwoBoxes/TwoBoxes.gltf";
    if (!fs::exists(twoBoxes)) GTEST_SKIP() << twoBoxes << " is missing: Debian's assimp-testmodels is not installed";
    json document = readJson(twoBoxes);
    fs::copy_file(twoBoxes.parent_path() / "Box.bin", path("Box.bin"));
    json nodes = json::object();
    constexpr int kDepth = 3000;
    for (int i = 0; i < kDepth; ++i) {
        json node = {{"children", json::array()}};
        if (i + 1 < kDepth) node["children"].push_back("n" + std::to_string(i + 1));
        nodes["n" + std::to_string(i)] = node;
    }
    nodes["n" + std::to_string(kDepth - 1)]["meshes"] = {"Geometry-mesh002"};
    document["nodes"] = nodes;
    document["scenes"] = {{"defaultScene", {{"nodes", {"n0"}}}}};
    writeJson(path("old.gltf"), document);
    try {
        (void)loadMeshFile(path("old.gltf"));
        ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/nodes/n1023/children: the node graph is 3000 levels deep"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace raycache
