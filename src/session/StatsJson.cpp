#include "session/StatsJson.h"

#include <vector>

namespace raycache {

namespace {

nlohmann::json cacheJson(const FrameCacheStats& c) {
    nlohmann::json objects = nlohmann::json::array();
    for (const ObjectCacheStats& o : c.objects)
        objects.push_back({{"object", o.name}, {"resolution", o.resolution}, {"resized_to", o.resizedTo},
                           {"lookups", o.lookups},
                           {"hits", o.hits}, {"misses", o.misses}, {"rejected", o.rejected},
                           {"own_surface", o.ownSurface}, {"view_dependent", o.viewDependent},
                           {"stores", o.stores}, {"stores_skipped", o.skippedStores},
                           {"prefilled_texels", o.prefilledTexels},
                           {"levels", o.levels},
                           {"hits_by_level", std::vector<std::uint64_t>(o.hitsByLevel.begin(), o.hitsByLevel.begin() + o.levels)},
                           {"cdct_searches", o.cdctSearches}, {"cdct_steps", o.cdctSteps},
                           {"cdct_steps_histogram", o.cdctStepsHistogram},
                           {"invalid_percent_before", o.invalidPercentBefore}, {"bytes", o.bytes},
                           // The cache policy (docs/caching.md, "Caching that never costs").
                           {"policy", {{"state", cubeStateName(o.state)},
                                       {"next", cubeStateName(o.next)},
                                       {"bypassed_rays", o.bypassedRays}, {"stores_queued", o.queuedStores},
                                       {"region_tests", o.regionTests},
                                       {"frames_caching", o.framesCaching}, {"frames_sampling", o.framesSampling},
                                       {"frames_bypassed", o.framesBypassed},
                                       {"mean_tree_rays", o.meanTree}, {"saving_rays", o.policySaving},
                                       {"cost_rays", o.policyCost}}}});
    return {{"lookups", c.lookups()}, {"hits", c.hits()}, {"misses", c.misses()}, {"rejected", c.rejected()},
            {"own_surface", c.ownSurface()}, {"view_dependent", c.viewDependent()}, {"stores", c.stores()}, {"stores_skipped", c.skippedStores()}, {"prefilled_texels", c.prefilledTexels()},
            {"bypassed_cubes", c.bypassedCubes()}, {"sampling_cubes", c.samplingCubes()}, {"bypassed_rays", c.bypassedRays()}, {"traced_as_uncached", c.tracedAsUncached},
            {"invalid_percent_before", c.invalidPercentBefore()}, {"bytes", c.bytes()}, {"objects", objects}};
}

nlohmann::json phasesJson(const PhaseTimes& p) {
    return {{"raster_ms", p.raster}, {"readback_ms", p.readback}, {"shadows_ms", p.shadows},
            {"secondary_ms", p.secondary}, {"compose_ms", p.compose}};
}

nlohmann::json sceneUpdateJson(const SceneUpdateStats& u) {
    return {{"ms", u.milliseconds},           {"pose_ms", u.poseMs},
            {"tracer_ms", u.tracerMs},        {"cache_ms", u.cacheMs},
            {"objects_changed", u.objectsChanged}, {"lights_changed", u.lightsChanged},
            {"texels_invalidated", u.texelsInvalidated}};
}

nlohmann::json gridsJson(const FrameTraceStats& g, double buildMs) {
    return {{"build_ms", buildMs},
            {"primary_build_ms", g.build.primaryBuildMs},
            {"shadow_build_ms", g.build.shadowBuildMs},
            {"primary_pairs", g.build.primaryPairs},
            {"shadow_pairs", g.build.shadowPairs},
            {"light_grids", g.build.lightGrids},
            {"lights_with_six_faces", g.build.lightsWithSixFaces},
            {"primary_answered", g.primaryAnswered},
            {"primary_refused", g.primaryRefused},
            {"shadow_answered", g.shadowAnswered},
            {"shadow_refused", g.shadowRefused}};
}

nlohmann::json clusterJson(const ClusterStats& c) {
    return {{"processes", c.processes},         {"assignment", c.assignment},
            {"tiles_per_process", c.tilesPerProcess}, {"imbalance", c.imbalance},
            {"store_bytes", c.storeBytes},        {"prefill_bytes", c.prefillBytes},
            {"image_bytes", c.imageBytes},        {"control_bytes", c.controlBytes},
            {"bytes", c.storeBytes + c.prefillBytes + c.imageBytes + c.controlBytes}};
}

}  // namespace

nlohmann::json stagesJson(const StageTimes& s) {
    return {{"first_hits_cpu_ms", s.firstHits},     {"surfaces_cpu_ms", s.surfaces},
            {"shadow_rays_cpu_ms", s.shadowRays},   {"direct_shading_cpu_ms", s.directShading},
            {"secondary_rays_cpu_ms", s.secondaryRays}, {"reuse_lookups_cpu_ms", s.reuseLookups},
            {"trace_secondary_cpu_ms", s.traceSecondary}, {"resolve_cpu_ms", s.resolve},
            {"compose_cpu_ms", s.compose},          {"visible_fill_cpu_ms", s.visibleFill},
            {"cache_frame_end_ms", s.cacheFrameEnd}, {"hits_shaded", s.hitsShaded}};
}

nlohmann::json toJson(const BuildInfo& b) {
    return {{"raycache", b.raycacheVersion}, {"git_commit", b.gitCommit},
            {"build_type", b.buildType},     {"compiler", b.compiler},
            {"embree", b.embreeVersion},     {"embree_instructions", b.embreeInstructions},
            {"tbb", b.tbbVersion},
            {"assimp", b.assimpVersion},     {"openexr", b.openExrVersion},
            {"lanes", b.lanes},              {"baseline_lanes_build", b.baselineLanesBuild}};
}

nlohmann::json raysJson(const RayCounts& r) {
    return {{"primary", r.primary}, {"shadow", r.shadow}, {"reflection", r.reflection},
            {"refraction", r.refraction}, {"prefill", r.prefill}, {"fill", r.fill}, {"total", r.total()}};
}

nlohmann::json renderCacheStatsJson(const RenderCacheStats& s) {
    return {{"reproject_ms", s.reprojectMs}, {"maps_ms", s.mapsMs}, {"filter_ms", s.filterMs},
            {"reconstruction_ms", s.reconstructionMs()}, {"trace_ms", s.traceMs}, {"reshade_ms", s.reshadeMs},
            {"sample_generation_ms", s.sampleGenerationMs()}, {"pixels", s.pixels}, {"budget", s.budget},
            {"fresh", s.fresh}, {"predicted", s.predicted}, {"reprojected", s.reprojected},
            {"reshaded", s.reshaded}, {"culled", s.culled}, {"holes", s.holes}, {"filled_3x3", s.filled3x3},
            {"filled_7x7", s.filled7x7}, {"unfilled", s.unfilled}, {"evicted", s.evicted}, {"lost", s.lost},
            {"live_samples", s.liveSamples}, {"refreshed_all", s.refreshedAll},
            {"counted_bytes", countedBytesJson(s)}, {"counted_gb_per_s", countedGbPerSecondJson(s)}};
}

nlohmann::json countedBytesJson(const RenderCacheStats& s) {
    return {{"first_round", s.firstRoundBytes},
            {"copy", s.copyBytes},
            {"holes", s.holesBytes},
            {"request_maps", s.requestMapBytes},
            {"fills", s.fillBytes},
            {"reproject", s.reprojectBytes()},
            {"maps", s.mapsBytes()},
            {"filter", s.filterBytes()},
            {"reconstruction", s.reconstructionBytes()}};
}

nlohmann::json countedGbPerSecondJson(const RenderCacheStats& s) {
    return {{"reproject", s.reprojectGbPerSecond()},
            {"maps", s.mapsGbPerSecond()},
            {"filter", s.filterGbPerSecond()},
            {"reconstruction", s.reconstructionGbPerSecond()}};
}

nlohmann::json frameStatsJson(const FrameResult& r) {
    const RayCounts& rays = r.stats.rays;
    const double mrays = static_cast<double>(rays.total()) / (r.milliseconds * 1e3);
    nlohmann::json frame = {{"frame", r.frame + 1}, {"ms", r.milliseconds}, {"rays", raysJson(rays)},
                            {"mrays_per_s", mrays}};
    if (r.stats.cache) frame["cache"] = cacheJson(*r.stats.cache);
    if (r.stats.phases) frame["phases"] = phasesJson(*r.stats.phases);
    if (r.stats.stages) frame["stages"] = stagesJson(*r.stats.stages);
    if (r.stats.trace) frame["grids"] = gridsJson(*r.stats.trace, r.stats.gridBuildMs);
    if (r.stats.renderCache) frame["render_cache"] = renderCacheStatsJson(*r.stats.renderCache);
    if (r.stats.cluster) frame["cluster"] = clusterJson(*r.stats.cluster);
    if (r.stats.sceneUpdate) frame["scene_update"] = sceneUpdateJson(*r.stats.sceneUpdate);
    return frame;
}

}  // namespace raycache
