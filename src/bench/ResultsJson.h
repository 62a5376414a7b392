#pragma once
// The pieces every experiment's results.json is made of, so they all record
// settings, environment, timings and the documents' figures the same way
// (render statistics: session/StatsJson.h, shared with `raycache render --stats`).
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bench/InterleavedRuns.h"
#include "bench/PaperFigures.h"
#include "bench/RunEnvironment.h"
#include "bench/SpeedupInterval.h"
#include "session/StatsJson.h"

namespace raycache {

// The machine and its load, with the build as "version".
nlohmann::json toJson(const RunEnvironment& environment);
// Every timed and warm-up frame in ms, with median, min, max and the median frame rate.
nlohmann::json toJson(const VariantTimes& times);
nlohmann::json toJson(const PaperTable& table);
// {"speedup", "ci95_low", "ci95_high" (null when unknown), "pairs",
// "relative_half_width", "no_measurable_difference"}.
nlohmann::json toJson(const SpeedupInterval& s);
// JSON has no infinity or NaN: such values (e.g. the PSNR of identical
// images) become null.
nlohmann::json finiteOrNull(double value);

// Writes `json` (indented) to `path` atomically.
void writeJsonFile(const std::filesystem::path& path, const nlohmann::json& json);

}  // namespace raycache
