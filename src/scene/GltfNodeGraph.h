#pragma once
// A glTF file's node graph checked as the specification requires (its nodes
// form disjoint trees: every child index names a node, no node has two
// parents, there are no cycles, a scene lists root nodes only, once each)
// and no deeper than kMaxGltfNodeDepth (GltfLimits.h). Assimp's readers
// recurse down this graph and copy a node once per parent, so each of these
// is refused before Assimp reads the file. Walked without recursion, in time
// and memory linear in the number of nodes.
#include <filesystem>
#include <nlohmann/json_fwd.hpp>

namespace raycache {

// Checks root["nodes"] and root["scenes"]: glTF 2.0's arrays and indices, or
// glTF 1.0's objects and ids. Throws InputError naming the file and the JSON
// pointer of the entry at fault (e.g. /nodes/17/children), one line.
void checkGltfNodeGraph(const std::filesystem::path& path, const nlohmann::json& root);

}  // namespace raycache
