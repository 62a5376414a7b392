#include "scene/GltfDocument.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <system_error>

#include "core/Errors.h"
#include "core/TextFormat.h"
#include "scene/GltfLimits.h"
#include "scene/MeshLimits.h"

namespace raycache {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& path, const std::string& message, int line = 0, int column = 0) {
    throw InputError(InputLocation{.file = path.string(), .line = line, .column = column}, message);
}

std::string readBytes(const fs::path& path, std::uintmax_t offset, std::uintmax_t count) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open glTF file");
    in.seekg(static_cast<std::streamoff>(offset));
    std::string bytes(static_cast<std::size_t>(count), '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (in.bad() || in.gcount() != static_cast<std::streamsize>(bytes.size())) fail(path, "cannot read glTF file");
    return bytes;
}

std::uint32_t littleEndianWord(const std::string& bytes, std::size_t at) {
    std::uint32_t word = 0;
    for (int i = 3; i >= 0; --i) word = word << 8 | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
    return word;
}

// The JSON of a glTF file, and where the file keeps its binary data.
struct GltfJsonText {
    std::string text;  // empty for a binary glTF 1.0 file whose content is not JSON
    GltfFileLayout layout;
    bool version1Binary = false;
};

// A binary glTF 1.0 file: a 20-byte header whose fourth word is the
// content's length and fifth its format (0: JSON), then the content.
GltfJsonText glb1Json(const fs::path& path, std::uintmax_t fileBytes, const std::string& header) {
    GltfJsonText file{.layout = {.binary = true}, .version1Binary = true};
    const std::uint32_t length = littleEndianWord(header, 12);
    if (length > fileBytes - 20)
        fail(path, "binary glTF 1.0 content claims " + std::to_string(length) + " bytes, more than the " +
                       std::to_string(fileBytes - 20) + " left in the file");
    if (littleEndianWord(header, 16) == 0) file.text = readBytes(path, 20, length);
    return file;
}

// Binary glTF: the JSON chunk's text and the length of the BIN chunk after it.
GltfJsonText glbJson(const fs::path& path, std::uintmax_t fileBytes) {
    if (fileBytes < 20)
        fail(path, "binary glTF file of " + std::to_string(fileBytes) + " bytes: too short for its header");
    const std::string header = readBytes(path, 0, 20);
    const std::uint32_t version = littleEndianWord(header, 4);
    if (version == 1) return glb1Json(path, fileBytes, header);
    if (version != 2) fail(path, "binary glTF version " + std::to_string(version) + " (expected 2)");
    const std::uint32_t length = littleEndianWord(header, 12);
    if (std::memcmp(header.data() + 16, "JSON", 4) != 0) fail(path, "binary glTF: the first chunk is not JSON");
    if (length > fileBytes - 20)
        fail(path, "binary glTF: the JSON chunk claims " + std::to_string(length) + " bytes, more than the " +
                       std::to_string(fileBytes - 20) + " left in the file");
    GltfJsonText file{.text = readBytes(path, 20, length), .layout = {.binary = true}};
    // The BIN chunk, if any, follows: its length, "BIN\0", its bytes.
    const std::uintmax_t binAt = 20 + std::uintmax_t{length};
    if (fileBytes >= binAt + 8) {
        const std::string binHeader = readBytes(path, binAt, 8);
        if (std::memcmp(binHeader.data() + 4, "BIN\0", 4) == 0)
            file.layout.binaryChunkBytes =
                std::min<std::uint64_t>(littleEndianWord(binHeader, 0), fileBytes - binAt - 8);
    }
    return file;
}

GltfJsonText gltfJsonText(const fs::path& path) {
    std::error_code ec;
    const std::uintmax_t bytes = fs::file_size(path, ec);
    if (ec) fail(path, "cannot read glTF file: " + ec.message());
    if (bytes > kMaxMeshFileBytes)
        fail(path, "glTF file is " + std::to_string(bytes) + " bytes, more than the limit of " +
                       std::to_string(kMaxMeshFileBytes));
    if (bytes >= 4 && readBytes(path, 0, 4) == "glTF") return glbJson(path, bytes);
    return {.text = readBytes(path, 0, bytes)};
}

std::vector<std::string> stringsOf(const json& document, const char* key) {
    std::vector<std::string> out;
    const auto it = document.find(key);
    if (it == document.end() || !it->is_array()) return out;
    for (const json& v : *it)
        if (v.is_string()) out.push_back(v.get<std::string>());
    return out;
}

// Whether some KHR_texture_transform under `v` carries a "texCoord".
bool transformSetsTexCoord(const json& v) {
    if (v.is_object()) {
        for (const auto& [key, value] : v.items()) {
            if (key == "KHR_texture_transform" && value.is_object() && value.contains("texCoord")) return true;
            if (transformSetsTexCoord(value)) return true;
        }
    } else if (v.is_array()) {
        for (const json& e : v)
            if (transformSetsTexCoord(e)) return true;
    }
    return false;
}

// Far deeper than any glTF (its own structure nests about 8 levels), low
// enough that the recursive parsers (nlohmann's here, rapidjson's in
// Assimp) cannot run out of stack on a file of nested brackets.
constexpr int kMaxNesting = 256;

// Whether arrays and objects nest deeper than kMaxNesting, outside strings.
bool nestedTooDeep(const std::string& text) {
    int depth = 0;
    bool inString = false, escaped = false;
    for (const char c : text) {
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxNesting) return true;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return false;
}

void refuseDeepNesting(const fs::path& path, const std::string& text) {
    if (nestedTooDeep(text))
        fail(path, "glTF JSON nested more than " + std::to_string(kMaxNesting) +
                       " levels deep (arrays and objects inside each other)");
}

// A number of a material's extension within [lo, hi], or the file is
// refused naming the field.
float extensionNumber(const fs::path& path, const json& value, const std::string& field, double lo, double hi) {
    const double v = value.is_number() ? value.get<double>() : std::numeric_limits<double>::quiet_NaN();
    if (!(v >= lo && v <= hi))
        fail(path, field + (hi < std::numeric_limits<float>::max()
                                ? " must be a number in [" + formatGeneral(lo) + ", " + formatGeneral(hi) + "]"
                                : " must be a finite number >= " + formatGeneral(lo)));
    return static_cast<float>(v);
}

// extensions.<name> of a material, or null.
const json* materialExtension(const json& material, const char* name) {
    if (!material.is_object()) return nullptr;
    const auto extensions = material.find("extensions");
    if (extensions == material.end() || !extensions->is_object()) return nullptr;
    const auto extension = extensions->find(name);
    return extension != extensions->end() && extension->is_object() ? &*extension : nullptr;
}

// What each material's KHR_materials_emissive_strength and
// KHR_materials_specular say, in the specification's ranges.
std::vector<GltfMaterialExtensions> materialExtensionsOf(const fs::path& path, const json& materials) {
    std::vector<GltfMaterialExtensions> out;
    if (!materials.is_array()) return out;
    constexpr double kFloatMax = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < materials.size(); ++i) {
        GltfMaterialExtensions e;
        const std::string at = "materials[" + std::to_string(i) + "].extensions.";
        if (const json* strength = materialExtension(materials[i], "KHR_materials_emissive_strength"))
            if (const auto v = strength->find("emissiveStrength"); v != strength->end())
                e.emissiveStrength =
                    extensionNumber(path, *v, at + "KHR_materials_emissive_strength.emissiveStrength", 0.0, kFloatMax);
        if (const json* specular = materialExtension(materials[i], "KHR_materials_specular")) {
            const std::string field = at + "KHR_materials_specular.";
            if (const auto v = specular->find("specularFactor"); v != specular->end())
                e.specularFactor = extensionNumber(path, *v, field + "specularFactor", 0.0, 1.0);
            if (const auto v = specular->find("specularColorFactor"); v != specular->end()) {
                if (!v->is_array() || v->size() != 3)
                    fail(path, field + "specularColorFactor must be an array of 3 numbers");
                e.specularColor = {extensionNumber(path, (*v)[0], field + "specularColorFactor[0]", 0.0, kFloatMax),
                                   extensionNumber(path, (*v)[1], field + "specularColorFactor[1]", 0.0, kFloatMax),
                                   extensionNumber(path, (*v)[2], field + "specularColorFactor[2]", 0.0, kFloatMax)};
            }
            e.specularTextures = specular->contains("specularTexture") || specular->contains("specularColorTexture");
        }
        out.push_back(e);
    }
    return out;
}

}  // namespace

GltfDocument readGltfDocument(const fs::path& path) {
    const GltfJsonText file = gltfJsonText(path);
    const std::string& text = file.text;
    const bool binary = file.layout.binary;
    GltfDocument document;
    if (file.version1Binary) {
        document.version = "1.0";
        return document;
    }

    refuseDeepNesting(path, text);
    json root;
    try {
        root = json::parse(text);
    } catch (const json::parse_error& e) {
        // nlohmann says "[json.exception.parse_error.101] parse error at line L, column C: what".
        std::string what = e.what();
        if (const std::size_t at = what.find(": "); at != std::string::npos) what = what.substr(at + 2);
        std::replace(what.begin(), what.end(), '\n', ' ');
        int line = 0, column = 0;
        if (!binary && e.byte > 0 && e.byte <= text.size()) {
            line = 1;
            std::size_t lineStart = 0;
            for (std::size_t i = 0; i + 1 < e.byte; ++i)
                if (text[i] == '\n') ++line, lineStart = i + 1;
            column = static_cast<int>(e.byte - lineStart);
        }
        fail(path, "not valid glTF JSON: " + what, line, column);
    } catch (const json::out_of_range& e) {
        // A number beyond a double (1e391): "[json.exception.out_of_range.406] number overflow parsing '1e391'".
        std::string what = e.what();
        if (const std::size_t at = what.find("] "); at != std::string::npos) what = what.substr(at + 2);
        fail(path, "not valid glTF JSON: " + what);
    }
    if (!root.is_object()) fail(path, "not a glTF file: its JSON is not an object");
    checkGltfLimits(path, root, file.layout);
    if (const auto asset = root.find("asset"); asset != root.end() && asset->is_object())
        if (const auto version = asset->find("version"); version != asset->end() && version->is_string())
            document.version = version->get<std::string>();
    document.extensionsUsed = stringsOf(root, "extensionsUsed");
    document.extensionsRequired = stringsOf(root, "extensionsRequired");
    if (const auto scenes = root.find("scenes"); scenes != root.end() && scenes->is_array())
        document.sceneCount = scenes->size();
    if (const auto scene = root.find("scene"); scene != root.end() && scene->is_number_unsigned())
        document.defaultScene = scene->get<std::size_t>();
    if (const auto cameras = root.find("cameras"); cameras != root.end() && cameras->is_array())
        for (const json& camera : *cameras)
            document.orthographicCameras.push_back(camera.is_object() &&
                                                   camera.value("type", json()) == "orthographic");
    if (const auto materials = root.find("materials"); materials != root.end()) {
        document.textureTransformSetsTexCoord = transformSetsTexCoord(*materials);
        document.materialExtensions = materialExtensionsOf(path, *materials);
    }
    return document;
}

}  // namespace raycache

namespace raycache {

void checkGltfBeforeAssimp(const fs::path& path) {
    const GltfJsonText file = gltfJsonText(path);
    refuseDeepNesting(path, file.text);
    const json root = json::parse(file.text, nullptr, /*allow_exceptions=*/false);
    // Not JSON, or not a glTF document: Assimp's glTF readers refuse it.
    if (root.is_discarded() || !root.is_object()) return;
    checkGltfLimits(path, root, file.layout);
}

}  // namespace raycache
