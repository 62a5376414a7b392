#pragma once
// The one place the renderer reaches oneTBB: a fixed-size worker arena and a
// loop over screen tiles. Callers never see TBB types.
#include <functional>
#include <memory>
#include <string>

namespace raycache {

struct TileRange {
    int x0, y0, x1, y1;  // half-open pixel rectangle [x0,x1) x [y0,y1)
};

class Parallel {
public:
    // threads <= 0 means "all hardware threads"; more than hardwareThreads() are clamped to it.
    explicit Parallel(int threads = 0);
    ~Parallel();
    Parallel(const Parallel&) = delete;
    Parallel& operator=(const Parallel&) = delete;

    int threadCount() const;

    // The threads this process may run at once (CPU affinity and limits included).
    static int hardwareThreads();

    // The oneTBB version the program runs with ("2021.8"), for reports.
    static std::string libraryVersion();

    // Calls body(tile, workerIndex) once per tile of size tileSize covering
    // width x height; workerIndex in [0, threadCount()) identifies per-thread
    // scratch. Tiles are independent, so the result never depends on order.
    void forEachTile(int width, int height, int tileSize,
                     const std::function<void(const TileRange&, int workerIndex)>& body) const;

    // Calls body(i, workerIndex) for i in [0, count).
    void forEachIndex(int count, const std::function<void(int, int workerIndex)>& body) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace raycache
