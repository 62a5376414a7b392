#include "rendercache/HoleFilling.h"

#include <algorithm>
#include <array>
#include <bit>

#include "rendercache/HoleFill3x3Lanes.h"
#include "rendercache/PixelStateBits.h"
#include "rendercache/SurfaceClusters.h"

namespace raycache {

namespace {

// An outcome is the hole's new state, so that the last pass is a select a
// register of pixels at a time.
enum Outcome : unsigned char {
    k3x3 = static_cast<unsigned char>(PixelState::Filled3x3),
    k7x7 = static_cast<unsigned char>(PixelState::Filled7x7),
    kUnfilled = static_cast<unsigned char>(PixelState::Unfilled),
    kNone = 0xff,
};

// Rows of the 7x7 box above and below its hole.
constexpr int kBoxRows = 2 * kPrefilterRadius + 1;

struct HoleFill;

// Per worker, what the filters reuse from row to row: a row's holes as
// bits (all of them, those the 3x3 left, those either filled), the last
// seven image rows read as the filters read them (a band of rows reads each
// image row once, not once per row of holes that needs it), the lanes'
// results, and the 7x7's column sums.
struct FillScratch {
    std::vector<std::uint64_t> holeBits, wantsBits, filledBits;
    std::array<FillRow, kBoxRows> ring;  // image row y in ring[y mod kBoxRows]
    Fill3x3Results results;
    std::vector<Rgb> columnSum;
    std::vector<int> columnCount;

    // Image row y (possibly outside the image), built unless held.
    const FillRow& rowOf(const HoleFill& fill, int y);
};

// What one fillHoles() shares. Both filters read `state` and the colours of
// pixels showing a sample, and write only the colours of holes and
// `outcome`: rows run in any order, without a data race. (When the fill
// also writes the samples' colours to the film, it reads them from
// `samples`, never from the film.) The states change at the end.
struct HoleFill {
    std::vector<PixelState>& state;
    Image& film;
    const SampleColors* samples;
    const SampleSurfaces* surfaces;
    std::vector<std::int32_t>* fillSource;
    const FilledHolesVisitor* onFilled;
    std::vector<unsigned char>& outcome;
    const int width, height;
    const std::size_t words;  // of a row's PixelStateBits
    std::vector<FillCounts> perRow;
    std::vector<unsigned char> hasHoles;  // per row (rows without are skipped by the last pass)

    HoleFill(std::vector<PixelState>& pixelStates, Image& image, const SampleColors* sampleColors,
             const SampleSurfaces* sampleSurfaces, std::vector<std::int32_t>* sources,
             const FilledHolesVisitor* filledHolesVisitor, std::vector<unsigned char>& outcomes)
        : state(pixelStates), film(image), samples(sampleColors), surfaces(sampleSurfaces), fillSource(sources),
          onFilled(filledHolesVisitor), outcome(outcomes), width(image.width()), height(image.height()),
          words(pixelStateWords(image.width())), perRow(static_cast<std::size_t>(height)),
          hasHoles(static_cast<std::size_t>(height), 0) {}

    std::size_t at(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    }

    // Where image row ny's fields are (no states for a row outside the image).
    FillRowSource sourceOf(int ny) const {
        FillRowSource r;
        if (ny < 0 || ny >= height) return r;
        const auto line = static_cast<std::size_t>(ny);
        r.states = state.data() + line * static_cast<std::size_t>(width);
        r.film = film.pixels().data() + line * static_cast<std::size_t>(width);
        if (samples) r.looks = samples->looks + samples->origin + line * samples->stride;
        if (surfaces) {
            r.keys = surfaces->depths->keyData() + surfaces->depths->pixelIndex(0, ny);
            r.points = surfaces->points + surfaces->origin + line * surfaces->stride;
        }
        return r;
    }

    // Row y: the samples' colours into the film, each hole the 3x3 filter
    // of its neighbours' samples (in lanes, rendercache/HoleFill3x3Lanes.h),
    // and each hole the 3x3 cannot fill the 7x7 box's mean.
    void fillRow(int y, FillScratch& scratch);
    // The 3x3 filter on row y's holes; those it cannot fill into `wantsBits`.
    void fill3x3(int y, FillScratch& scratch, FillCounts& row);
    // The samples around hole (x, y) grouped by surface, in the filter's
    // order: for a hole whose samples lie on several surfaces.
    SurfaceClusters groupsAround(const std::array<const FillRow*, 3>& boxRows, int x, int y) const;
    // The 7x7 box's mean on the holes of row y in `wantsBits`.
    void fill7x7(int y, FillScratch& scratch, FillCounts& row);
    // Row y's holes take their new states.
    void applyOutcomesRow(int y);
};

const FillRow& FillScratch::rowOf(const HoleFill& fill, int y) {
    FillRow& row = ring[static_cast<std::size_t>((y % kBoxRows + kBoxRows) % kBoxRows)];
    if (row.row == y) return row;
    buildFillRow(fill.sourceOf(y), fill.width, row);
    row.row = y;
    return row;
}

void HoleFill::fillRow(int y, FillScratch& scratch) {
    FillCounts row;
    const std::size_t rowStart = at(0, y);
    std::vector<std::uint64_t>& holeBits = scratch.holeBits;
    holeBits.resize(words);
    pixelStateBits(state.data() + rowStart, width, PixelState::Culled, PixelState::Hole, holeBits.data());
    if (std::none_of(holeBits.begin(), holeBits.end(), [](std::uint64_t b) { return b != 0; })) {
        // Every pixel shows its sample (a still camera's frame).
        if (samples) {
            Rgb* const filmData = film.pixels().data() + rowStart;
            const SampleLook* const looks =
                samples->looks + samples->origin + static_cast<std::size_t>(y) * samples->stride;
            for (int x = 0; x < width; ++x) filmData[x] = looks[x].color;
        }
        perRow[static_cast<std::size_t>(y)] = row;
        return;
    }
    hasHoles[static_cast<std::size_t>(y)] = 1;
    scratch.filledBits.assign(words, 0);
    fill3x3(y, scratch, row);
    if (std::any_of(scratch.wantsBits.begin(), scratch.wantsBits.end(), [](std::uint64_t b) { return b != 0; }))
        fill7x7(y, scratch, row);
    perRow[static_cast<std::size_t>(y)] = row;
    if (onFilled && row.filled3x3 + row.filled7x7 > 0) (*onFilled)(y, scratch.filledBits.data());
}

void HoleFill::fill3x3(int y, FillScratch& scratch, FillCounts& row) {
    // Addresses in locals: through the vectors and the image the compiler
    // reloaded them after every store to the film.
    Rgb* const filmData = film.pixels().data();
    std::int32_t* const sourceData = fillSource && surfaces ? fillSource->data() : nullptr;
    unsigned char* const outcomeData = outcome.data();
    std::uint64_t* const filledBits = scratch.filledBits.data();
    std::vector<std::uint64_t>& wantsBits = scratch.wantsBits;
    wantsBits.assign(words, 0);
    const std::size_t rowStart = at(0, y);
    // The three rows a hole's box reads, the filter in lanes, and the row's
    // samples and single-surface holes into the film.
    const std::array<const FillRow*, 3> boxRows = {&scratch.rowOf(*this, y - 1), &scratch.rowOf(*this, y),
                                                   &scratch.rowOf(*this, y + 1)};
    Fill3x3Results& lanes = scratch.results;
    fill3x3Row(*boxRows[0], *boxRows[1], *boxRows[2], scratch.holeBits.data(), width, lanes);
    composeFilmRow(*boxRows[1], lanes, samples != nullptr, width, filmData + rowStart);
    forEachPixelSet(scratch.holeBits.data(), width, [&](int x) {
        const auto column = static_cast<std::size_t>(x);
        const std::int32_t info = lanes.info[column];
        const std::size_t i = rowStart + column;
        const std::uint64_t bit = std::uint64_t{1} << (x % 64);
        switch (Fill3x3Results::outcome(info)) {
        case Fill3x3Outcome::OneSurface:  // its colour is in the film
            if (sourceData) {
                const Fill3x3Neighbour& n = kFill3x3Neighbours[Fill3x3Results::firstNeighbour(info)];
                sourceData[i] = (y - 1 + n.row) * width + x + n.dx;
            }
            break;
        case Fill3x3Outcome::SeveralSurfaces: {
            const SurfaceClusters groups = groupsAround(boxRows, x, y);
            filmData[i] = groups.mean();
            if (sourceData) sourceData[i] = groups.chosenSource();
            break;
        }
        case Fill3x3Outcome::NoSample:
            wantsBits[static_cast<std::size_t>(x / 64)] |= bit;
            return;
        }
        outcomeData[i] = k3x3;
        filledBits[static_cast<std::size_t>(x / 64)] |= bit;
        ++row.filled3x3;
    });
}

SurfaceClusters HoleFill::groupsAround(const std::array<const FillRow*, 3>& boxRows, int x, int y) const {
    SurfaceClusters groups;
    for (const Fill3x3Neighbour& n : kFill3x3Neighbours) {
        const FillRow& r = *boxRows[static_cast<std::size_t>(n.row)];
        const auto column = static_cast<std::size_t>(x + 1 + n.dx);
        if (!r.sample[column]) continue;
        groups.add(Rgb(r.red[column], r.green[column], r.blue[column]), n.weight, r.depth[column], r.object[column],
                   (y - 1 + n.row) * width + x + n.dx);
    }
    return groups;
}

void HoleFill::fill7x7(int y, FillScratch& scratch, FillCounts& row) {
    const std::uint64_t* const wantsBits = scratch.wantsBits.data();
    int first = width, last = -1, wanting = 0;
    forEachPixelSet(wantsBits, width, [&](int x) {
        first = std::min(first, x);
        last = x;
        ++wanting;
    });
    // The box's rows, rows outside the image without samples.
    std::array<const FillRow*, kBoxRows> boxRows;
    for (int k = 0; k < kBoxRows; ++k)
        boxRows[static_cast<std::size_t>(k)] = &scratch.rowOf(*this, y - kPrefilterRadius + k);
    // Where the holes are dense, the sums of each column's 7 pixels
    // (samples only) over the span of those holes, then 7 columns per hole:
    // a wide hole costs 7 + 7 reads per pixel, not 49. Where they are few
    // and far apart, the 49 pixels of each box. The edge-aware filter groups
    // each box's samples itself: the 49 pixels. (The choice depends on the
    // holes only, so the image does not depend on the thread count.)
    const bool dense = !surfaces && last - first + 1 + 2 * kPrefilterRadius < 6 * wanting;
    const int x0 = dense ? std::max(0, first - kPrefilterRadius) : 0;
    const int x1 = dense ? std::min(width - 1, last + kPrefilterRadius) : -1;  // no columns when sparse
    std::vector<Rgb>& columnSum = scratch.columnSum;
    std::vector<int>& columnCount = scratch.columnCount;
    columnSum.assign(static_cast<std::size_t>(x1 - x0 + 1), Rgb{});
    columnCount.assign(static_cast<std::size_t>(x1 - x0 + 1), 0);
    for (const FillRow* r : boxRows)
        for (int nx = x0; nx <= x1; ++nx) {
            const auto column = static_cast<std::size_t>(nx + 1);
            if (!r->sample[column]) continue;
            columnSum[static_cast<std::size_t>(nx - x0)] += Rgb(r->red[column], r->green[column], r->blue[column]);
            ++columnCount[static_cast<std::size_t>(nx - x0)];
        }
    Rgb* const filmData = film.pixels().data();
    unsigned char* const outcomeData = outcome.data();
    std::uint64_t* const filledBits = scratch.filledBits.data();
    forEachPixelSet(wantsBits, width, [&](int x) {
        SurfaceClusters groups;
        const int nx0 = std::max(0, x - kPrefilterRadius), nx1 = std::min(width - 1, x + kPrefilterRadius);
        if (dense) {
            Rgb sum;
            int count = 0;
            for (int nx = nx0; nx <= nx1; ++nx) {
                sum += columnSum[static_cast<std::size_t>(nx - x0)];
                count += columnCount[static_cast<std::size_t>(nx - x0)];
            }
            if (count > 0) groups.add(sum * (1.0f / static_cast<float>(count)), 1.0f, 0.0f, 0);
        } else {
            for (int k = 0; k < kBoxRows; ++k) {
                const FillRow& r = *boxRows[static_cast<std::size_t>(k)];
                const int ny = y - kPrefilterRadius + k;
                for (int nx = nx0; nx <= nx1; ++nx) {
                    const auto column = static_cast<std::size_t>(nx + 1);
                    if (!r.sample[column]) continue;
                    groups.add(Rgb(r.red[column], r.green[column], r.blue[column]), 1.0f, r.depth[column],
                               r.object[column], ny * width + nx);
                }
            }
        }
        const std::size_t i = at(x, y);
        if (groups.empty()) {
            outcomeData[i] = kUnfilled;
            ++row.unfilled;
            return;
        }
        filmData[i] = groups.mean();
        if (fillSource && surfaces) (*fillSource)[i] = groups.chosenSource();
        outcomeData[i] = k7x7;
        filledBits[static_cast<std::size_t>(x / 64)] |= std::uint64_t{1} << (x % 64);
        ++row.filled7x7;
    });
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
                     std::vector<std::int32_t>* fillSource, const FilledHolesVisitor* onFilled) {
    std::vector<unsigned char> ownScratch;
    std::vector<unsigned char>& outcome = scratch ? *scratch : ownScratch;
    outcome.assign(state.size(), kNone);
    if (fillSource) fillSource->resize(state.size());
    HoleFill fill(state, film, samples, surfaces, fillSource, onFilled, outcome);
    const int height = film.height();
    // Bands of rows, so that a worker reads each image row once for the
    // rows of holes around it that need it. Counts per row go to a local,
    // written once (no false sharing).
    std::vector<FillScratch> perWorker(static_cast<std::size_t>(parallel.threadCount()));
    constexpr int kBandRows = 16;
    parallel.forEachIndex((height + kBandRows - 1) / kBandRows, [&](int band, int worker) {
        FillScratch& rows = perWorker[static_cast<std::size_t>(worker)];
        for (int y = band * kBandRows; y < std::min(height, (band + 1) * kBandRows); ++y) fill.fillRow(y, rows);
    });
    parallel.forEachIndex(height, [&](int y, int) { fill.applyOutcomesRow(y); });
    FillCounts total;
    for (const FillCounts& c : fill.perRow) {
        total.filled3x3 += c.filled3x3;
        total.filled7x7 += c.filled7x7;
        total.unfilled += c.unfilled;
    }
    for (unsigned char h : fill.hasHoles) total.rowsWithHoles += h;
    return total;
}

}  // namespace raycache
