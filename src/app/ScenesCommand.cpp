#include "app/ScenesCommand.h"

#include <ostream>
#include <string>

#include "scene/BuiltinScenes.h"
#include "scene/RealMeshScenes.h"

namespace raycache {

namespace {

void sceneLine(std::ostream& out, const std::string& name, const std::string& description) {
    out << name;
    for (std::size_t i = name.size(); i < 16; ++i) out << ' ';
    out << description << '\n';
}

}  // namespace

void runScenesCommand(std::ostream& out, const MeshSearchPath& meshes) {
    for (const BuiltinSceneInfo& info : builtinScenes()) sceneLine(out, info.name, info.description);
    for (const RealMeshSceneInfo& info : realMeshScenes()) {
        const std::string missing = missingMeshFiles(info, meshes);
        sceneLine(out, info.name, missing.empty() ? info.description
                                                  : info.description + " (unavailable: " + missing + ")");
    }
}

void runScenesCommand(std::ostream& out) { runScenesCommand(out, meshSearchPathFromEnvironment()); }

}  // namespace raycache
