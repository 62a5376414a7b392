#include "app/RenderCommand.h"

#include <algorithm>
#include <optional>
#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "app/FramePathPattern.h"
#include "app/OutputDirectory.h"
#include "session/BuildInfo.h"
#include "bench/ResultsJson.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "core/Parallel.h"
#include "core/ProcessAgreement.h"
#include "core/SampleSummary.h"
#include "render/ImageWriter.h"
#include "session/FrameLoop.h"
#include "session/FrameParallelLoop.h"
#include "session/FrameReport.h"

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

nlohmann::json renderCacheJson(const RenderCacheStats& s) {
    return {{"reproject_ms", s.reprojectMs}, {"maps_ms", s.mapsMs}, {"filter_ms", s.filterMs},
            {"reconstruction_ms", s.reconstructionMs()}, {"trace_ms", s.traceMs}, {"reshade_ms", s.reshadeMs},
            {"sample_generation_ms", s.sampleGenerationMs()}, {"pixels", s.pixels}, {"budget", s.budget},
            {"fresh", s.fresh}, {"predicted", s.predicted}, {"reprojected", s.reprojected},
            {"reshaded", s.reshaded}, {"culled", s.culled}, {"holes", s.holes}, {"filled_3x3", s.filled3x3},
            {"filled_7x7", s.filled7x7}, {"unfilled", s.unfilled}, {"evicted", s.evicted}, {"lost", s.lost},
            {"live_samples", s.liveSamples}, {"refreshed_all", s.refreshedAll},
            {"counted_bytes", countedBytesJson(s)}, {"counted_gb_per_s", countedGbPerSecondJson(s)}};
}

nlohmann::json stagesJson(const StageTimes& s) {
    return {{"first_hits_cpu_ms", s.firstHits},     {"surfaces_cpu_ms", s.surfaces},
            {"shadow_rays_cpu_ms", s.shadowRays},   {"direct_shading_cpu_ms", s.directShading},
            {"secondary_rays_cpu_ms", s.secondaryRays}, {"reuse_lookups_cpu_ms", s.reuseLookups},
            {"trace_secondary_cpu_ms", s.traceSecondary}, {"resolve_cpu_ms", s.resolve},
            {"compose_cpu_ms", s.compose},          {"visible_fill_cpu_ms", s.visibleFill},
            {"cache_frame_end_ms", s.cacheFrameEnd}, {"hits_shaded", s.hitsShaded}};
}

nlohmann::json clusterJson(const ClusterStats& c) {
    return {{"processes", c.processes},         {"assignment", c.assignment},
            {"tiles_per_process", c.tilesPerProcess}, {"imbalance", c.imbalance},
            {"store_bytes", c.storeBytes},        {"prefill_bytes", c.prefillBytes},
            {"image_bytes", c.imageBytes},        {"control_bytes", c.controlBytes},
            {"bytes", c.storeBytes + c.prefillBytes + c.imageBytes + c.controlBytes}};
}

nlohmann::json raysJson(const RayCounts& r) {
    return {{"primary", r.primary}, {"shadow", r.shadow}, {"reflection", r.reflection},
            {"refraction", r.refraction}, {"prefill", r.prefill}, {"fill", r.fill}, {"total", r.total()}};
}

}  // namespace

void runRenderCommand(const RenderCommandOptions& options, std::ostream& out, std::ostream& notes,
                      const ProcessGroup& group) {
    std::optional<FramePathPattern> outPatternOrNone;
    std::optional<RenderJob> preparedJob;
    bool wholeFrames = false;
    // Every process loads the scene; a failure on any of them stops all.
    runOnEveryProcess(group, [&] {
        validateRenderJobOptions(options.job);
        outPatternOrNone.emplace(options.out);
        preparedJob.emplace(prepareRenderJob(options.job));
        if (group.size() > 1) {
            wholeFrames = preparedJob->frames > 1 && framesAreIndependent(preparedJob->scene, preparedJob->settings);
            if (!wholeFrames && preparedJob->settings.pipeline != PipelineKind::Ray)
                throw InputError(std::string("--pipeline ") + pipelineKindName(preparedJob->settings.pipeline) +
                                 " cannot share a frame's tiles among MPI processes; use --pipeline ray, or caches "
                                 "off with several frames (whole frames per process; docs/cluster.md)");
        }
        // Only now that the input is known to be good: no directories left behind by a failed run.
        if (!group.isRoot()) return;
        if (!options.out.empty()) {
            createParentDirectories(outPatternOrNone->pathFor(1));
            checkWritableImagePath(outPatternOrNone->pathFor(1));
        }
        if (!options.statsPath.empty()) createParentDirectories(options.statsPath);
    });
    const FramePathPattern& outPattern = *outPatternOrNone;
    const RenderJob& job = *preparedJob;
    const bool writesFiles = group.isRoot();

    const Scene& scene = job.scene;
    const RenderSettings& settings = job.settings;
    const int frames = job.frames;
    if (group.isRoot()) printSceneNotes(scene, notes);

    out << "scene " << scene.name << ": " << scene.objects.size() << " objects, " << scene.lights.size()
        << " lights, " << settings.width << "x" << settings.height << ", " << frames << " frames\n";
    if (group.size() > 1)
        out << "cluster: " << group.size() << " MPI processes, "
            << (wholeFrames ? "whole frames per process (caches off)"
                            : std::string("tiles of every frame shared (") + tileBalanceName(settings.tileBalance) +
                                  " balance), cache stores exchanged")
            << "\n";
    if (!job.cacheBudgetNote.empty()) out << "note: " << job.cacheBudgetNote << "\n";
    if (settings.threads > Parallel::hardwareThreads())
        out << "note: --threads " << settings.threads << " is more than the " << Parallel::hardwareThreads()
            << " hardware threads; using " << Parallel::hardwareThreads() << "\n";

    std::vector<double> times;
    nlohmann::json frameStats = nlohmann::json::array();
    RayCounts totalRays;
    std::string pipelineLine;
    const auto onPipeline = [&](const std::string& description) {
        pipelineLine = description;
        out << description << "\n";
    };
    const auto onFrame = [&](const FrameResult& r, const Image& film, const RayCache&) {
        const RayCounts& rays = r.stats.rays;
        out << formatFrameLine(r, frames) << std::endl;
        times.push_back(r.milliseconds);
        totalRays += rays;
        const bool lastFrame = r.frame + 1 == frames;
        // Files count from 1 like the progress lines: "frame 1/N" is _0001.
        if (writesFiles && !options.out.empty() && (outPattern.perFrame() || lastFrame))
            writeImage(film, outPattern.pathFor(r.frame + 1));
        if (options.statsPath.empty()) return;  // the statistics are only for --stats
        const double mrays = static_cast<double>(rays.total()) / (r.milliseconds * 1e3);
        nlohmann::json frameJson = {{"frame", r.frame + 1}, {"ms", r.milliseconds}, {"rays", raysJson(rays)},
                                    {"mrays_per_s", mrays}};
        if (r.stats.cache) frameJson["cache"] = cacheJson(*r.stats.cache);
        if (r.stats.phases) frameJson["phases"] = phasesJson(*r.stats.phases);
        if (r.stats.stages) frameJson["stages"] = stagesJson(*r.stats.stages);
        if (const auto& g = r.stats.trace)
            frameJson["grids"] = {{"build_ms", r.stats.gridBuildMs},
                                  {"primary_build_ms", g->build.primaryBuildMs},
                                  {"shadow_build_ms", g->build.shadowBuildMs},
                                  {"primary_pairs", g->build.primaryPairs},
                                  {"shadow_pairs", g->build.shadowPairs},
                                  {"light_grids", g->build.lightGrids},
                                  {"lights_with_six_faces", g->build.lightsWithSixFaces},
                                  {"primary_answered", g->primaryAnswered},
                                  {"primary_refused", g->primaryRefused},
                                  {"shadow_answered", g->shadowAnswered},
                                  {"shadow_refused", g->shadowRefused}};
        if (r.stats.renderCache) frameJson["render_cache"] = renderCacheJson(*r.stats.renderCache);
        if (r.stats.cluster) frameJson["cluster"] = clusterJson(*r.stats.cluster);
        if (r.stats.sceneUpdate) {
            frameJson["time"] = job.timeline.timeOf(r.frame);
            frameJson["scene_update"] = sceneUpdateJson(*r.stats.sceneUpdate);
        }
        frameStats.push_back(std::move(frameJson));
    };
    if (wholeFrames) {
        const auto needsFilm = [&](int frame) {
            return !options.out.empty() && (outPattern.perFrame() || frame + 1 == frames);
        };
        renderFramesAcrossProcesses(scene, job.path, settings, frames, group, onFrame, needsFilm, onPipeline,
                                    job.timeline);
    } else {
        renderFrames(scene, job.path, settings, frames, onFrame, onPipeline, job.timeline, &group);
    }
    // Process 0 alone saw the frames (the others' statistics are partial).
    if (!group.isRoot()) return;

    const SampleSummary summary = summarize(times);
    out << "median " << formatFixed(summary.median, 1) << " ms (min " << formatFixed(summary.min, 1) << ", max "
        << formatFixed(summary.max, 1) << ") over " << frames << " frames\n";
    if (!options.statsPath.empty()) {
        const nlohmann::json stats = {
            {"version", toJson(currentBuildInfo())},
            {"scene", scene.name},
            {"width", settings.width},
            {"height", settings.height},
            {"max_depth", settings.maxDepth},
            {"min_weight", settings.minWeight},
            // What ran, not what was asked: Parallel clamps to the hardware threads.
            {"threads", Parallel(settings.threads).threadCount()},  // per process
            {"processes", group.size()},
            {"threads_requested", settings.threads},  // 0 = all
            {"pipeline", pipelineKindName(settings.pipeline)},
            {"pipeline_description", pipelineLine},
            {"frames", frameStats},
            {"summary", {{"median_ms", summary.median}, {"min_ms", summary.min}, {"max_ms", summary.max},
                         {"rays", raysJson(totalRays)}}}};
        writeTextFileAtomically(options.statsPath, stats.dump(2) + "\n");
    }
}

}  // namespace raycache
