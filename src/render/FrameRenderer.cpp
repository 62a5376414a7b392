#include "render/FrameRenderer.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "core/Elapsed.h"
#include "core/Errors.h"
#include "render/CacheFrame.h"
#include "render/CameraRays.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

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
      group_(group && group->size() > 1 ? group : nullptr), kernel_(scene, tracer, settings, cache_) {
    // Process 0 gathers the other processes' pixels, not their records.
    if (group_ && settings.recordCacheLevels)
        throw InputError("the per-pixel cache-level record is made by a single process only");
}

FrameStats FrameRenderer::render(const Camera& camera, Image& film, CacheLevelImage* levels,
                                 const PixelSamples* samples, int sample) const {
    if (film.width() != settings_.width || film.height() != settings_.height)
        film = Image(settings_.width, settings_.height);
    const CameraRays cameraRays = samples ? CameraRays(camera, settings_.width, settings_.height, *samples, sample)
                                          : CameraRays(camera, settings_.width, settings_.height);
    if (group_) return renderDistributed(cameraRays, film);
    kernel_.prepareFrame();  // meshes that moved since the last frame  // never with the record (see the constructor)
    if (!settings_.recordCacheLevels) levels = nullptr;
    if (levels && (levels->width() != settings_.width || levels->height() != settings_.height))
        *levels = CacheLevelImage(settings_.width, settings_.height);
    std::vector<TileScratch>& scratch = scratch_;
    scratch.resize(static_cast<std::size_t>(parallel_.threadCount()));
    for (TileScratch& s : scratch) s.beginFrame();
    CacheFrame cacheFrame(cache_, parallel_.threadCount(), nullptr, nullptr, levels != nullptr);
    parallel_.forEachTile(settings_.width, settings_.height, settings_.tileSize, [&](const TileRange& tile, int worker) {
        kernel_.renderCameraTile(cameraRays, tile, tileKey(tile, settings_.width, settings_.tileSize),
                                 scratch[static_cast<std::size_t>(worker)], cacheFrame.worker(worker), film,
                                 levels);
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
// tiles' indices, pixels, costs and ray counts.
FrameStats FrameRenderer::renderDistributed(const CameraRays& cameraRays, Image& film) const {
    const ProcessGroup& group = *group_;
    const int width = settings_.width, height = settings_.height, tileSize = settings_.tileSize;
    const int tiles = tileCount(width, height, tileSize);
    ClusterStats cluster;
    cluster.processes = group.size();

    std::vector<TileScratch>& scratch = scratch_;
    scratch.resize(static_cast<std::size_t>(parallel_.threadCount()));
    for (TileScratch& s : scratch) s.beginFrame();
    CacheFrame cacheFrame(cache_, parallel_.threadCount(), &group, &storeExchange_);
    // This process's message to process 0: the pixels of its tiles (none
    // from process 0 itself), then a trailer of the tiles' indices, kernel
    // times and ray counts. Each tile's pixels are copied right after the
    // tile is rendered, while they are still in the cache: worker 0's
    // straight into the message, the others' into buffers appended to it.
    const bool sendsPixels = !group.isRoot();
    const auto workers = static_cast<std::size_t>(parallel_.threadCount());
    Bytes& part = imagePart_;
    part.clear();
    workerPixels_.resize(workers);
    for (Bytes& pixels : workerPixels_) pixels.clear();
    std::vector<std::vector<int>> doneTiles(workers);
    std::vector<std::vector<double>> doneCosts(workers);
    const auto renderTile = [&](int t, int worker) {
        const auto w = static_cast<std::size_t>(worker);
        const auto tileStart = Clock::now();
        const TileRange tile = tileAt(t, width, height, tileSize);
        kernel_.renderCameraTile(cameraRays, tile, tileKey(tile, width, tileSize), scratch[w], cacheFrame.worker(worker),
                                 film);
        doneTiles[w].push_back(t);
        doneCosts[w].push_back(millisecondsSince(tileStart));
        if (!sendsPixels) return;
        Bytes& out = w == 0 ? part : workerPixels_[w];
        for (int y = tile.y0; y < tile.y1; ++y)
            appendBytes(out, std::span<const Rgb>(&film.at(tile.x0, y), static_cast<std::size_t>(tile.x1 - tile.x0)));
    };
    if (settings_.tileBalance == TileBalance::Claim) {
        cluster.assignment = "claimed tiles";
        parallel_.forEachIndex(parallel_.threadCount(), [&](int, int worker) {
            for (std::int64_t t = group.drawTickets(1); t < tiles; t = group.drawTickets(1))
                renderTile(static_cast<int>(t), worker);
        });
        // Every process has drawn its last ticket of the frame before the
        // counter is reset, and nobody draws the next frame's before.
        group.barrier();
        if (group.isRoot()) group.resetTickets();
        group.barrier();
    } else {
        const std::vector<int> owners = agreeTileOwners(group, settings_.tileBalance, tiles, lastTileCosts_,
                                                        cluster.assignment, cluster.controlBytes);
        std::vector<int> mine;
        for (int t = 0; t < tiles; ++t)
            if (owners[static_cast<std::size_t>(t)] == group.rank()) mine.push_back(t);
        parallel_.forEachIndex(static_cast<int>(mine.size()),
                               [&](int k, int worker) { renderTile(mine[static_cast<std::size_t>(k)], worker); });
    }

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

    // The tiles in the order of their pixels: worker 0's, then worker 1's, ...
    std::uint64_t tileTotal = 0;
    for (std::size_t w = 0; w < workers; ++w) {
        if (w > 0) part.insert(part.end(), workerPixels_[w].begin(), workerPixels_[w].end());
        tileTotal += doneTiles[w].size();
    }
    for (const std::vector<int>& t : doneTiles) appendBytes(part, std::span<const int>(t));
    for (const std::vector<double>& c : doneCosts) appendBytes(part, std::span<const double>(c));
    appendBytes(part, tileTotal);
    appendBytes(part, tileRays);
    appendBytes(part, stages);
    GatheredBytes& parts = imageParts_;
    group.gatherToRoot(part, parts);
    if (!group.isRoot()) {
        stats.cluster = cluster;
        return stats;
    }

    cluster.tilesPerProcess.assign(static_cast<std::size_t>(group.size()), 0);
    lastTileCosts_.assign(static_cast<std::size_t>(tiles), 0.0);
    StageTimes allStages;
    std::vector<double> busy(parts.count(), 0.0);
    std::vector<int> theirTiles;
    std::vector<double> theirCosts;
    constexpr std::size_t kFixedTrailer = sizeof(std::uint64_t) + sizeof(RayCounts) + sizeof(StageTimes);
    for (std::size_t r = 0; r < parts.count(); ++r) {
        const std::span<const std::byte> message = parts.of(r);
        if (message.size() < kFixedTrailer) throw std::out_of_range("truncated process message");
        ByteReader fixed(message.last(kFixedTrailer));
        const auto count = fixed.read<std::uint64_t>();
        stats.rays += fixed.read<RayCounts>();
        allStages += fixed.read<StageTimes>();
        if (count > static_cast<std::uint64_t>(tiles)) throw std::out_of_range("process message: too many tiles");
        const std::size_t trailer = kFixedTrailer + static_cast<std::size_t>(count) * (sizeof(int) + sizeof(double));
        if (message.size() < trailer) throw std::out_of_range("truncated process message");
        theirTiles.resize(static_cast<std::size_t>(count));
        theirCosts.resize(static_cast<std::size_t>(count));
        ByteReader lists(message.subspan(message.size() - trailer, trailer - kFixedTrailer));
        lists.readInto(std::span<int>(theirTiles));
        lists.readInto(std::span<double>(theirCosts));
        ByteReader pixels(message.first(message.size() - trailer));
        cluster.tilesPerProcess[r] = static_cast<int>(count);
        for (std::size_t k = 0; k < theirTiles.size(); ++k) {
            const int t = theirTiles[k];
            if (t < 0 || t >= tiles) throw std::out_of_range("process message: tile index out of range");
            lastTileCosts_[static_cast<std::size_t>(t)] = theirCosts[k];
            busy[r] += theirCosts[k];
            if (static_cast<int>(r) == group.rank()) continue;  // already in the film
            const TileRange tile = tileAt(t, width, height, tileSize);
            for (int y = tile.y0; y < tile.y1; ++y)
                pixels.readInto(std::span<Rgb>(&film.at(tile.x0, y), static_cast<std::size_t>(tile.x1 - tile.x0)));
        }
        if (!pixels.atEnd()) throw std::out_of_range("process message: more pixels than tiles");
        if (static_cast<int>(r) != group.rank()) {
            cluster.controlBytes += trailer;
            cluster.imageBytes += message.size() - trailer;
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
