#include "app/RenderCommand.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "app/FramePathPattern.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "render/FrameLoop.h"
#include "render/ImageWriter.h"
#include "scene/SceneLoader.h"

namespace raycache {

namespace {

constexpr int kMaxImageSide = 16384;
constexpr int kMaxFrames = 1000000;

void checkOptions(const RenderCommandOptions& o) {
    if (o.width < 1 || o.height < 1 || o.width > kMaxImageSide || o.height > kMaxImageSide)
        throw InputError("--width/--height must be between 1 and " + std::to_string(kMaxImageSide));
    if (o.frames && (*o.frames < 1 || *o.frames > kMaxFrames))
        throw InputError("--frames must be between 1 and " + std::to_string(kMaxFrames));
    if (o.maxDepth < 1 || o.maxDepth > 64) throw InputError("--max-depth must be between 1 and 64");
    if (!(o.minWeight >= 0.0f && o.minWeight <= 1.0f)) throw InputError("--min-weight must be in [0, 1]");
    if (o.threads < 0 || o.threads > 1024) throw InputError("--threads must be between 0 (all) and 1024");
    if (o.technique && *o.technique != "none" && *o.technique != "cct")
        throw InputError("--technique must be none or cct (got '" + *o.technique + "'; cdct is not implemented yet)");
    if (o.cacheResolution &&
        (*o.cacheResolution < RayCache::kMinResolution || *o.cacheResolution > RayCache::kMaxResolution))
        throw InputError("--cache-res must be between 16 and 2048 (got " + std::to_string(*o.cacheResolution) + ")");
    if (o.path && *o.path != "static" && *o.path != "orbit" && *o.path != "pan")
        throw InputError("--path must be static, orbit or pan (got '" + *o.path + "')");
}

CameraPath chooseCameraPath(const Scene& scene, const std::optional<std::string>& override) {
    if (!override) return scene.cameraPath;
    CameraPath path;
    if (*override == "static") return path;
    path.kind = *override == "orbit" ? CameraPathKind::Orbit : CameraPathKind::Pan;
    // Keep the scene's own centre and speed when it already orbits or pans.
    const bool sceneTurns = scene.cameraPath.kind == CameraPathKind::Orbit || scene.cameraPath.kind == CameraPathKind::Pan;
    path.center = scene.cameraPath.kind == CameraPathKind::Orbit ? scene.cameraPath.center : scene.camera.lookAt;
    path.degreesPerFrame = sceneTurns ? scene.cameraPath.degreesPerFrame : 1.0f;
    return path;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fixed(double value, int decimals) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

nlohmann::json cacheJson(const FrameCacheStats& c) {
    nlohmann::json objects = nlohmann::json::array();
    for (const ObjectCacheStats& o : c.objects)
        objects.push_back({{"object", o.name}, {"resolution", o.resolution}, {"lookups", o.lookups},
                           {"hits", o.hits}, {"misses", o.misses}, {"stores", o.stores},
                           {"invalid_percent_before", o.invalidPercentBefore}, {"bytes", o.bytes}});
    return {{"lookups", c.lookups()}, {"hits", c.hits()}, {"misses", c.misses()}, {"stores", c.stores()},
            {"invalid_percent_before", c.invalidPercentBefore()}, {"bytes", c.bytes()}, {"objects", objects}};
}

nlohmann::json raysJson(const RayCounts& r) {
    return {{"primary", r.primary}, {"shadow", r.shadow}, {"reflection", r.reflection},
            {"refraction", r.refraction}, {"total", r.total()}};
}

}  // namespace

void runRenderCommand(const RenderCommandOptions& options, std::ostream& out) {
    checkOptions(options);
    const FramePathPattern outPattern(options.out);
    if (!options.out.empty()) checkWritableImagePath(outPattern.pathFor(0));
    if (!options.statsPath.empty()) {
        const auto parent = std::filesystem::path(options.statsPath).parent_path();
        if (!parent.empty() && !std::filesystem::is_directory(parent))
            throw InputError("--stats: directory " + parent.string() + " does not exist");
    }

    const Scene scene = loadScene(options.scene);
    const CameraPath path = chooseCameraPath(scene, options.path);
    const int frames = options.frames.value_or(scene.defaultFrames);

    RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.maxDepth = options.maxDepth;
    settings.minWeight = options.minWeight;
    settings.threads = options.threads;
    if (options.technique)
        settings.cache.techniqueOverride = *options.technique == "cct" ? CacheTechnique::Cct : CacheTechnique::None;
    settings.cache.resolutionOverride = options.cacheResolution;
    settings.cache.ideal = options.cacheIdeal;

    out << "scene " << scene.name << ": " << scene.objects.size() << " objects, " << scene.lights.size()
        << " lights, " << settings.width << "x" << settings.height << ", " << frames << " frames\n";

    std::vector<double> times;
    nlohmann::json frameStats = nlohmann::json::array();
    RayCounts totalRays;
    renderFrames(scene, path, settings, frames, [&](const FrameResult& r, const Image& film) {
        const RayCounts& rays = r.stats.rays;
        const double mrays = static_cast<double>(rays.total()) / (r.milliseconds * 1e3);
        out << "frame " << (r.frame + 1) << "/" << frames << "  " << fixed(r.milliseconds, 1)
            << " ms  rays: primary " << rays.primary << ", shadow " << rays.shadow << ", reflection "
            << rays.reflection << ", refraction " << rays.refraction << "  " << fixed(mrays, 2) << " Mrays/s";
        if (const auto& c = r.stats.cache) {
            const double hitRate = c->lookups() ? 100.0 * static_cast<double>(c->hits()) / static_cast<double>(c->lookups()) : 0.0;
            out << "  cache: " << c->objects.size() << " cubes, hits " << fixed(hitRate, 1) << "% of " << c->lookups()
                << ", stores " << c->stores() << ", invalid before " << fixed(c->invalidPercentBefore(), 1) << "%, "
                << fixed(static_cast<double>(c->bytes()) / (1024.0 * 1024.0), 1) << " MiB";
        }
        out << std::endl;
        times.push_back(r.milliseconds);
        totalRays += rays;
        nlohmann::json frameJson = {{"frame", r.frame}, {"ms", r.milliseconds}, {"rays", raysJson(rays)},
                                    {"mrays_per_s", mrays}};
        if (r.stats.cache) frameJson["cache"] = cacheJson(*r.stats.cache);
        frameStats.push_back(std::move(frameJson));
        const bool lastFrame = r.frame + 1 == frames;
        if (!options.out.empty() && (outPattern.perFrame() || lastFrame)) writeImage(film, outPattern.pathFor(r.frame));
    });

    const auto [minIt, maxIt] = std::minmax_element(times.begin(), times.end());
    out << "median " << fixed(median(times), 1) << " ms (min " << fixed(*minIt, 1) << ", max " << fixed(*maxIt, 1)
        << ") over " << frames << " frames\n";
    if (!options.statsPath.empty()) {
        const nlohmann::json stats = {
            {"scene", scene.name},
            {"width", settings.width},
            {"height", settings.height},
            {"max_depth", settings.maxDepth},
            {"min_weight", settings.minWeight},
            {"threads", settings.threads},
            {"frames", frameStats},
            {"summary", {{"median_ms", median(times)}, {"min_ms", *minIt}, {"max_ms", *maxIt},
                         {"rays", raysJson(totalRays)}}}};
        writeTextFileAtomically(options.statsPath, stats.dump(2) + "\n");
    }
}

}  // namespace raycache
