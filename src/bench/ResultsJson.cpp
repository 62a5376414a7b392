#include "bench/ResultsJson.h"

#include <cmath>

#include "core/AtomicFile.h"
#include "core/SampleSummary.h"

namespace raycache {

nlohmann::json toJson(const RunEnvironment& e) {
    return {{"cpu_model", e.cpuModel},           {"hardware_threads", e.hardwareThreads},
            {"worker_threads", e.workerThreads}, {"os", e.os},
            {"version", toJson(e.build)},        {"started_at", e.startedAt},
            {"load_average_at_start", e.loadAverage}};
}

nlohmann::json toJson(const VariantTimes& t) {
    const SampleSummary s = summarize(t.milliseconds);
    return {{"frame_ms", t.milliseconds},
            {"warmup_ms", t.warmupMilliseconds},
            {"median_ms", s.median},
            {"min_ms", s.min},
            {"max_ms", s.max},
            {"fps_median", finiteOrNull(s.median > 0.0 ? 1000.0 / s.median : 0.0)}};
}

nlohmann::json toJson(const PaperTable& table) {
    nlohmann::json rows = nlohmann::json::array();
    for (const PaperRow& r : table.rows) {
        nlohmann::json row = {{"label", r.label}};
        for (std::size_t c = 0; c < table.columns.size() && c < r.values.size(); ++c)
            row[table.columns[c]] = r.values[c];
        rows.push_back(std::move(row));
    }
    return {{"source", table.source}, {"conditions", table.conditions}, {"rows", rows}};
}

nlohmann::json toJson(const SpeedupInterval& s) {
    return {{"speedup", finiteOrNull(s.speedup)},
            {"ci95_low", finiteOrNull(s.low)},
            {"ci95_high", finiteOrNull(s.high)},
            {"pairs", s.pairs},
            {"relative_half_width", finiteOrNull(s.relativeHalfWidth())},
            {"no_measurable_difference", s.containsOne()}};
}

nlohmann::json finiteOrNull(double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

void writeJsonFile(const std::filesystem::path& path, const nlohmann::json& json) {
    writeTextFileAtomically(path, json.dump(2) + "\n");
}

}  // namespace raycache
