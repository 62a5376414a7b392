#include "trace/EmbreeDeviceConfig.h"

#include "core/LaneLevels.h"

#include <cstdlib>
#include <optional>

namespace raycache {

namespace {

struct InstructionBound {
    LaneLevel level;
    const char* setBy;  // the environment variable that set it
};

// RAYCACHE_EMBREE_ISA first, then a narrowed lane level, else no bound.
std::optional<InstructionBound> instructionBound() {
    if (const std::optional<LaneLevel> pinned = parseLaneLevel(std::getenv("RAYCACHE_EMBREE_ISA")))
        return InstructionBound{*pinned, "RAYCACHE_EMBREE_ISA"};
    if (const std::optional<LaneLevel> narrowed = narrowedLaneLevel())
        return InstructionBound{*narrowed, "RAYCACHE_LANES"};
    return std::nullopt;
}

// Embree's name for the instructions of a lane level.
const char* embreeIsaName(LaneLevel level) {
    switch (level) {
    case LaneLevel::Avx512: return "avx512";
    case LaneLevel::Avx2: return "avx2";
    case LaneLevel::Baseline: return "sse2";
    }
    return "sse2";
}

}  // namespace

std::string embreeDeviceConfig(int buildThreads) {
    std::string config;
    const auto append = [&config](const std::string& entry) { config += (config.empty() ? "" : ",") + entry; };
    if (buildThreads > 0) append("threads=" + std::to_string(buildThreads));
    if (const std::optional<InstructionBound> bound = instructionBound())
        append(std::string("max_isa=") + embreeIsaName(bound->level));
    return config;
}

std::string embreeInstructionSet() {
    const std::optional<InstructionBound> bound = instructionBound();
    if (!bound) return "the processor's widest";
    return std::string("at most ") + laneLevelName(bound->level) + " (" + bound->setBy + ")";
}

}  // namespace raycache
