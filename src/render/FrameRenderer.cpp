#include "render/FrameRenderer.h"

#include <chrono>
#include <vector>

#include "render/CacheFrame.h"
#include "render/CameraRays.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// This frame's owner of every tile, decided by process 0 and sent to all,
// so that every process agrees even if their clocks or builds differ.
std::vector<int> agreeTileOwners(const ProcessGroup& group, TileBalance balance, int tiles,
                                 const std::vector<double>& lastCosts, const char*& used, std::uint64_t& bytes) {
    const bool dynamic = balance == TileBalance::Dynamic && static_cast<int>(lastCosts.size()) == tiles;
    std::vector<int> owners;
    Bytes message;
    if (group.isRoot()) {
        owners = dynamic ? balancedTileOwners(lastCosts, group.size()) : interleavedTileOwners(tiles, group.size());
        appendBytes(message, static_cast<std::uint8_t>(dynamic));
        appendBytes(message, std::span<const int>(owners));
    }
    group.broadcastFromRoot(message);
    bytes += message.size() * static_cast<std::uint64_t>(group.size() - 1);
    ByteReader reader(message);
    used = reader.read<std::uint8_t>() ? "dynamic tiles" : "static tiles";
    owners.resize(static_cast<std::size_t>(tiles));
    reader.readInto(std::span<int>(owners));
    return owners;
}

}  // namespace

FrameRenderer::FrameRenderer(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                             const Parallel& parallel, RayCache* cache, const ProcessGroup* group)
    : settings_(settings), parallel_(parallel), cache_(cache && !cache->empty() ? cache : nullptr),
      group_(group && group->size() > 1 ? group : nullptr), kernel_(scene, tracer, settings, cache_) {}

FrameStats FrameRenderer::render(const Camera& camera, Image& film) const {
    if (film.width() != settings_.width || film.height() != settings_.height)
        film = Image(settings_.width, settings_.height);
    const CameraRays cameraRays(camera, settings_.width, settings_.height);
    if (group_) return renderDistributed(cameraRays, film);
    std::vector<TileScratch>& scratch = scratch_;
    scratch.resize(static_cast<std::size_t>(parallel_.threadCount()));
    for (TileScratch& s : scratch) s.beginFrame();
    CacheFrame cacheFrame(cache_, parallel_.threadCount());
    parallel_.forEachTile(settings_.width, settings_.height, settings_.tileSize, [&](const TileRange& tile, int worker) {
        kernel_.renderCameraTile(cameraRays, tile, tileKey(tile, settings_.width, settings_.tileSize),
                                 scratch[static_cast<std::size_t>(worker)], cacheFrame.worker(worker), film);
    });

    FrameStats stats;
    StageTimes stages;
    for (const TileScratch& s : scratch) {
        stats.rays += s.counts;
        stages += s.stages;
    }
    const auto start = Clock::now();
    stats.cache = cacheFrame.finish(kernel_, parallel_, stats.rays);
    if (settings_.stageTimes) {
        stages.cacheFrameEnd = millisecondsSince(start);
        stats.stages = stages;
    }
    return stats;
}

// One frame over several processes: the same tile kernel on this process's
// tiles, then (collectives, in this order on every process) the cache
// exchange inside CacheFrame::finish and one gather to process 0 of the
// tiles' pixels, costs and ray counts.
FrameStats FrameRenderer::renderDistributed(const CameraRays& cameraRays, Image& film) const {
    const ProcessGroup& group = *group_;
    const int width = settings_.width, height = settings_.height, tileSize = settings_.tileSize;
    const int tiles = tileCount(width, height, tileSize);
    ClusterStats cluster;
    cluster.processes = group.size();
    const std::vector<int> owners =
        agreeTileOwners(group, settings_.tileBalance, tiles, lastTileCosts_, cluster.assignment, cluster.controlBytes);
    std::vector<int> mine;
    for (int t = 0; t < tiles; ++t)
        if (owners[static_cast<std::size_t>(t)] == group.rank()) mine.push_back(t);

    std::vector<TileScratch>& scratch = scratch_;
    scratch.resize(static_cast<std::size_t>(parallel_.threadCount()));
    for (TileScratch& s : scratch) s.beginFrame();
    std::vector<double> costs(mine.size());
    CacheFrame cacheFrame(cache_, parallel_.threadCount(), &group, &storeExchange_);
    parallel_.forEachIndex(static_cast<int>(mine.size()), [&](int k, int worker) {
        const auto tileStart = Clock::now();
        const TileRange tile = tileAt(mine[static_cast<std::size_t>(k)], width, height, tileSize);
        kernel_.renderCameraTile(cameraRays, tile, tileKey(tile, width, tileSize),
                                 scratch[static_cast<std::size_t>(worker)], cacheFrame.worker(worker), film);
        costs[static_cast<std::size_t>(k)] = millisecondsSince(tileStart);
    });

    FrameStats stats;
    StageTimes stages;
    RayCounts tileRays;
    for (const TileScratch& s : scratch) {
        tileRays += s.counts;
        stages += s.stages;
    }
    const auto start = Clock::now();
    // This process's share of the pre-fill counts with its tiles' rays.
    stats.cache = cacheFrame.finish(kernel_, parallel_, tileRays);
    cluster.storeBytes = cacheFrame.exchangedBytes();
    cluster.prefillBytes = cacheFrame.prefillBytes();
    stages.cacheFrameEnd = millisecondsSince(start);

    // Every process's part, in its tiles' increasing index order.
    Bytes& part = imagePart_;
    part.clear();
    std::size_t pixels = 0;
    for (const int t : mine) {
        const TileRange tile = tileAt(t, width, height, tileSize);
        pixels += static_cast<std::size_t>(tile.x1 - tile.x0) * static_cast<std::size_t>(tile.y1 - tile.y0);
    }
    part.reserve(sizeof tileRays + sizeof stages + costs.size() * sizeof(double) + pixels * sizeof(Rgb));
    appendBytes(part, tileRays);
    appendBytes(part, stages);
    appendBytes(part, std::span<const double>(costs));
    for (const int t : mine) {
        const TileRange tile = tileAt(t, width, height, tileSize);
        for (int y = tile.y0; y < tile.y1; ++y)
            appendBytes(part, std::span<const Rgb>(&film.at(tile.x0, y), static_cast<std::size_t>(tile.x1 - tile.x0)));
    }
    GatheredBytes& parts = imageParts_;
    group.gatherToRoot(part, parts);
    if (!group.isRoot()) {
        stats.cluster = cluster;
        return stats;
    }

    cluster.tilesPerProcess.assign(static_cast<std::size_t>(group.size()), 0);
    for (const int owner : owners) ++cluster.tilesPerProcess[static_cast<std::size_t>(owner)];
    lastTileCosts_.assign(static_cast<std::size_t>(tiles), 0.0);
    StageTimes allStages;
    std::vector<double> busy(parts.count(), 0.0);
    for (std::size_t r = 0; r < parts.count(); ++r) {
        ByteReader reader(parts.of(r));
        stats.rays += reader.read<RayCounts>();
        allStages += reader.read<StageTimes>();
        std::vector<double> theirCosts(static_cast<std::size_t>(cluster.tilesPerProcess[r]));
        reader.readInto(std::span<double>(theirCosts));
        std::size_t k = 0;
        for (int t = 0; t < tiles; ++t) {
            if (owners[static_cast<std::size_t>(t)] != static_cast<int>(r)) continue;
            lastTileCosts_[static_cast<std::size_t>(t)] = theirCosts[k];
            busy[r] += theirCosts[k++];
            if (static_cast<int>(r) == group.rank()) continue;  // already in the film
            const TileRange tile = tileAt(t, width, height, tileSize);
            for (int y = tile.y0; y < tile.y1; ++y)
                reader.readInto(std::span<Rgb>(&film.at(tile.x0, y), static_cast<std::size_t>(tile.x1 - tile.x0)));
        }
        if (static_cast<int>(r) != group.rank()) {
            const std::size_t control = sizeof(RayCounts) + sizeof(StageTimes) + theirCosts.size() * sizeof(double);
            cluster.controlBytes += control;
            cluster.imageBytes += parts.of(r).size() - control;
        }
    }
    double mean = 0.0, most = 0.0;
    for (const double b : busy) {
        mean += b / static_cast<double>(busy.size());
        most = std::max(most, b);
    }
    cluster.imbalance = mean > 0.0 ? most / mean : 1.0;
    if (settings_.stageTimes) {
        allStages.cacheFrameEnd = stages.cacheFrameEnd;  // wall time: this process's
        stats.stages = allStages;
    }
    stats.cluster = cluster;
    return stats;
}

}  // namespace raycache
