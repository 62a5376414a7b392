#include "scene/AssimpLogCapture.h"

#include <array>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Logger.hpp>
#include <string_view>

namespace raycache {
namespace {

// Messages that do not mean lost or altered geometry.
constexpr std::array<std::string_view, 3> kHarmless = {
    "unreferenced vertices",      // vertices no face uses: nothing is drawn from them
    "failed to locate material",  // OBJ material library: raycache takes materials from the scene file
    "material library not found",
};

bool harmless(std::string_view message) {
    for (std::string_view h : kHarmless)
        if (message.find(h) != std::string_view::npos) return true;
    return false;
}

// Owned by Assimp once installed (DefaultLogger::set deletes the previous one).
class Collector : public Assimp::Logger {
public:
    explicit Collector(std::vector<std::string>& out) : Assimp::Logger(Assimp::Logger::NORMAL), out_(out) {}
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
        std::string& s = out_.emplace_back(message);
        while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
        for (char& c : s)
            if (c == '\n' || c == '\r') c = ' ';
    }
    std::vector<std::string>& out_;
};

}  // namespace

AssimpLogCapture::AssimpLogCapture() {
    Assimp::DefaultLogger::set(new Collector(problems_));
}

AssimpLogCapture::~AssimpLogCapture() {
    Assimp::DefaultLogger::set(nullptr);
}

}  // namespace raycache
