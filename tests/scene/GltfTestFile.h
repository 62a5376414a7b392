#pragma once
// Small glTF 2.0 files written by tests: meshes go into one buffer embedded
// as a base64 data: URI, the rest of the document is plain JSON the test
// edits (nodes, materials, cameras, KHR_lights_punctual, extensions).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "scene/TriangleMesh.h"

namespace raycache {

inline std::string base64(const std::vector<unsigned char>& bytes) {
    static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t a = bytes[i];
        const std::uint32_t b = i + 1 < bytes.size() ? bytes[i + 1] : 0;
        const std::uint32_t c = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const std::uint32_t triple = a << 16 | b << 8 | c;
        out += kDigits[triple >> 18 & 63];
        out += kDigits[triple >> 12 & 63];
        out += i + 1 < bytes.size() ? kDigits[triple >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? kDigits[triple & 63] : '=';
    }
    return out;
}

inline std::vector<unsigned char> fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A unit quaternion [x, y, z, w] turning `degrees` about the unit `axis`, as glTF writes rotations.
inline nlohmann::json quaternion(float ax, float ay, float az, double degrees) {
    const double half = degrees * std::numbers::pi / 360.0;
    const double s = std::sin(half);
    return {ax * s, ay * s, az * s, std::cos(half)};
}

// A UV sphere of `radius` about the origin, with normals and texture coordinates.
inline TriangleMesh uvSphere(float radius, int rings = 16, int segments = 32) {
    TriangleMesh m;
    for (int r = 0; r <= rings; ++r) {
        const float theta = std::numbers::pi_v<float> * static_cast<float>(r) / static_cast<float>(rings);
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.0f * std::numbers::pi_v<float> * static_cast<float>(s) / static_cast<float>(segments);
            const Vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
            m.positions.push_back(n * radius);
            m.normals.push_back(n);
            m.uvs.push_back({static_cast<float>(s) / static_cast<float>(segments),
                             1.0f - static_cast<float>(r) / static_cast<float>(rings)});
        }
    }
    const auto at = [&](int r, int s) { return static_cast<std::uint32_t>(r * (segments + 1) + s); };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            if (r > 0) m.triangles.push_back({at(r, s), at(r + 1, s), at(r, s + 1)});
            if (r + 1 < rings) m.triangles.push_back({at(r, s + 1), at(r + 1, s), at(r + 1, s + 1)});
        }
    return m;
}

class GltfTestFile {
public:
    GltfTestFile() {
        document_ = {{"asset", {{"version", "2.0"}}},
                     {"scene", 0},
                     {"scenes", {{{"nodes", nlohmann::json::array()}}}},
                     {"nodes", nlohmann::json::array()},
                     {"meshes", nlohmann::json::array()}};
    }

    nlohmann::json& document() { return document_; }

    // The mesh as one primitive (positions, normals and TEXCOORD_0 when it
    // has them), with `material` unless it is negative. Texture coordinates
    // are raycache's (v up); glTF's v runs down, so they are written as
    // (u, 1 - v), which Assimp turns back. Returns the mesh's index.
    int addMesh(const TriangleMesh& mesh, int material = -1) {
        nlohmann::json attributes;
        std::vector<float> positions;
        for (const Vec3& p : mesh.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
        attributes["POSITION"] = addFloats(positions, "VEC3", mesh.positions.size(), true);
        if (!mesh.normals.empty()) {
            std::vector<float> normals;
            for (const Vec3& n : mesh.normals) normals.insert(normals.end(), {n.x, n.y, n.z});
            attributes["NORMAL"] = addFloats(normals, "VEC3", mesh.normals.size(), false);
        }
        if (!mesh.uvs.empty()) {
            std::vector<float> uvs;
            for (const auto& uv : mesh.uvs) uvs.insert(uvs.end(), {uv[0], 1.0f - uv[1]});
            attributes["TEXCOORD_0"] = addFloats(uvs, "VEC2", mesh.uvs.size(), false);
        }
        std::vector<std::uint32_t> indices;
        for (const auto& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
        const int indexAccessor = addView(indices.data(), indices.size() * 4, 34963, 5125, "SCALAR", indices.size());
        nlohmann::json primitive = {{"attributes", attributes}, {"indices", indexAccessor}};
        if (material >= 0) primitive["material"] = material;
        document_["meshes"].push_back({{"primitives", {primitive}}});
        return static_cast<int>(document_["meshes"].size()) - 1;
    }

    int addMaterial(const nlohmann::json& material) { return append("materials", material); }
    // A root node of the default scene.
    int addNode(const nlohmann::json& node) {
        const int index = append("nodes", node);
        document_["scenes"][0]["nodes"].push_back(index);
        return index;
    }
    int addCamera(const nlohmann::json& camera) { return append("cameras", camera); }
    int addLight(const nlohmann::json& light) {
        useExtension("KHR_lights_punctual");
        nlohmann::json& lights = document_["extensions"]["KHR_lights_punctual"]["lights"];
        lights.push_back(light);
        return static_cast<int>(lights.size()) - 1;
    }
    // An image as a data: URI, and a texture of it with the default sampler.
    int addTexture(const std::vector<unsigned char>& png) {
        const int image = append("images", {{"uri", "data:image/png;base64," + base64(png)}});
        return append("textures", {{"source", image}});
    }
    void useExtension(const std::string& name) {
        nlohmann::json& used = document_["extensionsUsed"];
        for (const auto& e : used)
            if (e == name) return;
        used.push_back(name);
    }

    void write(const std::filesystem::path& path) const {
        nlohmann::json document = document_;
        document["buffers"] = {
            {{"byteLength", buffer_.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer_)}}};
        std::ofstream out(path, std::ios::binary);
        out << document.dump(1);
    }

private:
    int append(const char* key, const nlohmann::json& value) {
        document_[key].push_back(value);
        return static_cast<int>(document_[key].size()) - 1;
    }

    int addFloats(const std::vector<float>& values, const char* type, std::size_t count, bool bounds) {
        const int accessor = addView(values.data(), values.size() * 4, 34962, 5126, type, count);
        if (bounds) {
            // POSITION accessors must carry their bounds.
            std::vector<float> lo(3, INFINITY), hi(3, -INFINITY);
            for (std::size_t i = 0; i < values.size(); ++i) {
                lo[i % 3] = std::min(lo[i % 3], values[i]);
                hi[i % 3] = std::max(hi[i % 3], values[i]);
            }
            document_["accessors"][accessor]["min"] = lo;
            document_["accessors"][accessor]["max"] = hi;
        }
        return accessor;
    }

    int addView(const void* data, std::size_t bytes, int target, int componentType, const char* type,
                std::size_t count) {
        while (buffer_.size() % 4 != 0) buffer_.push_back(0);
        const std::size_t offset = buffer_.size();
        buffer_.resize(offset + bytes);
        std::memcpy(buffer_.data() + offset, data, bytes);
        const int view =
            append("bufferViews", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
        return append("accessors",
                      {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    }

    nlohmann::json document_;
    std::vector<unsigned char> buffer_;
};

}  // namespace raycache
