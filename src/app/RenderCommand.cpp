#include "app/RenderCommand.h"

#include <algorithm>
#include <optional>
#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "app/FramePathPattern.h"
#include "app/OutputDirectory.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "core/Parallel.h"
#include "core/ProcessAgreement.h"
#include "core/SampleSummary.h"
#include "render/ImageWriter.h"
#include "session/BuildInfo.h"
#include "session/FrameLoop.h"
#include "session/FrameParallelLoop.h"
#include "session/FrameReport.h"
#include "session/StatsJson.h"

namespace raycache {

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
            writeImage(film, outPattern.pathFor(r.frame + 1), job.display);
        if (options.statsPath.empty()) return;  // the statistics are only for --stats
        nlohmann::json frameJson = frameStatsJson(r);
        if (r.stats.sceneUpdate) frameJson["time"] = job.timeline.timeOf(r.frame);
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
