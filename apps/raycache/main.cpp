// raycache command line: parses arguments and hands them to the library.
#include <CLI/CLI.hpp>
#include <iostream>
#include <optional>
#include <ostream>

#include "ChoiceOption.h"
#include "app/BenchCommand.h"
#include "app/CacheViewCommand.h"
#include "app/DiffCommand.h"
#include "app/RenderCommand.h"
#include "app/ScenesCommand.h"
#include "app/ViewCommand.h"
#include "cluster/ClusterRuntime.h"
#include "core/Errors.h"
#include "core/ProcessAgreement.h"
#include "core/FreedMemory.h"
#include "core/ProgressBar.h"
#include "core/TextFormat.h"
#include "core/ViewTransform.h"
#include "render/RenderCacheSettings.h"
#include "render/VisibleSurfaceFill.h"
#include "scene/CacheTechnique.h"
#include "scene/Material.h"
#include "session/BuildInfo.h"

namespace {

// The --rc-* options, their defaults read from RenderCacheSettings.
void addRenderCacheOptions(CLI::App& command, raycache::RenderJobOptions& job) {
    const raycache::RenderCacheSettings defaults;
    const auto number = [](float value) { return raycache::formatShortestFloat(value); };
    // " the default" after the choice that is the default.
    const auto theDefault = [](bool isDefault) { return isDefault ? std::string("; the default") : std::string(); };
    command.add_option("--rc-budget", job.renderCache.budget,
                       "Render cache: share of the pixels traced per frame, (0, 1] (default " + number(defaults.budget) +
                           ")");
    command.add_option("--rc-target-ms", job.renderCache.targetFrameMs,
                       "Render cache: choose the budget each frame to hold this frame time, ms (0 = off; images "
                       "then depend on the machine's speed; default " +
                           number(defaults.targetFrameMs) + (defaults.targetFrameMs == 0.0f ? " = off)" : ")"));
    command.add_option("--rc-alpha", job.renderCache.alpha,
                       "Render cache: request map mix, (1-alpha) uniform + alpha priority, [0, 1] (default " +
                           number(defaults.alpha) + ")");
    command.add_option("--rc-max-age", job.renderCache.maxAge,
                       "Render cache: frames a sample lives (default " + std::to_string(defaults.maxAge) + ")");
    command.add_option("--rc-predict", job.renderCache.predictShare,
                       "Render cache: share of the budget for holes the predicted next camera will see, [0, 0.9] "
                       "(default " +
                           number(defaults.predictShare) + ")");
    raycache::addChoiceOption(
        command, "--rc-reflections", job.renderCache.reflections, raycache::kReprojectedReflections,
        raycache::reprojectedReflectionsName,
        "Render cache: reprojected mirror/glass/glossy samples: reshade (highlights and reflections from the new eye, "
        "through the caching cubes" +
            theDefault(defaults.reflections == raycache::ReprojectedReflections::Reshade) + ") or reproject (as traced" +
            theDefault(defaults.reflections == raycache::ReprojectedReflections::Reproject) + ")");
    command.add_option("--rc-reshade-every", job.renderCache.reshadeInterval,
                       "Render cache: a moving frame reshades one in N reprojected mirror/glass/glossy samples, each "
                       "in turn; the first still frame the rest, 1.." +
                           std::to_string(raycache::kMaxReshadeInterval) + " (default " +
                           std::to_string(defaults.reshadeInterval) + ": all, every frame)");
    raycache::addChoiceOption(command, "--rc-texture", job.renderCache.textureRefetch, raycache::kTextureRefetchValues,
                              raycache::textureRefetchName,
                              "Render cache: reprojected textured samples: refetch (the albedo where the pixel's "
                              "centre meets the sample's primitive" +
                                  theDefault(defaults.textureRefetch) + ") or reproject (as traced" +
                                  theDefault(!defaults.textureRefetch) + ")");
    command.add_option("--rc-seed", job.renderCache.seed,
                       "Render cache: seed of the request map's random choices (default " +
                           std::to_string(defaults.seed) + ")");
    command.add_option("--rc-margin", job.renderCache.margin,
                       "Render cache: samples kept past each image edge, share of the side, [0, 0.5] (default " +
                           number(defaults.margin) + ")");
    command.add_option("--rc-depth-cull", job.renderCache.depthCullThreshold,
                       "Render cache: depth culling hides a sample whose neighbours are nearer by this share of its "
                       "depth, [0, 1] (0 = off; default " +
                           number(defaults.depthCullThreshold) + ")");
    command.add_option("--rc-tile", job.renderCache.requestTileSize,
                       "Render cache: side of the hole-detection and request-map tiles, pixels, 1..256 (default " +
                           std::to_string(defaults.requestTileSize) + ")");
}

// The options every rendering command shares: what to render and how.
void addRenderJobOptions(CLI::App& command, raycache::RenderJobOptions& job) {
    command.add_option("--scene", job.scene, "Built-in scene name (see `raycache scenes`), scene .json file, or glTF 2.0 scene (.gltf, .glb)")
        ->capture_default_str();
    command
        .add_option_function<std::string>(
            "--gltf-materials",
            [&job](const std::string& mapping) { job.blinnPhongGltfMaterials = mapping == "blinn-phong"; },
            "glTF scenes: metallic-roughness (glTF's BRDF, default) or blinn-phong (the Whitted mapping, for "
            "comparisons)")
        ->check(CLI::IsMember({"metallic-roughness", "blinn-phong"}));
    command.add_option("--width", job.width, "Image width in pixels")->capture_default_str();
    command.add_option("--height", job.height, "Image height in pixels")->capture_default_str();
    command.add_option("--frames", job.frames, "Frames to render (default: the scene's path length)");
    raycache::addChoiceOption(command, "--path", job.path, raycache::kPathOptionKinds, raycache::cameraPathKindName,
                              "Camera path: static, orbit or pan (default: the scene's own)");
    command.add_option("--time", job.time,
                       "Animated scenes: the time in seconds the first frame shows; frame f shows time + f / fps")
        ->capture_default_str();
    command.add_option("--fps", job.fps, "Animated scenes: frames per second of animation time (default: the scene's, 30)");
    command.add_option("--threads", job.threads, "Worker threads, 0 = all cores")->capture_default_str();
    command.add_option("--spp", job.samplesPerPixel,
                       "Camera rays per pixel, 1..4096: 1 = one ray through each pixel's centre; N > 1 = stratified "
                       "jittered rays from a fixed sequence, filtered with Blackman-Harris 1.5 px as Cycles does "
                       "(ray pipeline only; images do not depend on the thread count; `view` refines a still view to N, one "
                       "sample layer a frame; docs/usage.md)")
        ->capture_default_str();
    command.add_option("--exposure", job.exposure,
                       "Exposure of PNG images and the viewer, in stops: the light is multiplied by 2^EV before the "
                       "view transform; EXR images stay scene-linear (default: the scene file's exposure, else 0)");
    raycache::addChoiceOption(
        command, "--view-transform", job.viewTransform, raycache::kViewTransforms, raycache::viewTransformName,
        "How PNG images and the viewer show light: standard (clamp to [0, 1], then sRGB: Blender's Standard), "
        "filmic (Blender 3's Filmic, base contrast), agx (Blender 4's AgX), khronos-pbr-neutral (docs/usage.md; "
        "default: the scene file's viewTransform, else standard)");
    command.add_option("--max-depth", job.maxDepth, "Longest ray path (primary ray = 1)")->capture_default_str();
    command.add_option("--min-weight", job.minWeight,
                       "Stop a path when the product of its ray weights (kr, kt; glTF: Fresnel's, largest "
                       "channel) falls below this")
        ->capture_default_str();
    raycache::addChoiceOption(
        command, "--technique", job.technique,
        raycache::kCacheTechniqueValues, raycache::cacheTechniqueName,
        "Secondary-ray caching for every mirror/glass object: " + raycache::cacheTechniqueNameList() +
            " (default: each material's own setting; see docs/caching.md)");
    command.add_option("--cdct-step", job.cdctStep,
                       "CDCT parity linear-search step along the ray, scene units (default: each material's own, 0.4)");
    command.add_option("--cdct-epsilon", job.cdctEpsilon,
                       "CDCT parity binary-search precision, < step (default: each material's own, 0.05)");
    command.add_option("--cdct-max-depth", job.cdctMaxDepth,
                       "CDCT depth for misses and farther hits (default: each material's own, 100)");
    command.add_option("--cdct-tolerance", job.cdctTolerance,
                       "Improved CDCT error control: trace the ray when the cached point lies farther than this "
                       "many texels from it (default: each material's own, 2)");
    command.add_option("--cdct-prefill-per-frame", job.cdctPrefillPerFrame,
                       "Improved CDCT: trace at most this many pre-fill rays (cube texels) per frame, whole face rows, "
                       "so no frame stalls filling cubes; 0 = fill every cube whole in the frame that first asks "
                       "for it (default: 0, but half the image's pixels a frame in the viewer)");
    command.add_option("--cache-res", job.cacheResolution,
                       "Caching-cube face resolution, " + std::to_string(raycache::CacheSettings::kMinFaceResolution) +
                           ".." + std::to_string(raycache::CacheSettings::kMaxFaceResolution) +
                           " (default: each material's own, 512 in built-in scenes)");
    command.add_option("--cache-levels", job.cacheLevels,
                       "CCT cubes' resolution levels, 1..8: each level halves the last's face resolution; a lookup "
                       "takes the finest valid texel no wider than its pixel's footprint allows (docs/caching.md)")
        ->capture_default_str();
    command.add_option("--cache-level-error", job.cacheLevelError,
                       "Multi-resolution cubes: a coarser texel may span this many times the angle between "
                       "neighbouring pixels' reflected rays, (0, 1000]")
        ->capture_default_str();
    command.add_flag("--cache-res-from-view", job.cacheResFromView,
                     "CCT cubes take the coarsest face resolution their lookups' pixel footprints allow within "
                     "--cache-level-error, re-chosen after every frame, up to --cache-res (docs/caching.md)");
    raycache::addChoiceOption(
        command, "--cache-fill", job.cacheFill, raycache::kVisibleFills, raycache::visibleFillName,
        "Fill CCT cubes from the surfaces the camera sees, one visibility ray per texel: off, exact "
        "(surfaces without highlights, mirrors or glass), approximate (also with highlights) (docs/caching.md)");
    command.add_option("--cache-budget", job.cacheBudgetMiB,
                       "Most memory the caching cubes may take, MiB: over it, cube resolutions are lowered "
                       "(smallest objects' first) and a note says so; a scene that cannot fit even at 16² faces "
                       "is refused (default: the scene file's cacheBudget, else half the machine's memory)");
    command.add_flag("--cache-store-changing", job.cacheStoreChanging,
                     "Animated scenes: also store what reached the objects and lights the last change moved, and "
                     "pre-fill CDCT cubes in frames that follow a change (by default both are skipped: the next "
                     "change would drop them; docs/dynamic-scenes.md)");
    raycache::addChoiceOption(
        command, "--cache-policy", job.cachePolicy, raycache::kCachePolicyModes, raycache::cachePolicyModeName,
        "auto: a cube whose lookups would cost more than they save (judged every frame from its hit, "
        "lookup and store counts, never the clock) stands aside, its rays traced directly, and "
        "probes again after 8, 16, ... 64 frames; a CCT cube judges on a sample of 1 texel in 16 "
        "first and caches fully only when the sample pays; always: every cube caches every frame, "
        "as the documents did (docs/caching.md)");
    command.add_flag("--cache-ideal", job.cacheIdeal,
                     "Benchmark switch: cache misses return black instead of being traced");
    command.add_flag("--stage-times", job.stageTimes,
                     "Time every stage of the tile kernel (CPU ms summed over threads) and print them per frame");
    raycache::addChoiceOption(command, "--pipeline", job.pipeline, raycache::kPipelineKinds, raycache::pipelineKindName,
                              "ray: primary rays per tile; hybrid: G-buffer (OpenGL or primary-ray packets), then "
                              "deferred shadow and secondary rays; render-cache: reproject earlier frames' samples and "
                              "trace a budget of pixels (docs/render-cache.md); default: the scene file's, else ray");
    raycache::addChoiceOption(
        command, "--accel", job.accel, raycache::kAccelerators, raycache::acceleratorName,
        "embree: primary and shadow rays through Embree's BVH; grids: a perspective grid for "
        "primary rays and a light-space grid per light for their shadow rays, rebuilt every frame "
        "(docs/grids.md); default: the scene file's, else embree");
    addRenderCacheOptions(command, job);
    raycache::addChoiceOption(command, "--gbuffer", job.gbuffer, raycache::kGBufferSources, raycache::gbufferSourceName,
                              "Hybrid G-buffer source: auto (OpenGL if a 4.5 context can be made, else packets), "
                              "gl or packets");
    raycache::addChoiceOption(
        command, "--tile-balance", job.tileBalance, raycache::kTileBalances, raycache::tileBalanceName,
        "MPI jobs (mpirun -np N raycache render ...): static deals tile i to process i mod N; dynamic "
        "(from the second frame) deals tiles by the previous frame's cost of each tile; claim lets "
        "every thread take the next tile from a counter on process 0 when it is free. Images do "
        "not depend on it (docs/cluster.md)");
}

// Every command's options, and the subcommand that fills them (to ask which was parsed).
struct Commands {
    raycache::RenderCommandOptions render;
    CLI::App* renderCmd = nullptr;
    raycache::CacheViewCommandOptions cacheView;
    CLI::App* cacheViewCmd = nullptr;
    raycache::ViewCommandOptions view;
    CLI::App* viewCmd = nullptr;
    raycache::DiffCommandOptions diff;
    CLI::App* diffCmd = nullptr;
    raycache::BenchCommandOptions bench;
    CLI::App* benchCmd = nullptr;
};

// main() proper, once the process knows its place in an MPI job (if any).
int run(int argc, char** argv, const raycache::ClusterRuntime& cluster);

}  // namespace

int main(int argc, char** argv) {
    raycache::keepFreedMemoryInProcess();
    std::optional<raycache::ClusterRuntime> cluster;
    try {
        cluster.emplace(argc, argv);
    } catch (const std::exception& e) {
        // Every process of the job fails alike here, before any MPI: process
        // 0 speaks and carries the exit code; the others end quietly (had
        // they failed too, the launcher could end process 0 before it spoke).
        if (raycache::launchedProcessRank() != 0) return 0;
        std::cerr << "error: " << e.what() << '\n';
        return 1;
    }
    return run(argc, argv, *cluster);
}

namespace {

void addRenderCommand(CLI::App& app, Commands& c) {
    c.renderCmd = app.add_subcommand(
        "render", "Render a scene along its camera path (under mpirun, over all its processes: docs/cluster.md)");
    addRenderJobOptions(*c.renderCmd, c.render.job);
    c.renderCmd->add_option("--out", c.render.out,
                            "Image to write (.png sRGB 8-bit, .exr linear float); %04d in the name writes every frame");
    c.renderCmd->add_option("--stats", c.render.statsPath, "Write per-frame statistics as JSON to this file");
}

void addCacheViewCommand(CLI::App& app, Commands& c) {
    c.cacheViewCmd = app.add_subcommand(
        "cache-view", "Render a scene's camera path with caching, then write one object's caching cube as a cross");
    c.cacheViewCmd->add_option("--object", c.cacheView.object, "Name of the caching object whose cube to show")
        ->required();
    c.cacheViewCmd->add_option("--out", c.cacheView.out,
                               "Image of the unfolded cube (.png sRGB 8-bit, .exr linear float)")
        ->required();
    c.cacheViewCmd->add_option("--show", c.cacheView.show,
                               "What to draw: color, or depth (CDCT cubes: grey near to far, blue environment, red "
                               "invalid)")
        ->capture_default_str();
    addRenderJobOptions(*c.cacheViewCmd, c.cacheView.job);
}

// `view`: the interactive viewer (docs/viewer.md).
void addViewCommand(CLI::App& app, Commands& c) {
    raycache::ViewCommandOptions& view = c.view;
    view.job.width = 960;
    view.job.height = 540;
    CLI::App* viewCmd = c.viewCmd = app.add_subcommand(
        "view", "Walk through a scene in a window; with --frames, play its camera path, print timings and exit");
    viewCmd->add_option("scene-name", view.job.scene, "Built-in scene name, scene .json file or glTF 2.0 scene (.gltf, .glb); same as --scene");
    addRenderJobOptions(*viewCmd, view.job);
    viewCmd->get_option("--width")->description("Window and film width in pixels");
    viewCmd->get_option("--height")->description("Window and film height in pixels");
    // The view command's own --pipeline: the render options' one plus auto, its default.
    viewCmd->remove_option(viewCmd->get_option("--pipeline"));
    raycache::addChoiceOption(
        *viewCmd, "--pipeline", view.pipeline, raycache::kViewerPipelines, raycache::viewerPipelineName,
        "auto: full frames (the ray pipeline) while they keep --target-fps or the camera is still, the Render "
        "Cache while the camera moves faster than full frames follow and it is faster (docs/viewer.md); ray, "
        "hybrid (primary-ray packet G-buffer), render-cache: always that pipeline");
    viewCmd->add_option("--target-fps", view.targetFps,
                        "--pipeline auto: the display rate full frames must keep while the camera moves")
        ->capture_default_str();
    viewCmd->get_option("--frames")->description(
        "Scripted run: show this many frames of the camera path, print per-frame timings, exit");
    viewCmd->add_option("--screenshot", view.screenshotPath,
                        "Scripted: write the window after the last frame here (.png/.exr); interactive: where F12 "
                        "writes (default raycache-<scene>-NNNN.png)");
    viewCmd->add_flag("--hide-ui", view.hideUi, "Start with the panel hidden: the window shows the frame only");
    viewCmd->add_option("--warmup", view.warmupFrames, "Scripted: frames left out of the timing summary")
        ->capture_default_str();
    viewCmd->add_flag("--no-vsync", view.noVsync, "Interactive: do not wait for the display's refresh");
    viewCmd->add_flag("--difference", view.difference,
                      "Start showing the difference to the uncached image as a heat map (key X toggles)");
    viewCmd->add_flag("--level-overlay", view.levelOverlay,
                      "Start with the cube level per pixel overlay on: which cube level answered each pixel "
                      "(key L toggles)");
    viewCmd->add_option("--inspect", view.inspectObject,
                        "Start with this caching object's cube unfolded in the cache inspector");
    viewCmd->add_option("--moving-scale", view.movingScale,
                        "Resolution factor while the camera moves, 0.1..1")
        ->capture_default_str();
    raycache::addChoiceOption(
        *viewCmd, "--render-cache-display", view.renderCacheDisplay, raycache::kRenderCacheDisplays,
        raycache::renderCacheDisplayName,
        "--pipeline render-cache: async reconstructs at the display's own rate while tracer threads feed it "
        "samples (default when interactive; images depend on timing); sync traces one request map per "
        "frame, the frames of `raycache render` (default with --frames). Scenes that move are always sync");
    viewCmd->add_option("--render-cache-trace-threads", view.renderCacheTraceThreads,
                        "Async Render Cache: threads that trace samples (0 = half of --threads, at least 1)")
        ->capture_default_str();
    viewCmd->add_option("--render-cache-display-threads", view.renderCacheDisplayThreads,
                        "Async Render Cache: threads that reconstruct the display (0 = --threads; they share the "
                        "cores with the tracer's)")
        ->capture_default_str();
    viewCmd->add_option("--render-cache-request-frames", view.renderCacheRequestFrames,
                        "Async Render Cache: a request map asks for what the tracer traces in this many display "
                        "frames (at least --rc-budget); 0: --rc-budget alone, leaving more of the cores to the display")
        ->capture_default_str();
    viewCmd->add_option("--render-cache-reshade-ms", view.renderCacheReshadeMs,
                        "Async Render Cache: keep reshading mirror/glass/glossy samples within this many ms a display "
                        "frame by reshading them in turns (--rc-reshade-every chosen each frame); 0: every sample "
                        "every frame")
        ->capture_default_str();
}

// raycache diff: image difference metrics and heat map.
void addDiffCommand(CLI::App& app, Commands& c) {
    c.diffCmd = app.add_subcommand("diff", "Compare two images: MAE, PSNR and SSIM of the displayed images");
    c.diffCmd->add_option("first", c.diff.first, "First image (.png, .exr, .hdr, .jpg, .bmp, .tga)")->required();
    c.diffCmd->add_option("second", c.diff.second, "Second image, same size")->required();
    c.diffCmd->add_option("--heatmap", c.diff.heatmap,
                          "Write the per-pixel difference as a heat map with a color bar (.png or .exr)");
    c.diffCmd->add_option("--heatmap-max", c.diff.heatmapMax, "Difference shown as full red, in (0, 1]")
        ->capture_default_str();
}

// raycache bench: the documents' experiments.
void addBenchCommand(CLI::App& app, Commands& c) {
    raycache::BenchCommandOptions& bench = c.bench;
    CLI::App* benchCmd = c.benchCmd = app.add_subcommand(
        "bench", "Reproduce the documents' experiments: tables, plots, images and results/report.md");
    benchCmd->add_option("experiments", bench.experiments,
                         "table-5.1, table-5.2, table-5.3, fill-rate, quality, parallax, render-cache, dynamic, grids, "
                         "or all (writes report.md); under mpirun the experiments are dealt over the processes "
                         "(docs/cluster.md)");
    benchCmd->add_flag("--quick", bench.quick, "Lower resolution, fewer frames: all in a few minutes (default)");
    benchCmd->add_flag("--full", bench.full, "The documents' resolutions and frame counts (long)");
    benchCmd->add_flag("--tiny", bench.tiny, "A few dozen pixels, seconds: a smoke test, numbers meaningless");
    benchCmd->add_option("--threads", bench.threads, "Worker threads, 0 = all cores")->capture_default_str();
    benchCmd->add_option("--out", bench.outDir, "Results directory")->capture_default_str();
    raycache::addChoiceOption(
        *benchCmd, "--cache-policy", bench.cachePolicy, raycache::kCachePolicyModes, raycache::cachePolicyModeName,
        "always: every cube caches every frame (the documents' protocol, comparable tables); auto: "
        "the cache policy of `raycache render` (docs/caching.md) in dynamic and parallax; the other "
        "experiments always cache (docs/bench.md)");
    benchCmd->add_flag("--list", bench.list, "List the experiments and exit");
}

// Every process parses the same arguments, so they all agree on the
// outcome. Returns the exit code when the process ends here (help,
// version, bad arguments), else nothing.
std::optional<int> parseArguments(CLI::App& app, int argc, char** argv, std::ostream& out, std::ostream& err) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e, out, err);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e, out, err);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e, out, err);
    } catch (const CLI::ParseError& e) {
        err << "error: " << e.what() << " (see --help)\n";
        return 2;
    }
    return std::nullopt;
}

void runParsedCommand(Commands& c, std::ostream& out, std::ostream& err, const raycache::ProcessGroup& group) {
    if (c.renderCmd->parsed()) raycache::runRenderCommand(c.render, out, err, group);
    else if (c.cacheViewCmd->parsed()) raycache::runCacheViewCommand(c.cacheView, std::cout, std::cerr);
    else if (c.viewCmd->parsed()) raycache::runViewCommand(c.view, std::cout, std::cerr);
    else if (c.diffCmd->parsed()) raycache::runDiffCommand(c.diff, std::cout);
    else if (c.benchCmd->parsed()) {
        c.bench.interactive = raycache::ProgressBar::stdoutIsTerminal();
        raycache::runBenchCommand(c.bench, out, group);
    }
    else raycache::runScenesCommand(std::cout);
}

int run(int argc, char** argv, const raycache::ClusterRuntime& cluster) {
    const raycache::ProcessGroup& group = cluster.group();
    // In an MPI job only process 0 speaks; the others' output goes nowhere
    // (a stream without a buffer drops what it is given).
    std::ostream discarded(nullptr);
    std::ostream& out = group.isRoot() ? std::cout : discarded;
    std::ostream& err = group.isRoot() ? std::cerr : discarded;

    CLI::App app{"raycache: real-time Whitted ray tracing with per-object ray caching"};
    app.require_subcommand(1);
    app.set_version_flag(
        "--version", [] { return raycache::formatBuildInfo(raycache::currentBuildInfo()); },
        "Print the version, git commit, build type and compiler, the Embree, oneTBB, Assimp and OpenEXR versions "
        "and the lane code's instruction set, then exit");
    Commands commands;
    addRenderCommand(app, commands);
    addCacheViewCommand(app, commands);
    app.add_subcommand("scenes", "List the built-in scenes, one per line");
    addViewCommand(app, commands);
    addDiffCommand(app, commands);
    addBenchCommand(app, commands);

    if (const std::optional<int> exitCode = parseArguments(app, argc, argv, out, err)) return *exitCode;
    if (group.size() > 1 && !commands.renderCmd->parsed() && !commands.benchCmd->parsed()) {
        err << "error: only `raycache render` and `raycache bench` run as MPI jobs; run the other commands without "
               "mpirun\n";
        return 2;
    }
    try {
        runParsedCommand(commands, out, err, group);
    } catch (const raycache::ProcessGroupFailure& e) {
        // Every process of the job threw this together: process 0 reports it.
        err << "error: " << e.what() << '\n';
        return e.exitCode();
    } catch (const std::exception& e) {
        const int code = dynamic_cast<const raycache::InputError*>(&e) ? 2 : 1;
        if (group.size() == 1) {
            std::cerr << "error: " << e.what() << '\n';
            return code;
        }
        // A failure on this process alone, mid-job: the others would wait for
        // it in the next exchange, so the whole job ends here.
        std::cerr << "error: process " << group.rank() << " of " << group.size() << ": " << e.what() << '\n';
        cluster.abortJob(code);
    }
    return 0;
}

}  // namespace
