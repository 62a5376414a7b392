#pragma once
// Render statistics as JSON: one writer for `raycache render --stats` and
// the bench's results.json, so that both name and shape every field alike.
#include <nlohmann/json.hpp>

#include "core/RayCounts.h"
#include "render/RenderCacheStats.h"
#include "session/BuildInfo.h"
#include "session/FrameLoop.h"

namespace raycache {

// The "version" object: what ran (BuildInfo).
nlohmann::json toJson(const BuildInfo& build);
// {"primary", "shadow", "reflection", "refraction", "prefill", "fill", "total"}.
nlohmann::json raysJson(const RayCounts& rays);
// The tile kernel's stages in one frame (render/FrameStats.h StageTimes):
// each stage's CPU ms ("first_hits_cpu_ms", …, "cache_frame_end_ms", wall
// time) and "hits_shaded".
nlohmann::json stagesJson(const StageTimes& stages);
// A Render Cache frame: its times (ms), sample counts, the budget and the
// counted bytes with their rates.
nlohmann::json renderCacheStatsJson(const RenderCacheStats& s);
// A Render Cache frame's counted bytes (RenderCacheStats; a model, not
// measured traffic: rendercache/ReconstructionBytes.h): per pass
// ("first_round", "copy", "holes", "request_maps", "fills"), per timed step
// ("reproject", "maps", "filter") and "reconstruction".
nlohmann::json countedBytesJson(const RenderCacheStats& s);
// The counted bytes over the wall time of each timed step and of
// reconstruction, GB/s (0 where the time is 0).
nlohmann::json countedGbPerSecondJson(const RenderCacheStats& s);
// One frame: "frame" (from 1), "ms", "rays", "mrays_per_s", and, where the
// frame has them, "cache", "phases", "stages", "grids", "render_cache",
// "cluster" and "scene_update".
nlohmann::json frameStatsJson(const FrameResult& r);

}  // namespace raycache
