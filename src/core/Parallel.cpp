#include "core/Parallel.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/version.h>

namespace raycache {

struct Parallel::Impl {
    // More threads than the hardware has cannot run at once; oneTBB would
    // ignore them anyway, with a warning on stderr.
    explicit Impl(int threads)
        : arena(threads > 0 ? std::min(threads, hardwareThreads()) : tbb::task_arena::automatic) {}
    tbb::task_arena arena;
};

Parallel::Parallel(int threads) : impl_(std::make_unique<Impl>(threads)) {}
Parallel::~Parallel() = default;

int Parallel::hardwareThreads() { return std::max(1, tbb::info::default_concurrency()); }

int Parallel::threadCount() const { return impl_->arena.max_concurrency(); }

std::string Parallel::libraryVersion() { return TBB_runtime_version(); }

void Parallel::forEachIndex(int count, const std::function<void(int, int)>& body) const {
    impl_->arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, count, 1), [&](const tbb::blocked_range<int>& r) {
            const int worker = tbb::this_task_arena::current_thread_index();
            for (int i = r.begin(); i != r.end(); ++i) body(i, worker);
        });
    });
}

void Parallel::forEachTile(int width, int height, int tileSize,
                           const std::function<void(const TileRange&, int)>& body) const {
    const int tilesX = (width + tileSize - 1) / tileSize;
    const int tilesY = (height + tileSize - 1) / tileSize;
    forEachIndex(tilesX * tilesY, [&](int i, int worker) {
        const int tx = i % tilesX, ty = i / tilesX;
        const TileRange tile{tx * tileSize, ty * tileSize, std::min(width, (tx + 1) * tileSize),
                             std::min(height, (ty + 1) * tileSize)};
        body(tile, worker);
    });
}

}  // namespace raycache
