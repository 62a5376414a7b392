#include "rendercache/HoleFilling.h"

#include <algorithm>
#include <array>
#include <bit>

#include "rendercache/PixelStateBits.h"
#include "rendercache/SurfaceClusters.h"

namespace raycache {

namespace {

// An outcome is the hole's new state, so that the last pass is a select a
// register of pixels at a time (kWants7x7 never outlives the 7x7 pass).
enum Outcome : unsigned char {
    k3x3 = static_cast<unsigned char>(PixelState::Filled3x3),
    k7x7 = static_cast<unsigned char>(PixelState::Filled7x7),
    kUnfilled = static_cast<unsigned char>(PixelState::Unfilled),
    kWants7x7 = 0xfe,
    kNone = 0xff,
};

// A row of what the filters read, its addresses made once per row (per row
// of holes, not per hole or neighbour): `states` null for a row outside the
// image.
struct SampleRow {
    const PixelState* states = nullptr;
    const Rgb* film = nullptr;
    const SampleLook* looks = nullptr;    // with `samples`
    const std::uint32_t* keys = nullptr;  // with `surfaces`
    const SamplePoint* points = nullptr;  // with `surfaces`
    int firstPixel = 0;                   // y * width of the row
};

// Per worker, the column sums of the dense 7x7 rows.
struct ColumnSums {
    std::vector<Rgb> sum;
    std::vector<int> count;
};

// What the passes of one fillHoles() share. Both filters read `state` and
// the colours of pixels showing a sample, and write only the colours of
// holes and `outcome`: rows run in any order, without a data race. (The
// first pass, when it also writes the samples' colours to the film, reads
// them from `samples`, never from the film.) The states change at the end.
struct HoleFill {
    std::vector<PixelState>& state;
    Image& film;
    const SampleColors* samples;
    const SampleSurfaces* surfaces;
    std::vector<std::int32_t>* fillSource;
    std::vector<unsigned char>& outcome;
    const int width, height;
    const std::size_t words;  // of a row's PixelStateBits
    std::vector<FillCounts> perRow;
    // Per row: holes the 3x3 filter could not fill, and whether the row has
    // any hole (rows without are skipped by the later passes).
    std::vector<int> wants7x7;
    // And those holes as bits (rendercache/PixelStateBits.h's layout): the
    // 7x7 pass visits them alone, not every pixel of their rows.
    std::vector<std::uint64_t> wants7x7Bits;
    std::vector<unsigned char> hasHoles;

    HoleFill(std::vector<PixelState>& pixelStates, Image& image, const SampleColors* sampleColors,
             const SampleSurfaces* sampleSurfaces, std::vector<std::int32_t>* sources,
             std::vector<unsigned char>& outcomes)
        : state(pixelStates), film(image), samples(sampleColors), surfaces(sampleSurfaces), fillSource(sources),
          outcome(outcomes), width(image.width()), height(image.height()), words(pixelStateWords(image.width())),
          perRow(static_cast<std::size_t>(height)), wants7x7(static_cast<std::size_t>(height), 0),
          wants7x7Bits(static_cast<std::size_t>(height) * words, 0), hasHoles(static_cast<std::size_t>(height), 0) {}

    std::size_t at(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    }

    SampleRow sampleRow(int ny) const {
        SampleRow r;
        if (ny < 0 || ny >= height) return r;
        const auto line = static_cast<std::size_t>(ny);
        r.states = state.data() + line * static_cast<std::size_t>(width);
        r.film = film.pixels().data() + line * static_cast<std::size_t>(width);
        if (samples) r.looks = samples->looks + samples->origin + line * samples->stride;
        if (surfaces) {
            r.keys = surfaces->depths->keyData() + surfaces->depths->pixelIndex(0, ny);
            r.points = surfaces->points + surfaces->origin + line * surfaces->stride;
        }
        r.firstPixel = ny * width;
        return r;
    }

    // The sample at column nx of row `r` into `groups`: without `surfaces`, all in one group.
    void addSample(SurfaceClusters& groups, const SampleRow& r, int nx, float w) const {
        const auto column = static_cast<std::size_t>(nx);
        const Rgb& color = r.looks ? r.looks[column].color : r.film[column];
        if (surfaces)
            groups.add(color, w, PointImage::depthOf(r.keys[column]), r.points[column].objectId, r.firstPixel + nx);
        else
            groups.add(color, w, 0.0f, 0);
    }

    void recordSource(int x, int y, const SurfaceClusters& groups) const {
        if (fillSource && surfaces) (*fillSource)[at(x, y)] = groups.chosenSource();
    }

    // Row y: the samples' colours into the film, and each hole the 3x3
    // filter of its neighbours' samples; the holes it cannot fill are
    // marked for the 7x7. `bits`: the worker's scratch for the rows' states
    // as bits (the samples of the three rows a box reads, and the holes).
    void fill3x3Row(int y, std::vector<std::uint64_t>& bits);
    // Row y's holes the 3x3 left: the 7x7 box's mean.
    void fill7x7Row(int y, ColumnSums& columns);
    // Row y's holes take their new states.
    void applyOutcomesRow(int y);
};

void HoleFill::fill3x3Row(int y, std::vector<std::uint64_t>& bits) {
    FillCounts row;
    int wanting = 0;
    bool holes = false;
    // Addresses and sizes in locals: through the vectors and the image the
    // compiler reloaded them after every store to the film.
    const PixelState* const stateData = state.data();
    Rgb* const filmData = film.pixels().data();
    unsigned char* const outcomeData = outcome.data();
    std::int32_t* const sourceData = fillSource && surfaces ? fillSource->data() : nullptr;
    const SampleLook* const looks = samples ? samples->looks + samples->origin : nullptr;
    const std::size_t lookStride = samples ? samples->stride : 0;
    const std::size_t rowStart = at(0, y);
    const int columns = width;
    bits.resize(4 * words);
    const std::array<std::uint64_t*, 3> sampleBits = {bits.data(), bits.data() + words, bits.data() + 2 * words};
    std::uint64_t* const holeBits = bits.data() + 3 * words;
    std::uint64_t* const wantsRow = wants7x7Bits.data() + static_cast<std::size_t>(y) * words;
    pixelStateBits(stateData + rowStart, columns, PixelState::Reprojected, PixelState::Fresh, sampleBits[1]);
    pixelStateBits(stateData + rowStart, columns, PixelState::Culled, PixelState::Hole, holeBits);
    // The samples' colours into the film, a run of samples at a time.
    if (looks) {
        const SampleLook* const rowLooks = looks + static_cast<std::size_t>(y) * lookStride;
        for (std::size_t w = 0; w + 1 < words; ++w)
            for (std::uint64_t b = sampleBits[1][w]; b;) {
                const int start = std::countr_zero(b), end = start + std::countr_one(b >> start);
                const std::size_t first = w * 64 + static_cast<std::size_t>(start);
                const SampleLook* from = rowLooks + first;
                Rgb* to = filmData + rowStart + first;
                for (Rgb* const runEnd = to + (end - start); to != runEnd; ++to, ++from) *to = from->color;
                b = end < 64 ? b & (~std::uint64_t{0} << end) : 0;
            }
    }
    const bool anyHole = std::any_of(holeBits, holeBits + words, [](std::uint64_t b) { return b != 0; });
    if (anyHole) {
        for (int r = 0; r < 3; r += 2) {
            const int ny = y - 1 + r;
            if (ny < 0 || ny >= height)
                std::fill(sampleBits[static_cast<std::size_t>(r)], sampleBits[static_cast<std::size_t>(r)] + words, 0);
            else
                pixelStateBits(stateData + at(0, ny), columns, PixelState::Reprojected, PixelState::Fresh,
                               sampleBits[static_cast<std::size_t>(r)]);
        }
    }
    // The three rows a hole's 3x3 box reads.
    const std::array<SampleRow, 3> neighbourRows = {sampleRow(y - 1), sampleRow(y), sampleRow(y + 1)};
    std::int64_t samplesRead = 0;  // by the holes' boxes (ReconstructionBytes.h)
    if (anyHole)
        forEachPixelSet(holeBits, columns, [&](int x) {
            holes = true;
            SurfaceClusters groups;
            // The box's samples row by row, each row's as bits dx + 1 (the
            // box clipped to the image by the bits: none past its edges);
            // edge neighbours weigh 2, corners 1.
            const auto addRow = [&](const SampleRow& r, unsigned three, float cornerWeight) {
                // The box row's samples: 2-bit counts of 0..7 in one constant
                // (std::popcount is a library call on the baseline target,
                // whose spills cost this pass more than the count).
                samplesRead += (0xE994u >> (three * 2)) & 3u;
                for (; three; three &= three - 1) {
                    const int dx = std::countr_zero(three) - 1;
                    addSample(groups, r, x + dx, dx == 0 ? 2.0f : cornerWeight);
                }
            };
            addRow(neighbourRows[0], threeBitsAround(sampleBits[0], x), 1.0f);
            addRow(neighbourRows[1], threeBitsAround(sampleBits[1], x), 2.0f);
            addRow(neighbourRows[2], threeBitsAround(sampleBits[2], x), 1.0f);
            const std::size_t i = rowStart + static_cast<std::size_t>(x);
            if (!groups.empty()) {
                filmData[i] = groups.mean();
                if (sourceData) sourceData[i] = groups.chosenSource();
                outcomeData[i] = k3x3;
                ++row.filled3x3;
            } else {
                outcomeData[i] = kWants7x7;
                wantsRow[static_cast<std::size_t>(x / 64)] |= std::uint64_t{1} << (x % 64);
                ++wanting;
            }
        });
    row.samplesRead += samplesRead;
    perRow[static_cast<std::size_t>(y)] = row;
    wants7x7[static_cast<std::size_t>(y)] = wanting;
    hasHoles[static_cast<std::size_t>(y)] = holes ? 1 : 0;
}

void HoleFill::fill7x7Row(int y, ColumnSums& columns) {
    if (wants7x7[static_cast<std::size_t>(y)] == 0) return;
    FillCounts row = perRow[static_cast<std::size_t>(y)];
    const std::uint64_t* const wantsRow = wants7x7Bits.data() + static_cast<std::size_t>(y) * words;
    int first = width, last = -1;
    forEachPixelSet(wantsRow, width, [&](int x) {
        first = std::min(first, x);
        last = x;
    });
    const int wanting = wants7x7[static_cast<std::size_t>(y)];
    // The edge-aware filter groups each box's samples itself: the 49 pixels of each box.
    const bool dense = !surfaces && last - first + 1 + 2 * kPrefilterRadius < 6 * wanting;
    const int x0 = dense ? std::max(0, first - kPrefilterRadius) : 0;
    const int x1 = dense ? std::min(width - 1, last + kPrefilterRadius) : -1;  // no columns when sparse
    const int y0 = std::max(0, y - kPrefilterRadius), y1 = std::min(height - 1, y + kPrefilterRadius);
    std::array<SampleRow, 2 * kPrefilterRadius + 1> boxRows;
    for (int ny = y0; ny <= y1; ++ny) boxRows[static_cast<std::size_t>(ny - y0)] = sampleRow(ny);
    columns.sum.assign(static_cast<std::size_t>(x1 - x0 + 1), Rgb{});
    columns.count.assign(static_cast<std::size_t>(x1 - x0 + 1), 0);
    for (int ny = y0; ny <= y1; ++ny)
        for (int nx = x0; nx <= x1; ++nx)
            if (showsSample(state[at(nx, ny)])) {
                columns.sum[static_cast<std::size_t>(nx - x0)] += film.at(nx, ny);
                ++columns.count[static_cast<std::size_t>(nx - x0)];
            }
    for (int c : columns.count) row.samplesRead += c;
    std::int64_t sparseReads = 0;  // a local: the row's counts are written once
    forEachPixelSet(wantsRow, width, [&](int x) {
        Rgb sum;
        int count = 0;
        SurfaceClusters groups;
        const int nx0 = std::max(0, x - kPrefilterRadius), nx1 = std::min(width - 1, x + kPrefilterRadius);
        if (dense) {
            for (int nx = nx0; nx <= nx1; ++nx) {
                sum += columns.sum[static_cast<std::size_t>(nx - x0)];
                count += columns.count[static_cast<std::size_t>(nx - x0)];
            }
            if (count > 0) groups.add(sum * (1.0f / static_cast<float>(count)), 1.0f, 0.0f, 0);
        } else {
            for (int ny = y0; ny <= y1; ++ny) {
                const SampleRow& r = boxRows[static_cast<std::size_t>(ny - y0)];
                for (int nx = nx0; nx <= nx1; ++nx)
                    if (showsSample(r.states[nx])) {
                        addSample(groups, r, nx, 1.0f);
                        ++sparseReads;
                    }
            }
        }
        if (!groups.empty()) {
            film.at(x, y) = groups.mean();
            recordSource(x, y, groups);
            outcome[at(x, y)] = k7x7;
            ++row.filled7x7;
        } else {
            outcome[at(x, y)] = kUnfilled;
            ++row.unfilled;
        }
    });
    row.samplesRead += sparseReads;
    perRow[static_cast<std::size_t>(y)] = row;
}

void HoleFill::applyOutcomesRow(int y) {
    if (!hasHoles[static_cast<std::size_t>(y)]) return;
    auto* __restrict const states = reinterpret_cast<unsigned char*>(state.data()) + at(0, y);
    const unsigned char* __restrict const outcomes = outcome.data() + at(0, y);
    const int columns = width;
    for (int x = 0; x < columns; ++x) states[x] = outcomes[x] == kNone ? states[x] : outcomes[x];
}

}  // namespace

FillCounts fillHoles(std::vector<PixelState>& state, Image& film, const Parallel& parallel,
                     std::vector<unsigned char>* scratch, const SampleColors* samples, const SampleSurfaces* surfaces,
                     std::vector<std::int32_t>* fillSource) {
    std::vector<unsigned char> ownScratch;
    std::vector<unsigned char>& outcome = scratch ? *scratch : ownScratch;
    outcome.assign(state.size(), kNone);
    if (fillSource) fillSource->resize(state.size());
    HoleFill fill(state, film, samples, surfaces, fillSource, outcome);
    const int height = film.height();
    // Counts per row go to a local, written once (no false sharing).
    std::vector<std::vector<std::uint64_t>> bitsPerWorker(static_cast<std::size_t>(parallel.threadCount()));
    parallel.forEachIndex(height, [&](int y, int worker) {
        fill.fill3x3Row(y, bitsPerWorker[static_cast<std::size_t>(worker)]);
    });
    // The 7x7 box only on rows with holes it must fill. Where they are
    // dense, per row the sums of each column's 7 pixels (samples only) over
    // the span of those holes, then 7 columns per hole: a wide hole costs
    // 7 + 7 reads per pixel, not 49. Where they are few and far apart, the
    // 49 pixels of each box. (The choice depends on the holes only, so the
    // image does not depend on the thread count.)
    std::vector<ColumnSums> columnsPerWorker(static_cast<std::size_t>(parallel.threadCount()));
    parallel.forEachIndex(height, [&](int y, int worker) {
        fill.fill7x7Row(y, columnsPerWorker[static_cast<std::size_t>(worker)]);
    });
    parallel.forEachIndex(height, [&](int y, int) { fill.applyOutcomesRow(y); });
    FillCounts total;
    for (const FillCounts& c : fill.perRow) {
        total.filled3x3 += c.filled3x3;
        total.filled7x7 += c.filled7x7;
        total.unfilled += c.unfilled;
        total.samplesRead += c.samplesRead;
    }
    for (unsigned char h : fill.hasHoles) total.rowsWithHoles += h;
    return total;
}

}  // namespace raycache
