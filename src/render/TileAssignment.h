#pragma once
// Which process renders which tile of a frame, in a job of several processes
// (core/ProcessGroup.h). Pure functions of their inputs: the image never
// depends on the assignment (cache stores are merged by tile key), only the
// time a frame takes does.
#include <array>
#include <span>
#include <vector>

namespace raycache {

// Static: tile i to process i mod n (neighbouring tiles, which cost about
// the same, land on different processes). Dynamic: from the second frame
// on, tiles are dealt by the previous frame's measured cost of each tile.
// Claim: nothing is dealt; every worker thread of every process takes the
// next tile from a counter on process 0 (ProcessGroup::drawTickets) when it
// is free, so the processes finish together whatever the tiles cost.
enum class TileBalance { Static, Dynamic, Claim };
// Every balance, in the order messages and help texts list them.
inline constexpr std::array kTileBalances{TileBalance::Static, TileBalance::Dynamic, TileBalance::Claim};

const char* tileBalanceName(TileBalance balance);

// owners[i] = i mod processes.
std::vector<int> interleavedTileOwners(int tileCount, int processes);

// Longest-processing-time first: tiles in decreasing cost (ties by index)
// each go to the process with the least cost so far (ties: lowest rank).
// Deterministic; at most 4/3 of the best possible largest load.
std::vector<int> balancedTileOwners(std::span<const double> tileCosts, int processes);

}  // namespace raycache
