#include "rendercache/Reprojection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/Errors.h"
#include "rendercache/ProjectionLanes.h"

namespace raycache {

namespace {

// The depth test without atomic instructions: the source pool is in pixel
// order (the last frame's), and a sample lands a few rows from where it
// was, so bands of kBandRows rows of source slots are tested in parallel,
// every other band at a time; a band touches only the rows within half a
// band of its own, which the bands running beside it never do. Samples
// that land farther (fast motion, the overflow's predicted samples) are
// tested afterwards on one thread. The nearest offer wins, equal depths
// going to the lower slot (looked up only on a tie: the image holds depths
// alone); a minimum does not depend on the order in which it is taken, so
// neither does the outcome.
constexpr int kBandRows = 32;
// Marks a second-chance offer in its key (the sign bit, which no depth
// sets): such offers go only to pixels no sample landed in, so among
// themselves they still order by depth, a tagged key is farther than any
// first-round key and nearer than none, and it tells the other losers that
// the pixel was empty after the first round.
constexpr std::uint32_t kSecondChanceTag = 1u << 31;

bool emptyAfterFirstRound(std::uint32_t key) { return (key & kSecondChanceTag) != 0; }  // emptyKey() too

using Landed = ReprojectionScratch::Landed;

// Counts go to a local and are written once per band or row: neighbouring
// counters share a cache line, and updating it per sample from two threads
// cost more than the projection.
struct BandCounts {
    std::int64_t live = 0, evicted = 0;
};

// What the steps of one reprojection share: the image's depths and, per
// pixel, the source slot holding it. Addresses in members copied to locals
// by each step's loop: through the image and the vectors the compiler
// reloaded every address and size after each store (it cannot tell a store
// into the image from one into a vector's own fields), a third of the first
// round's instructions.
struct DepthTest {
    const SamplePool& from;
    const ScreenProjection& projection;
    const ScreenProjection* next;
    std::uint32_t* keys;
    std::uint32_t* winner;
    const Vec3* origins;
    int width, height, margin, rows, bands;
    std::size_t stride;
    int coverX0, coverX1, coverY1;  // the image and its margin: [coverX0, coverX1) x [coverX0, coverY1)

    std::size_t pixelOfImage(int x, int y) const {
        return static_cast<std::size_t>(y + margin) * stride + static_cast<std::size_t>(x + margin);
    }

    // Offers `sample` to pixel (x, y); the one that loses goes to `list`
    // (of the band that reached the pixel, so also reaches its
    // neighbours), a sample it pushed out projected again.
    void offer(int x, int y, const Landed& sample, std::vector<Landed>& list) const {
        const std::uint32_t key = PointImage::key(sample.depth);
        const std::size_t pixel = pixelOfImage(x, y);
        const std::uint32_t held = keys[pixel];
        if (key > held || (key == held && sample.slot > winner[pixel])) {
            list.push_back(sample);
            return;
        }
        keys[pixel] = key;
        const std::uint32_t loser = winner[pixel];
        winner[pixel] = sample.slot;
        if (held == PointImage::emptyKey()) return;
        Landed pushedOut{loser, 0.0f, 0.0f, 0.0f};
        projectPoint(from.point[loser], origins, projection, pushedOut.x, pushedOut.y, pushedOut.depth);
        list.push_back(pushedOut);
    }

    // Runs body(begin, end, band, counts) over every band's slots, every
    // other band at a time, then body(begin, end, -1, counts) over the
    // overflow slots on this thread.
    template <typename Body>
    void forEachBand(const Parallel& parallel, std::vector<BandCounts>& perBand, const Body& body) const {
        for (int phase = 0; phase < 2; ++phase)
            parallel.forEachIndex((bands - phase + 1) / 2, [&](int i, int) {
                const int band = 2 * i + phase;
                BandCounts counts = perBand[static_cast<std::size_t>(band)];
                const std::size_t end = static_cast<std::size_t>(std::min(rows, (band + 1) * kBandRows)) * stride;
                body(static_cast<std::size_t>(band) * kBandRows * stride, end, band, counts);
                perBand[static_cast<std::size_t>(band)] = counts;
            });
        body(from.pixelSlots, from.used(), -1, perBand.back());
    }
};

// First round, one band's slots (band -1: the overflow's, on this thread):
// project every live sample once and offer it to its pixel; the depth test
// picks each pixel's winner. Losers go to `lost`, samples landing beyond
// the band's reach to `tooFar`.
void firstRoundOfBand(const DepthTest& test, std::size_t begin, std::size_t end, int band, int maxAge,
                      std::int32_t* nextOfSource, BandCounts& bandCounts, std::vector<Landed>& lost,
                      std::vector<Landed>& tooFar) {
    BandCounts counts = bandCounts;
    // Copies the stores cannot touch.
    const ScreenProjection through = test.projection;
    const ScreenProjection nextThrough = test.next ? *test.next : test.projection;
    // What the loop reads, in locals of its own (through `test` each was
    // loaded for every sample).
    const SamplePoint* const points = test.from.point.data();
    const SampleLook* const looks = test.from.look.data();
    const Vec3* const objectOrigins = test.origins;
    std::int32_t* const nextPixels = test.next ? nextOfSource : nullptr;
    const int oldest = maxAge, imageWidth = test.width, imageHeight = test.height, imageMargin = test.margin;
    const int x0 = test.coverX0, x1 = test.coverX1, y1 = test.coverY1;
    // The image rows y in [reachFirst, reachEnd) in which the band may test
    // a sample in parallel: within half a band of its own, less one row, as
    // a second chance reaches one row farther (every row on one thread).
    const int reachFirst =
        band < 0 ? std::numeric_limits<int>::min() : band * kBandRows - kBandRows / 2 + 1 - imageMargin;
    const int reachEnd =
        band < 0 ? std::numeric_limits<int>::max() : (band + 1) * kBandRows + kBandRows / 2 - 1 - imageMargin;
    // The depth test's common case, a sample landing in a pixel still
    // empty, without the call to `offer` (which reloaded the image's
    // address, stride and margin for every sample).
    std::uint32_t* const imageKeys = test.keys;
    std::uint32_t* const winners = test.winner;
    const std::size_t rowStride = test.stride;
    // Sixteen samples projected at a time (both cameras), then offered one by one.
    ProjectedSamples projected;
    for (std::size_t block = begin; block < end; block += kFloatLanes) {
        const int count = static_cast<int>(std::min<std::size_t>(kFloatLanes, end - block));
        projectSamples16(points + block, count, objectOrigins, through, test.next ? &nextThrough : nullptr,
                         imageWidth, imageHeight, projected);
        // Where the block's samples land through the next camera, the whole
        // block at once: only the slots of samples that win a pixel are ever
        // read (per sample, behind the tests below, the store cost six
        // instructions).
        if (nextPixels) std::copy(projected.nextPixel, projected.nextPixel + count, nextPixels + block);
        for (int lane = 0; lane < count; ++lane) {
            const std::size_t slot = block + static_cast<std::size_t>(lane);
            if (points[slot].objectId == SamplePool::kEmpty) continue;
            ++counts.live;
            if (looks[slot].age >= oldest) {
                ++counts.evicted;
                continue;
            }
            if (!projected.landed[lane]) continue;
            const Landed sample{static_cast<std::uint32_t>(slot), projected.x[lane], projected.y[lane],
                                projected.depth[lane]};
            const int x = projected.pixelX[lane], y = projected.pixelY[lane];
            if (x < x0 || y < x0 || x >= x1 || y >= y1) continue;
            if (y < reachFirst || y >= reachEnd) {
                tooFar.push_back(sample);
                continue;
            }
            const std::size_t pixel =
                static_cast<std::size_t>(y + imageMargin) * rowStride + static_cast<std::size_t>(x + imageMargin);
            const std::uint32_t key = PointImage::key(sample.depth);
            if (imageKeys[pixel] == PointImage::emptyKey() && key != PointImage::emptyKey()) {
                imageKeys[pixel] = key;  // what offer() does there: the offer wins, nobody is pushed out
                winners[pixel] = sample.slot;
            } else {
                test.offer(x, y, sample, lost);
            }
        }
    }
    bandCounts = counts;
}

// Second chance: a loser offers itself to the nearest neighbouring pixel
// that the first round left empty (first-round winners stay).
void giveSecondChance(const DepthTest& test, const Landed& l) {
    std::uint32_t* const keys = test.keys;
    const int coverX0 = test.coverX0, coverX1 = test.coverX1, coverY1 = test.coverY1;
    const std::size_t stride = test.stride;
    const int x = ScreenProjection::pixelOf(l.x), y = ScreenProjection::pixelOf(l.y);
    // Mostly the whole neighbourhood lies in the image and its margin: then
    // no neighbour is tested against its edges, and each one's key is a
    // step from the centre's (per neighbour, the tests and the index cost
    // fourteen instructions).
    const bool inside = x > coverX0 && y > coverX0 && x + 1 < coverX1 && y + 1 < coverY1;
    const auto centre = static_cast<std::ptrdiff_t>(y - coverX0) * static_cast<std::ptrdiff_t>(stride) +
                        static_cast<std::ptrdiff_t>(x - coverX0);
    // The nearest empty neighbour by distance to its centre; among equals
    // the first in row order (a fixed order).
    const float fx = l.x - static_cast<float>(x) - 0.5f, fy = l.y - static_cast<float>(y) - 0.5f;
    float nearest = std::numeric_limits<float>::infinity();
    int bestX = 0, bestY = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dy == 0) continue;
            const int nx = x + dx, ny = y + dy;
            if (!inside && (nx < coverX0 || ny < coverX0 || nx >= coverX1 || ny >= coverY1)) continue;
            if (!emptyAfterFirstRound(keys[centre + dy * static_cast<std::ptrdiff_t>(stride) + dx])) continue;
            const float ex = static_cast<float>(dx) - fx, ey = static_cast<float>(dy) - fy;
            const float distance = ex * ex + ey * ey;
            if (distance < nearest) {
                nearest = distance;
                bestX = nx;
                bestY = ny;
            }
        }
    if (nearest == std::numeric_limits<float>::infinity()) return;
    const std::uint32_t key = PointImage::key(l.depth) | kSecondChanceTag;
    const std::size_t pixel = test.pixelOfImage(bestX, bestY);
    const std::uint32_t held = keys[pixel];
    if (key < held || (key == held && l.slot < test.winner[pixel])) {
        keys[pixel] = key;
        test.winner[pixel] = l.slot;
    }
}

// What copying the winners found, per row.
struct CopiedCounts {
    std::int64_t placed = 0, moved = 0, reshaded = 0, textured = 0;
};

// One row of pixel slots: each pixel's winner to its own slot of `to` (two
// 16-byte records and, for a sample that depends on the eye, its reshading
// inputs, for a textured one its colour's parts); the image's keys lose
// their second-chance marks.
CopiedCounts copyWinnersOfRow(const DepthTest& test, int row, SamplePool& to, const std::int32_t* nextOfSource,
                              std::vector<std::int32_t>* nextPixel, int ageStep) {
    // The arrays' addresses in locals: the compiler cannot tell that the
    // stores do not change the vectors, and reloaded their addresses for
    // every sample.
    const SamplePool& from = test.from;
    std::uint32_t* const keys = test.keys;
    const ReshadeInputs* fromReshade = from.reshade.data();
    SamplePoint* toPoint = to.point.data();
    SampleLook* toLook = to.look.data();
    ReshadeInputs* toReshade = to.reshade.data();
    const SampleTexturing* fromTexturing = from.texturing.data();
    SampleTexturing* toTexturing = to.texturing.data();
    std::int32_t* nextOfPixel = test.next ? nextPixel->data() : nullptr;
    const std::uint32_t* const winners = test.winner;
    const std::int32_t* const nextOfWinner = nextOfSource;
    const SamplePoint* const points = from.point.data();
    const SampleLook* const looks = from.look.data();
    const int ageAdded = ageStep;
    CopiedCounts counts;
    const std::size_t rowEnd = (static_cast<std::size_t>(row) + 1) * test.stride;
    for (std::size_t pixel = static_cast<std::size_t>(row) * test.stride; pixel < rowEnd; ++pixel) {
        const std::uint32_t key = keys[pixel];
        if (key == PointImage::emptyKey()) {
            toPoint[pixel].objectId = SamplePool::kEmpty;
            if (nextOfPixel) nextOfPixel[pixel] = -1;
            continue;
        }
        const std::size_t source = winners[pixel];
        if (key & kSecondChanceTag) {
            keys[pixel] = key & ~kSecondChanceTag;
            ++counts.moved;
        }
        if (nextOfPixel) nextOfPixel[pixel] = nextOfWinner[source];
        toPoint[pixel] = points[source];
        // The look copied whole (one load and one store; field by field it
        // took ten instructions), then its age.
        const SampleLook look = looks[source];
        toLook[pixel] = look;
        toLook[pixel].age = static_cast<std::uint16_t>(look.age + ageAdded);
        // What reshading needs, only where it means something.
        if (look.viewDependent) {
            toReshade[pixel] = fromReshade[source];
            ++counts.reshaded;
        }
        if (look.textured) {
            toTexturing[pixel] = fromTexturing[source];
            ++counts.textured;
        }
        ++counts.placed;
    }
    return counts;
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
                             const Parallel& parallel, ReprojectionScratch& scratch, const ScreenProjection* next,
                             std::vector<std::int32_t>* nextPixel, int ageStep) {
    if (to.capacity() != from.capacity() || to.pixelSlots != image.pixelCount() ||
        from.pixelSlots != image.pixelCount() || (next && !nextPixel))
        throw RuntimeError("reproject: the pools do not fit the image");
    const std::vector<Vec3> origins = objectOrigins(scene);
    const int rows = image.rows();
    const int bands = (rows + kBandRows - 1) / kBandRows;
    if (next) {
        scratch.nextPixel.resize(from.capacity());  // written for every live slot, read for the winners
        nextPixel->resize(to.pixelSlots);           // every pixel slot written below
    }
    // Per pixel, the slot of `from` whose sample holds it: written when an
    // offer wins, read on a tie and where the image holds a key.
    scratch.winner.resize(image.pixelCount());
    std::vector<std::vector<Landed>>& far = scratch.far;
    far.resize(static_cast<std::size_t>(bands));
    // The last list: losers of the offers made on one thread.
    std::vector<std::vector<Landed>>& losers = scratch.losers;
    losers.resize(static_cast<std::size_t>(bands) + 1);
    for (std::vector<Landed>& list : far) list.clear();
    for (std::vector<Landed>& list : losers) list.clear();
    const int margin = image.margin();
    const DepthTest test{from,          projection,     next,          image.keyData(),
                         scratch.winner.data(), origins.data(), image.width(), image.height(),
                         margin,        rows,           bands,         static_cast<std::size_t>(image.stride()),
                         -margin,       image.width() + margin, image.height() + margin};
    std::int32_t* const nextOfSource = scratch.nextPixel.data();

    // 1. First round, band by band, then the samples that landed far from their band on one thread.
    std::vector<BandCounts> perBand(static_cast<std::size_t>(bands) + 1);
    test.forEachBand(parallel, perBand, [&](std::size_t begin, std::size_t end, int band, BandCounts& counts) {
        std::vector<Landed>& lost = losers[band < 0 ? losers.size() - 1 : static_cast<std::size_t>(band)];
        std::vector<Landed>& tooFar = far[band < 0 ? 0 : static_cast<std::size_t>(band)];
        firstRoundOfBand(test, begin, end, band, maxAge, nextOfSource, counts, lost, tooFar);
    });
    for (const std::vector<Landed>& list : far)
        for (const Landed& sample : list)
            test.offer(ScreenProjection::pixelOf(sample.x), ScreenProjection::pixelOf(sample.y), sample, losers.back());

    // 2. Second chance for the losers, band by band as the first round, then the last list.
    for (int phase = 0; phase < 2; ++phase)
        parallel.forEachIndex((bands - phase + 1) / 2, [&](int i, int) {
            for (const Landed& loser : losers[static_cast<std::size_t>(2 * i + phase)]) giveSecondChance(test, loser);
        });
    for (const Landed& loser : losers.back()) giveSecondChance(test, loser);

    // 3. Each pixel's winner copied to its own slot of `to`.
    std::vector<CopiedCounts> copiedPerRow(static_cast<std::size_t>(rows));
    parallel.forEachIndex(rows, [&](int row, int) {
        copiedPerRow[static_cast<std::size_t>(row)] = copyWinnersOfRow(test, row, to, nextOfSource, nextPixel, ageStep);
    });
    to.overflowUsed = 0;

    ReprojectionCounts total;
    for (const CopiedCounts& c : copiedPerRow) {
        total.placed += c.placed;
        total.moved += c.moved;
        total.reshadeCopied += c.reshaded;
        total.texturingCopied += c.textured;
    }
    for (const BandCounts& c : perBand) {
        total.live += c.live;
        total.evicted += c.evicted;
    }
    total.lost = total.live - total.evicted - total.placed;
    for (const std::vector<Landed>& list : far) total.farOffers += static_cast<std::int64_t>(list.size());
    for (const std::vector<Landed>& list : losers) total.secondChances += static_cast<std::int64_t>(list.size());
    // Every offer ends as its pixel's first-round winner or, once, on a
    // losers' list (pushed out included); the second chance fills only
    // pixels the first round left empty.
    total.offered = total.placed - total.moved + total.secondChances;
    return total;
}

}  // namespace raycache
