#include "scene/GltfNodeGraph.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "scene/GltfLimits.h"

namespace raycache {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

// A JSON pointer token (RFC 6901): ~ as ~0, / as ~1.
std::string pointerToken(const std::string& key) {
    std::string out;
    for (const char c : key) {
        if (c == '~')
            out += "~0";
        else if (c == '/')
            out += "~1";
        else
            out += c;
    }
    return out;
}

// The nodes of either glTF version, numbered 0..n-1: glTF 2.0's array
// indices, or glTF 1.0's ids in the object's (sorted) order.
class NodeGraph {
public:
    NodeGraph(const fs::path& path, const json& root) : path_(path) {
        const auto nodes = root.find("nodes");
        if (nodes == root.end()) return;
        if (nodes->is_array()) {
            for (const json& node : *nodes) nodes_.push_back(&node);
        } else if (nodes->is_object()) {
            byId_ = true;
            for (const auto& [id, node] : nodes->items()) {
                indexOfId_.emplace(id, nodes_.size());
                ids_.push_back(id);
                nodes_.push_back(&node);
            }
        }
        parent_.assign(nodes_.size(), kNone);
        slotInParent_.assign(nodes_.size(), 0);
    }

    void check(const json& root) {
        linkChildren();
        refuseCycles();
        refuseDepth();
        checkScenes(root);
    }

private:
    [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
        throw InputError(InputLocation{.file = path_.string(), .jsonPath = pointer}, what);
    }

    std::string pointerOf(std::size_t node) const {
        return "/nodes/" + (byId_ ? pointerToken(ids_[node]) : std::to_string(node));
    }
    std::string label(std::size_t node) const {
        return byId_ ? "node " + json(ids_[node]).dump(-1, ' ', false, json::error_handler_t::replace)
                     : "node " + std::to_string(node);
    }
    std::string slotPointer(std::size_t child) const {
        return pointerOf(parent_[child]) + "/children/" + std::to_string(slotInParent_[child]);
    }

    // The node an entry of "children" or of a scene's "nodes" names.
    std::size_t resolve(const json& entry, const std::string& pointer) const {
        if (byId_) {
            if (!entry.is_string()) fail(pointer, "not a node id (a string)");
            const auto it = indexOfId_.find(entry.get<std::string>());
            if (it == indexOfId_.end()) fail(pointer, entry.dump() + " names no node");
            return it->second;
        }
        if (!entry.is_number_integer() || (!entry.is_number_unsigned() && entry.get<std::int64_t>() < 0))
            fail(pointer, "not a node index (an integer >= 0)");
        const auto index = entry.get<std::uint64_t>();
        if (index >= nodes_.size())
            fail(pointer, "node " + std::to_string(index) + " does not exist (the file has " +
                              std::to_string(nodes_.size()) + " nodes)");
        return static_cast<std::size_t>(index);
    }

    void linkChildren() {
        for (std::size_t n = 0; n < nodes_.size(); ++n) {
            if (!nodes_[n]->is_object()) continue;  // Assimp's reader refuses it
            const auto children = nodes_[n]->find("children");
            if (children == nodes_[n]->end()) continue;
            if (!children->is_array()) fail(pointerOf(n) + "/children", "not an array of nodes");
            for (std::size_t k = 0; k < children->size(); ++k) {
                const std::string pointer = pointerOf(n) + "/children/" + std::to_string(k);
                const std::size_t child = resolve((*children)[k], pointer);
                if (child == n) fail(pointer, label(n) + " lists itself as its child (a cycle)");
                if (parent_[child] != kNone)
                    fail(pointer, label(child) + " is already a child of " + label(parent_[child]) +
                                      " (a glTF node has at most one parent)");
                parent_[child] = n;
                slotInParent_[child] = k;
            }
        }
    }

    // Every node has at most one parent now, so a node that no walk down
    // from the parentless nodes reaches lies on a cycle or below one.
    void refuseCycles() {
        depth_.assign(nodes_.size(), 0);
        std::vector<std::vector<std::size_t>> children(nodes_.size());
        for (std::size_t n = 0; n < nodes_.size(); ++n)
            if (parent_[n] != kNone) children[parent_[n]].push_back(n);
        std::vector<std::size_t> stack;
        for (std::size_t n = 0; n < nodes_.size(); ++n)
            if (parent_[n] == kNone) {
                depth_[n] = 1;
                stack.push_back(n);
            }
        while (!stack.empty()) {
            const std::size_t n = stack.back();
            stack.pop_back();
            for (const std::size_t child : children[n]) {
                depth_[child] = depth_[n] + 1;
                stack.push_back(child);
            }
        }
        for (std::size_t n = 0; n < nodes_.size(); ++n)
            if (depth_[n] == 0) failCycleAbove(n);
    }

    // Goes up from `start` (unreached, so every ancestor has a parent) until
    // a node repeats: that node lies on the cycle, which is then named.
    [[noreturn]] void failCycleAbove(std::size_t start) const {
        std::vector<bool> seen(nodes_.size(), false);
        std::size_t onCycle = start;
        while (!seen[onCycle]) {
            seen[onCycle] = true;
            onCycle = parent_[onCycle];
        }
        std::vector<std::size_t> upward{onCycle};
        for (std::size_t n = parent_[onCycle]; n != onCycle; n = parent_[n]) upward.push_back(n);
        // Parent to child from that node round to it again; the link out of it is named.
        std::vector<std::size_t> down{onCycle};
        down.insert(down.end(), upward.rbegin(), upward.rend());
        constexpr std::size_t kNamed = 6;
        std::string cycle;
        for (std::size_t i = 0; i < down.size(); ++i) {
            if (i > 0) cycle += " -> ";
            if (i == kNamed && down.size() > kNamed + 2) {
                cycle += "... (" + std::to_string(upward.size()) + " nodes) -> ";
                i = down.size() - 1;
            }
            cycle += label(down[i]);
        }
        fail(slotPointer(upward.back()), "the node graph has a cycle: " + cycle);
    }

    void refuseDepth() const {
        std::size_t deepest = 0;
        for (std::size_t n = 0; n < nodes_.size(); ++n)
            if (depth_[n] > depth_[deepest]) deepest = n;
        if (nodes_.empty() || depth_[deepest] <= kMaxGltfNodeDepth) return;
        // The node at the limit's level whose children go past it.
        std::size_t last = deepest;
        while (depth_[last] > kMaxGltfNodeDepth) last = parent_[last];
        fail(pointerOf(last) + "/children", "the node graph is " + std::to_string(depth_[deepest]) +
                                                " levels deep, more than the limit of " +
                                                std::to_string(kMaxGltfNodeDepth));
    }

    void checkScenes(const json& root) const {
        const auto scenes = root.find("scenes");
        if (scenes == root.end() || !(scenes->is_array() || scenes->is_object())) return;
        for (const auto& [key, scene] : scenes->items()) {
            const std::string scenePointer = "/scenes/" + pointerToken(key);
            if (!scene.is_object()) continue;
            const auto roots = scene.find("nodes");
            if (roots == scene.end() || !roots->is_array()) continue;
            std::map<std::size_t, std::size_t> listedAt;
            for (std::size_t k = 0; k < roots->size(); ++k) {
                const std::string pointer = scenePointer + "/nodes/" + std::to_string(k);
                const std::size_t node = resolve((*roots)[k], pointer);
                if (parent_[node] != kNone)
                    fail(pointer, label(node) + " is a child of " + label(parent_[node]) +
                                      ", not a root node (a scene lists root nodes only)");
                if (const auto [at, fresh] = listedAt.emplace(node, k); !fresh)
                    fail(pointer, label(node) + " is listed twice (also at " + scenePointer + "/nodes/" +
                                      std::to_string(at->second) + ")");
            }
        }
    }

    const fs::path& path_;
    bool byId_ = false;
    std::vector<const json*> nodes_;
    std::vector<std::string> ids_;
    std::map<std::string, std::size_t> indexOfId_;
    std::vector<std::size_t> parent_;        // kNone for a root
    std::vector<std::size_t> slotInParent_;  // its position in the parent's "children"
    std::vector<std::size_t> depth_;         // a root is 1; 0 until reached
};

}  // namespace

void checkGltfNodeGraph(const fs::path& path, const json& root) {
    NodeGraph(path, root).check(root);
}

}  // namespace raycache
