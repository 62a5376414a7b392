#include "render/TileAssignment.h"

#include <algorithm>
#include <numeric>

namespace raycache {

const char* tileBalanceName(TileBalance balance) {
    switch (balance) {
        case TileBalance::Static: return "static";
        case TileBalance::Dynamic: return "dynamic";
        case TileBalance::Claim: return "claim";
    }
    return "?";
}

std::vector<int> interleavedTileOwners(int tileCount, int processes) {
    std::vector<int> owners(static_cast<std::size_t>(std::max(0, tileCount)));
    for (std::size_t i = 0; i < owners.size(); ++i) owners[i] = static_cast<int>(i % static_cast<std::size_t>(processes));
    return owners;
}

std::vector<int> balancedTileOwners(std::span<const double> tileCosts, int processes) {
    std::vector<std::size_t> order(tileCosts.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return tileCosts[a] > tileCosts[b]; });
    std::vector<double> load(static_cast<std::size_t>(processes), 0.0);
    std::vector<int> owners(tileCosts.size(), 0);
    for (const std::size_t tile : order) {
        const auto lightest = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
        owners[tile] = static_cast<int>(lightest);
        // A negative or NaN cost (a broken clock) must not starve a process.
        load[lightest] += tileCosts[tile] > 0.0 ? tileCosts[tile] : 0.0;
    }
    return owners;
}

}  // namespace raycache
