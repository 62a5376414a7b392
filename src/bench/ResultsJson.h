#pragma once
// The pieces every experiment's results.json is made of, so they all record
// settings, environment, timings and the documents' figures the same way.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bench/InterleavedRuns.h"
#include "bench/PaperFigures.h"
#include "bench/RunEnvironment.h"
#include "bench/SpeedupInterval.h"
#include "render/RenderCacheStats.h"

namespace raycache {

// The "version" object, the same in results.json and `raycache render --stats`.
nlohmann::json toJson(const BuildInfo& build);
// The machine and its load, with the build as "version".
nlohmann::json toJson(const RunEnvironment& environment);
// Every timed and warm-up frame in ms, with median, min, max and the median frame rate.
nlohmann::json toJson(const VariantTimes& times);
nlohmann::json toJson(const PaperTable& table);
// {"speedup", "ci95_low", "ci95_high" (null when unknown), "pairs",
// "relative_half_width", "no_measurable_difference"}.
nlohmann::json toJson(const SpeedupInterval& s);
// A Render Cache frame's counted bytes (RenderCacheStats; a model, not
// measured traffic: rendercache/ReconstructionBytes.h), the same in
// results.json and `raycache render --stats`: per pass ("first_round",
// "copy", "holes", "request_maps", "fills"), per timed step ("reproject",
// "maps", "filter") and "reconstruction".
nlohmann::json countedBytesJson(const RenderCacheStats& s);
// The counted bytes over the wall time of each timed step and of
// reconstruction, GB/s (0 where the time is 0).
nlohmann::json countedGbPerSecondJson(const RenderCacheStats& s);
// JSON has no infinity or NaN: such values (e.g. the PSNR of identical
// images) become null.
nlohmann::json finiteOrNull(double value);

// Writes `json` (indented) to `path` atomically.
void writeJsonFile(const std::filesystem::path& path, const nlohmann::json& json);

}  // namespace raycache
