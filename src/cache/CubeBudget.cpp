#include "cache/CubeBudget.h"

#include <algorithm>
#include <queue>
#include <sstream>
#include <tuple>

#include "cache/CoarseLevels.h"
#include "cache/RayTreeBounds.h"
#include "core/Errors.h"

namespace raycache {

namespace {

std::size_t bitWords(std::size_t texels) { return (texels + 63) / 64 * sizeof(std::uint64_t); }

std::string mebibytes(std::size_t bytes) {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(1);
    if (bytes < 1024 * 1024) out << static_cast<double>(bytes) / 1024.0 << " KiB";
    else out << static_cast<double>(bytes) / (1024.0 * 1024.0) << " MiB";
    return out.str();
}

}  // namespace

std::size_t cubeBytes(bool depth, int resolution, int levels, bool tracksDependencies, bool viewSized) {
    const auto texels = 6u * static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution);
    std::size_t bytes = texels * sizeof(std::uint32_t) * (depth ? 2u : 1u) + bitWords(texels);
    if (viewSized && !depth) bytes += texels;  // CachingCube's inherited levels
    if (!depth && levels > 1) {
        // Levels as CoarseLevels makes them: halving down to kMinSize.
        for (int k = 1; k < std::min(levels, CoarseLevels::kMaxLevels); ++k) {
            const int size = (resolution + (1 << k) - 1) >> k;
            if (size < CoarseLevels::kMinSize) break;
            const auto coarse = 6u * static_cast<std::size_t>(size) * static_cast<std::size_t>(size);
            bytes += coarse * (sizeof(std::uint32_t) + sizeof(SeenPoint)) + bitWords(coarse);
        }
    }
    if (tracksDependencies) {
        bytes += bitWords(texels);  // dropped-texel bits
        if (!depth) {
            const auto blocks = static_cast<std::size_t>((resolution + 7) / 8);
            bytes += 6u * blocks * blocks * sizeof(RayTreeBounds);
        }
    }
    return bytes;
}

CubeBudgetPlan planCubeBudget(std::span<const CubeRequest> cubes, std::optional<std::size_t> budget, int levels,
                              bool tracksDependencies, int minResolution) {
    CubeBudgetPlan plan;
    std::vector<std::size_t> bytes(cubes.size());
    std::size_t smallest = 0;
    for (std::size_t i = 0; i < cubes.size(); ++i) {
        plan.resolutions.push_back(cubes[i].resolution);
        bytes[i] = cubeBytes(cubes[i].depth, cubes[i].resolution, levels, tracksDependencies, cubes[i].viewSized);
        plan.askedBytes += bytes[i];
        smallest += cubeBytes(cubes[i].depth, std::min(cubes[i].resolution, minResolution), levels, tracksDependencies,
                              cubes[i].viewSized);
    }
    plan.bytes = plan.askedBytes;
    if (!budget || plan.bytes <= *budget) return plan;
    if (smallest > *budget)
        throw InputError("the caching cubes of " + std::to_string(cubes.size()) + " objects need " + mebibytes(smallest) +
                         " even at " + std::to_string(minResolution) + "² faces, more than the cache budget of " +
                         mebibytes(*budget) + ": raise --cache-budget or cache fewer objects");
    // Largest texels-per-size first; ties: more bytes, then the earlier cube.
    using Key = std::tuple<float, std::size_t, long>;
    const auto keyOf = [&](std::size_t i) {
        return Key{static_cast<float>(plan.resolutions[i]) / cubes[i].size, bytes[i], -static_cast<long>(i)};
    };
    std::priority_queue<Key> queue;
    for (std::size_t i = 0; i < cubes.size(); ++i)
        if (plan.resolutions[i] > minResolution) queue.push(keyOf(i));
    while (plan.bytes > *budget && !queue.empty()) {
        const auto i = static_cast<std::size_t>(-std::get<2>(queue.top()));
        queue.pop();
        plan.resolutions[i] = std::max(minResolution, plan.resolutions[i] / 2);
        const std::size_t now = cubeBytes(cubes[i].depth, plan.resolutions[i], levels, tracksDependencies, cubes[i].viewSized);
        plan.bytes -= bytes[i] - now;
        bytes[i] = now;
        if (plan.resolutions[i] > minResolution) queue.push(keyOf(i));
    }
    int lowest = 0, highest = 0;
    for (std::size_t i = 0; i < cubes.size(); ++i) {
        if (plan.resolutions[i] == cubes[i].resolution) continue;
        ++plan.lowered;
        lowest = lowest == 0 ? plan.resolutions[i] : std::min(lowest, plan.resolutions[i]);
        highest = std::max(highest, plan.resolutions[i]);
    }
    std::ostringstream note;
    note << "cache budget " << mebibytes(*budget) << ": the cubes would take " << mebibytes(plan.askedBytes)
         << "; lowered " << plan.lowered << " of " << cubes.size() << " cubes to " << lowest << "²";
    if (highest != lowest) note << "–" << highest << "²";
    note << " faces (smallest objects' first), now " << mebibytes(plan.bytes);
    plan.note = note.str();
    return plan;
}

}  // namespace raycache
