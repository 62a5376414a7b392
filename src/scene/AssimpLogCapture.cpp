#include "scene/AssimpLogCapture.h"

#include <algorithm>
#include <array>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Logger.hpp>
#include <string_view>

namespace raycache {
namespace {

// Messages that do not mean lost or altered geometry.
constexpr std::array<std::string_view, 7> kHarmless = {
    "unreferenced vertices",      // vertices no face uses: nothing is drawn from them
    "failed to locate material",  // OBJ material library: raycache takes materials from the scene file
    "material library not found",
    // After a missing material file, the OBJ reader tries <name>.mtl; the
    // note names the file the OBJ asked for.
    "Unable to locate fallback material file",
    // OBJ `usemtl` before any object: Assimp starts a default object, and
    // every face still arrives (Assimp's testmixed.obj keeps its 12 triangles).
    "No object detected to attach a new mesh instance",
    // Three texture coordinates declared, two used: raycache reads two anyway.
    "UVs are declared to be 3D but they're obviously not",
    // Cameras in a mesh file are not read (Khronos' Cameras.gltf has fov 0).
    "is not a valid value for aiCamera::",
};

// Assimp's OBJ reader says "OBJ: Unable to locate material file <name>".
constexpr std::string_view kMissingMaterialFile = "Unable to locate material file ";

bool harmless(std::string_view message) {
    for (std::string_view h : kHarmless)
        if (message.find(h) != std::string_view::npos) return true;
    return false;
}

// Owned by Assimp once installed (DefaultLogger::set deletes the previous one).
class Collector : public Assimp::Logger {
public:
    Collector(std::vector<std::string>& out, std::vector<std::string>& missingMaterialFiles)
        : Assimp::Logger(Assimp::Logger::NORMAL), out_(out), missingMaterialFiles_(missingMaterialFiles) {}
    bool attachStream(Assimp::LogStream*, unsigned) override { return false; }
    bool detachStream(Assimp::LogStream*, unsigned) override { return false; }

protected:
    void OnDebug(const char*) override {}
    void OnVerboseDebug(const char*) override {}
    void OnInfo(const char*) override {}
    void OnWarn(const char* message) override { keep(message); }
    void OnError(const char* message) override { keep(message); }

private:
    void keep(std::string_view message) {
        if (harmless(message)) return;
        std::string s(message);
        while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
        for (char& c : s)
            if (c == '\n' || c == '\r') c = ' ';
        if (const std::size_t at = s.find(kMissingMaterialFile); at != std::string::npos) {
            const std::string name = s.substr(at + kMissingMaterialFile.size());
            if (std::find(missingMaterialFiles_.begin(), missingMaterialFiles_.end(), name) ==
                missingMaterialFiles_.end())
                missingMaterialFiles_.push_back(name);
            return;
        }
        out_.push_back(std::move(s));
    }
    std::vector<std::string>& out_;
    std::vector<std::string>& missingMaterialFiles_;
};

}  // namespace

AssimpLogCapture::AssimpLogCapture() {
    Assimp::DefaultLogger::set(new Collector(problems_, missingMaterialFiles_));
}

AssimpLogCapture::~AssimpLogCapture() {
    Assimp::DefaultLogger::set(nullptr);
}

}  // namespace raycache
