#include "rendercache/Reprojection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/Errors.h"

namespace raycache {

namespace {

// The depth test without atomic instructions: the source pool is in pixel
// order (the last frame's), and a sample lands a few rows from where it
// was, so bands of kBandRows rows of source slots are tested in parallel,
// every other band at a time; a band touches only the rows within half a
// band of its own, which the bands running beside it never do. Samples
// that land farther (fast motion, the overflow's predicted samples) are
// tested afterwards on one thread. A minimum does not depend on the order
// in which it is taken, so neither does the outcome.
constexpr int kBandRows = 32;
// Marks a second-chance offer in the slot half of its key: such offers go
// only to pixels no sample landed in, so among themselves they still order
// by (depth, slot), and a tagged key tells the other losers that the pixel
// was empty after the first round. Slots stay below 2^31.
constexpr std::uint32_t kSecondChanceTag = 1u << 31;
constexpr float kNoPixel = -1.0f;

bool emptyAfterFirstRound(std::uint64_t key) {
    return key == PointImage::emptyKey() || (PointImage::slotOf(key) & kSecondChanceTag) != 0;
}

}  // namespace

std::vector<Vec3> objectOrigins(const Scene& scene) {
    std::vector<Vec3> origins;
    origins.reserve(scene.objects.size());
    for (const SceneObject& object : scene.objects) origins.push_back(object.origin);
    return origins;
}

ReprojectionCounts reproject(const SamplePool& from, SamplePool& to, const Scene& scene,
                             const ScreenProjection& projection, int maxAge, PointImage& image,
                             const Parallel& parallel, ReprojectionScratch& scratch) {
    if (to.capacity() != from.capacity() || to.pixelSlots != image.pixelCount() ||
        from.pixelSlots != image.pixelCount() || from.capacity() >= kSecondChanceTag)
        throw RuntimeError("reproject: the pools do not fit the image");
    const std::vector<Vec3> origins = objectOrigins(scene);
    const int rows = image.rows();
    const int margin = image.margin();
    const auto stride = static_cast<std::size_t>(image.stride());
    const int bands = (rows + kBandRows - 1) / kBandRows;
    std::vector<ReprojectionScratch::Landing>& landing = scratch.landing;
    landing.resize(from.capacity());  // the used slots are all written below
    std::vector<std::vector<std::uint32_t>>& far = scratch.farSlots;
    far.resize(static_cast<std::size_t>(bands));
    // Whether band `band` may test a sample that landed in image row `row`
    // (from 0 at the margin's top) in parallel: its second chance reaches
    // one row farther.
    const auto withinReach = [](int band, int row) {
        return row >= band * kBandRows - kBandRows / 2 + 1 && row < (band + 1) * kBandRows + kBandRows / 2 - 1;
    };
    // Counts go to a local and are written once per band or row:
    // neighbouring counters share a cache line, and updating it per sample
    // from two threads cost more than the projection.
    struct Counts {
        std::int64_t live = 0, evicted = 0;
    };
    std::vector<Counts> perBand(static_cast<std::size_t>(bands) + 1);
    // Runs body(slot, band, counts) over every band's slots, every other
    // band at a time, then body(slot, -1, counts) over the overflow slots
    // on this thread.
    const auto forEachBand = [&](const auto& body) {
        for (int phase = 0; phase < 2; ++phase)
            parallel.forEachIndex((bands - phase + 1) / 2, [&](int i, int) {
                const int band = 2 * i + phase;
                Counts counts = perBand[static_cast<std::size_t>(band)];
                const std::size_t end = static_cast<std::size_t>(std::min(rows, (band + 1) * kBandRows)) * stride;
                for (std::size_t slot = static_cast<std::size_t>(band) * kBandRows * stride; slot < end; ++slot)
                    body(slot, band, counts);
                perBand[static_cast<std::size_t>(band)] = counts;
            });
        Counts& counts = perBand.back();
        for (std::size_t slot = from.pixelSlots; slot < from.used(); ++slot) body(slot, -1, counts);
    };

    // First round: project every live sample once and offer it to its
    // pixel; the depth test picks each pixel's winner.
    const int* objectId = from.objectId.data();
    const std::uint16_t* age = from.age.data();
    ReprojectionScratch::Landing* landed = landing.data();
    for (std::vector<std::uint32_t>& list : far) list.clear();
    forEachBand([&](std::size_t slot, int band, Counts& counts) {
        ReprojectionScratch::Landing& l = landed[slot];
        l.depth = kNoPixel;
        if (objectId[slot] == SamplePool::kEmpty) return;
        ++counts.live;
        if (age[slot] >= maxAge) {
            ++counts.evicted;
            return;
        }
        float px, py, depth;
        if (!projectSample(from, slot, origins, projection, px, py, depth)) return;
        const int x = static_cast<int>(std::floor(px)), y = static_cast<int>(std::floor(py));
        if (!image.covers(x, y)) return;
        l = {px, py, depth};
        const std::uint64_t key = PointImage::key(depth, static_cast<std::uint32_t>(slot));
        if (band < 0) image.offerUnshared(x, y, key);
        else if (withinReach(band, y + margin)) image.offerUnshared(x, y, key);
        else far[static_cast<std::size_t>(band)].push_back(static_cast<std::uint32_t>(slot));
    });
    for (const std::vector<std::uint32_t>& list : far)
        for (std::uint32_t slot : list) {
            const ReprojectionScratch::Landing& l = landed[slot];
            image.offerUnshared(static_cast<int>(std::floor(l.x)), static_cast<int>(std::floor(l.y)),
                                PointImage::key(l.depth, slot));
        }

    // Second chance: a loser offers itself to the nearest neighbouring pixel
    // that the first round left empty (first-round winners stay).
    const auto secondChance = [&](std::size_t slot) {
        const ReprojectionScratch::Landing l = landed[slot];
        const int x = static_cast<int>(std::floor(l.x)), y = static_cast<int>(std::floor(l.y));
        // Its own pixel's first round is over: no second-chance offer goes there.
        if (image.keyAt(x, y) == PointImage::key(l.depth, static_cast<std::uint32_t>(slot))) return;
        // The nearest empty neighbour by distance to its centre; among
        // equals the first in row order (a fixed order).
        const float fx = l.x - static_cast<float>(x) - 0.5f, fy = l.y - static_cast<float>(y) - 0.5f;
        float nearest = std::numeric_limits<float>::infinity();
        int bestX = 0, bestY = 0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                if (dx == 0 && dy == 0) continue;
                const int nx = x + dx, ny = y + dy;
                if (!image.covers(nx, ny) || !emptyAfterFirstRound(image.keyAt(nx, ny))) continue;
                const float ex = static_cast<float>(dx) - fx, ey = static_cast<float>(dy) - fy;
                const float distance = ex * ex + ey * ey;
                if (distance < nearest) {
                    nearest = distance;
                    bestX = nx;
                    bestY = ny;
                }
            }
        if (nearest < std::numeric_limits<float>::infinity())
            image.offerUnshared(bestX, bestY,
                                PointImage::key(l.depth, static_cast<std::uint32_t>(slot) | kSecondChanceTag));
    };
    forEachBand([&](std::size_t slot, int band, Counts&) {
        const ReprojectionScratch::Landing& l = landed[slot];
        if (!(l.depth >= 0.0f)) return;
        if (band >= 0 && !withinReach(band, static_cast<int>(std::floor(l.y)) + margin)) return;  // below
        secondChance(slot);
    });
    for (const std::vector<std::uint32_t>& list : far)
        for (std::uint32_t slot : list) secondChance(slot);

    // Each pixel's winner to its own slot of `to`; the image now names those slots.
    std::vector<std::int64_t> placedPerRow(static_cast<std::size_t>(rows), 0);
    std::vector<std::int64_t> movedPerRow(static_cast<std::size_t>(rows), 0);
    parallel.forEachIndex(rows, [&](int row, int) {
        const int y = row - margin;
        std::int64_t placed = 0, moved = 0;
        for (int x = -margin; x < image.width() + margin; ++x) {
            const std::size_t pixel = image.pixelIndex(x, y);
            const std::uint64_t key = image.keyAt(x, y);
            if (key == PointImage::emptyKey()) {
                to.objectId[pixel] = SamplePool::kEmpty;
                continue;
            }
            const std::uint32_t tagged = PointImage::slotOf(key);
            to.copySample(from, tagged & ~kSecondChanceTag, pixel);
            ++to.age[pixel];
            image.place(x, y, PointImage::depthOf(key), static_cast<std::uint32_t>(pixel));
            ++placed;
            moved += (tagged & kSecondChanceTag) ? 1 : 0;
        }
        placedPerRow[static_cast<std::size_t>(row)] = placed;
        movedPerRow[static_cast<std::size_t>(row)] = moved;
    });
    to.overflowUsed = 0;

    ReprojectionCounts total;
    for (std::int64_t p : placedPerRow) total.placed += p;
    for (std::int64_t m : movedPerRow) total.moved += m;
    std::int64_t live = 0;
    for (const Counts& c : perBand) {
        live += c.live;
        total.evicted += c.evicted;
    }
    total.lost = live - total.evicted - total.placed;
    return total;
}

}  // namespace raycache
