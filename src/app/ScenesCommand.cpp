#include "app/ScenesCommand.h"

#include <ostream>

#include "scene/BuiltinScenes.h"

namespace raycache {

void runScenesCommand(std::ostream& out) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        out << info.name;
        for (std::size_t i = info.name.size(); i < 16; ++i) out << ' ';
        out << info.description << '\n';
    }
}

}  // namespace raycache
