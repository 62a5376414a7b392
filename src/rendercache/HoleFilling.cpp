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

struct HoleFill;

// Per worker, what the 3x3 filter reuses from row to row: a row's holes as
// bits, the last three image rows it read as
// the lanes read them (a band of rows reads each image row once, not three
// times), and the lanes' results.
struct Fill3x3Scratch {
    std::vector<std::uint64_t> holeBits;
    std::vector<std::uint64_t> filledBits;  // the holes of the row it filled
    std::array<FillRow, 3> ring;  // image row y in ring[y mod 3]
    Fill3x3Results results;

    // Image row y (possibly outside the image), built unless held.
    const FillRow& rowOf(const HoleFill& fill, int y);
};

// Per worker, the column sums of the dense 7x7 rows, and the holes of the
// row the 7x7 filled.
struct ColumnSums {
    std::vector<Rgb> sum;
    std::vector<int> count;
    std::vector<std::uint64_t> filledBits;
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
    const FilledHolesVisitor* onFilled;
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
             const FilledHolesVisitor* filledHolesVisitor, std::vector<unsigned char>& outcomes)
        : state(pixelStates), film(image), samples(sampleColors), surfaces(sampleSurfaces), fillSource(sources),
          onFilled(filledHolesVisitor), outcome(outcomes), width(image.width()), height(image.height()), words(pixelStateWords(image.width())),
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
    // filter of its neighbours' samples (in lanes, rendercache/HoleFill3x3Lanes.h);
    // the holes it cannot fill are marked for the 7x7.
    void fill3x3Row(int y, Fill3x3Scratch& scratch);
    // The samples around hole (x, y) grouped by surface, in the filter's
    // order: for a hole whose samples lie on several surfaces.
    SurfaceClusters groupsAround(const std::array<const FillRow*, 3>& boxRows, int x, int y) const;
    // Row y's holes the 3x3 left: the 7x7 box's mean.
    void fill7x7Row(int y, ColumnSums& columns);
    // Row y's holes take their new states.
    void applyOutcomesRow(int y);
};

void HoleFill::fill3x3Row(int y, Fill3x3Scratch& scratch) {
    FillCounts row;
    int wanting = 0;
    bool holes = false;
    // Addresses and sizes in locals: through the vectors and the image the
    // compiler reloaded them after every store to the film.
    const PixelState* const stateData = state.data();
    Rgb* const filmData = film.pixels().data();
    unsigned char* const outcomeData = outcome.data();
    std::int32_t* const sourceData = fillSource && surfaces ? fillSource->data() : nullptr;
    const std::size_t rowStart = at(0, y);
    const int columns = width;
    std::vector<std::uint64_t>& holeBits = scratch.holeBits;
    holeBits.resize(words);
    std::uint64_t* const wantsRow = wants7x7Bits.data() + static_cast<std::size_t>(y) * words;
    pixelStateBits(stateData + rowStart, columns, PixelState::Culled, PixelState::Hole, holeBits.data());
    const bool anyHole = std::any_of(holeBits.begin(), holeBits.end(), [](std::uint64_t b) { return b != 0; });
    if (!anyHole) {
        // Every pixel shows its sample (a still camera's frame).
        if (samples) {
            const SampleLook* const looks =
                samples->looks + samples->origin + static_cast<std::size_t>(y) * samples->stride;
            for (int x = 0; x < columns; ++x) filmData[rowStart + static_cast<std::size_t>(x)] = looks[x].color;
        }
        perRow[static_cast<std::size_t>(y)] = row;
        wants7x7[static_cast<std::size_t>(y)] = 0;
        hasHoles[static_cast<std::size_t>(y)] = 0;
        return;
    }
    // The three rows a hole's 3x3 box reads, the filter in lanes, and the
    // row's samples and single-surface holes into the film.
    const std::array<const FillRow*, 3> boxRows = {&scratch.rowOf(*this, y - 1), &scratch.rowOf(*this, y),
                                                   &scratch.rowOf(*this, y + 1)};
    Fill3x3Results& lanes = scratch.results;
    raycache::fill3x3Row(*boxRows[0], *boxRows[1], *boxRows[2], holeBits.data(), columns, lanes);
    composeFilmRow(*boxRows[1], lanes, samples != nullptr, columns, filmData + rowStart);
    std::vector<std::uint64_t>& filledBits = scratch.filledBits;
    filledBits.assign(words, 0);
    std::int64_t samplesRead = 0;  // by the holes' boxes (ReconstructionBytes.h)
    forEachPixelSet(holeBits.data(), columns, [&](int x) {
        holes = true;
        const auto column = static_cast<std::size_t>(x);
        const std::int32_t info = lanes.info[column];
        samplesRead += Fill3x3Results::samples(info);
        const std::size_t i = rowStart + column;
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
            outcomeData[i] = kWants7x7;
            wantsRow[static_cast<std::size_t>(x / 64)] |= std::uint64_t{1} << (x % 64);
            ++wanting;
            return;
        }
        outcomeData[i] = k3x3;
        filledBits[static_cast<std::size_t>(x / 64)] |= std::uint64_t{1} << (x % 64);
        ++row.filled3x3;
    });
    if (onFilled && row.filled3x3 > 0) (*onFilled)(y, filledBits.data());
    row.samplesRead += samplesRead;
    perRow[static_cast<std::size_t>(y)] = row;
    wants7x7[static_cast<std::size_t>(y)] = wanting;
    hasHoles[static_cast<std::size_t>(y)] = holes ? 1 : 0;
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

const FillRow& Fill3x3Scratch::rowOf(const HoleFill& fill, int y) {
    FillRow& row = ring[static_cast<std::size_t>((y % 3 + 3) % 3)];
    if (row.row == y) return row;
    const SampleRow source = fill.sampleRow(y);
    buildFillRow(FillRowSource{source.states, source.looks, source.film, source.keys, source.points}, fill.width, row);
    row.row = y;
    return row;
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
    for (int c : columns.count) row.prefilterSamplesRead += c;
    std::int64_t sparseReads = 0;  // a local: the row's counts are written once
    const std::int64_t filledBefore = row.filled7x7;
    columns.filledBits.assign(words, 0);
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
            columns.filledBits[static_cast<std::size_t>(x / 64)] |= std::uint64_t{1} << (x % 64);
            ++row.filled7x7;
        } else {
            outcome[at(x, y)] = kUnfilled;
            ++row.unfilled;
        }
    });
    row.prefilterSamplesRead += sparseReads;
    row.samplesRead += row.prefilterSamplesRead;
    perRow[static_cast<std::size_t>(y)] = row;
    if (onFilled && row.filled7x7 > filledBefore) (*onFilled)(y, columns.filledBits.data());
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
    // Counts per row go to a local, written once (no false sharing).
    // Bands of rows, so that a worker reads each image row once for the
    // three rows of holes that need it.
    std::vector<Fill3x3Scratch> fill3x3PerWorker(static_cast<std::size_t>(parallel.threadCount()));
    constexpr int kBandRows = 16;
    parallel.forEachIndex((height + kBandRows - 1) / kBandRows, [&](int band, int worker) {
        Fill3x3Scratch& rows = fill3x3PerWorker[static_cast<std::size_t>(worker)];
        for (int y = band * kBandRows; y < std::min(height, (band + 1) * kBandRows); ++y) fill.fill3x3Row(y, rows);
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
        total.prefilterSamplesRead += c.prefilterSamplesRead;
    }
    for (unsigned char h : fill.hasHoles) total.rowsWithHoles += h;
    return total;
}

}  // namespace raycache
