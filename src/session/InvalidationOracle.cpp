#include "session/InvalidationOracle.h"

#include "render/TileKernel.h"

#include <algorithm>
#include <cmath>

namespace raycache {

namespace {

bool withinTolerance(std::uint32_t word, std::uint32_t other) {
    const Rgb a = CachingCube::decodeTexel(word), b = CachingCube::decodeTexel(other);
    return std::max({std::fabs(a.r - b.r), std::fabs(a.g - b.g), std::fabs(a.b - b.b)}) <= InvalidationCounts::kTolerance;
}

}  // namespace

InvalidationCounts& InvalidationCounts::operator+=(const InvalidationCounts& o) {
    checked += o.checked;
    kept += o.kept;
    stale += o.stale;
    dropped += o.dropped;
    needless += o.needless;
    differing += o.differing;
    differingBeyondTolerance += o.differingBeyondTolerance;
    movedCube += o.movedCube;
    movedCubeWithinTolerance += o.movedCubeWithinTolerance;
    movedCubeKept += o.movedCubeKept;
    return *this;
}

void InvalidationOracle::take(const RenderSession& session) {
    texels_.clear();
    const RayCache& cache = session.cache();
    cubeCenters_.assign(session.scene().objects.size(), Vec3{});
    for (int object = 0; object < static_cast<int>(session.scene().objects.size()); ++object) {
        if (!cache.cachesObject(object)) continue;
        const CachingCube& cube = cache.cube(object);
        cubeCenters_[static_cast<std::size_t>(object)] = cube.center();
        for (int t = 0; t < static_cast<int>(cube.texelCount()); ++t)
            if (cube.isValid(t))
                texels_.push_back({object, t, cube.texels()[static_cast<std::size_t>(t)], cache.storedTree(object, t)});
    }
    const std::vector<std::uint32_t> same = retrace(session);
    differing_ = differingBeyondTolerance_ = 0;
    for (std::size_t i = 0; i < texels_.size(); ++i) {
        if (same[i] == texels_[i].word) continue;
        ++differing_;
        if (!withinTolerance(same[i], texels_[i].word)) ++differingBeyondTolerance_;
    }
}

InvalidationCounts InvalidationOracle::check(const RenderSession& session) const {
    InvalidationCounts counts;
    counts.differing = differing_;
    counts.differingBeyondTolerance = differingBeyondTolerance_;
    const std::vector<std::uint32_t> now = retrace(session);
    for (std::size_t i = 0; i < texels_.size(); ++i) {
        const CachingCube& cube = session.cache().cube(texels_[i].objectId);
        const bool kept = cube.isValid(texels_[i].texel);
        const bool unchanged = now[i] == texels_[i].word;
        ++counts.checked;
        if (!(cube.center() == cubeCenters_[static_cast<std::size_t>(texels_[i].objectId)])) {
            ++counts.movedCube;
            if (withinTolerance(now[i], texels_[i].word)) ++counts.movedCubeWithinTolerance;
            if (kept) ++counts.movedCubeKept;
        }
        if (kept) {
            ++counts.kept;
            if (!unchanged) ++counts.stale;
        } else {
            ++counts.dropped;
            if (unchanged) ++counts.needless;
        }
    }
    return counts;
}

std::vector<std::uint32_t> InvalidationOracle::retrace(const RenderSession& session) const {
    const TileKernel kernel(session.scene(), session.tracer(), session.settings(), nullptr);
    std::vector<RayTreeRecord> rays;
    rays.reserve(texels_.size());
    for (const StoredTexel& t : texels_) {
        rays.push_back(t.tree);
        // A caching object that moved took its cube along: its texels now
        // stand for rays leaving it where it is.
        if (!cubeCenters_.empty())
            rays.back().origin += session.cache().cube(t.objectId).center() -
                                  cubeCenters_[static_cast<std::size_t>(t.objectId)];
    }
    std::vector<Rgb> colors(rays.size());
    // In slices, so the kernel's per-ray buffers stay small.
    constexpr std::size_t kSlice = 4096;
    TileScratch scratch;
    for (std::size_t begin = 0; begin < rays.size(); begin += kSlice) {
        const std::size_t count = std::min(kSlice, rays.size() - begin);
        kernel.renderRays(std::span(rays).subspan(begin, count), std::span(colors).subspan(begin, count), scratch);
    }
    std::vector<std::uint32_t> words;
    words.reserve(colors.size());
    for (const Rgb& c : colors) words.push_back(CachingCube::encodeTexel(c));
    return words;
}

}  // namespace raycache
