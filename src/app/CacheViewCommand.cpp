#include "app/CacheViewCommand.h"

#include <ostream>
#include <vector>

#include "app/OutputDirectory.h"
#include "cache/CubeCross.h"
#include "core/Errors.h"
#include "render/ImageWriter.h"
#include "session/FrameLoop.h"
#include "session/FrameReport.h"

namespace raycache {

namespace {

// Checked before the caches (and their memory) exist, with RayCache's own rule.
bool hasCache(const SceneObject& object, const RayCacheSettings& settings) {
    return RayCache::techniqueFor(object, settings) != CacheTechnique::None;
}

// The id of the object named `name`; InputError if there is none or it has no
// cache, naming the objects that do.
int cachedObjectId(const Scene& scene, const RayCacheSettings& settings, const std::string& name) {
    std::string cachingNames;
    int id = -1;
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        if (object.name == name && id < 0) id = static_cast<int>(i);
        if (hasCache(object, settings)) cachingNames += (cachingNames.empty() ? "" : ", ") + object.name;
    }
    if (cachingNames.empty()) cachingNames = "none";
    if (id < 0) throw InputError("--object: no object named '" + name + "'; caching objects: " + cachingNames);
    const SceneObject& object = scene.objects[static_cast<std::size_t>(id)];
    if (!object.material.reflects() && !object.material.refracts())
        throw InputError("--object: object '" + name +
                         "' has no caching cube: it is neither reflective nor refractive; caching objects: " +
                         cachingNames);
    if (!hasCache(object, settings))
        throw InputError("--object: object '" + name + "' has no caching cube: its caching technique is none" +
                         (settings.techniqueOverride ? " (--technique none)" : "") +
                         "; caching objects: " + cachingNames);
    return id;
}

}  // namespace

void runCacheViewCommand(const CacheViewCommandOptions& options, std::ostream& out, std::ostream& notes) {
    validateRenderJobOptions(options.job);
    if (options.out.empty()) throw InputError("--out is required: the image to write the cube's cross to");
    if (options.object.empty()) throw InputError("--object is required: the name of a caching object");
    if (options.show != "color" && options.show != "depth")
        throw InputError("--show must be color or depth (got '" + options.show + "')");

    const RenderJob job = prepareRenderJob(options.job);
    printSceneNotes(job.scene, notes);
    const int objectId = cachedObjectId(job.scene, job.settings.cache, options.object);
    createParentDirectories(options.out);
    checkWritableImagePath(options.out);
    const SceneObject& object = job.scene.objects[static_cast<std::size_t>(objectId)];
    const CacheTechnique technique = RayCache::techniqueFor(object, job.settings.cache);
    if (options.show == "depth" && technique != CacheTechnique::Cdct && technique != CacheTechnique::CdctParity)
        throw InputError("--show depth: object '" + options.object +
                         "' is cached with CCT, which keeps no depths (use --technique cdct or cdct-parity)");
    const float maxDepth = RayCache::cdctParametersFor(object, job.settings.cache).maxDepth;

    out << "scene " << job.scene.name << ": " << job.scene.objects.size() << " objects, " << job.scene.lights.size()
        << " lights, " << job.settings.width << "x" << job.settings.height << ", " << job.frames
        << " frames; showing the cube of '" << options.object << "'\n";

    renderFrames(job.scene, job.path, job.settings, job.frames,
                 [&](const FrameResult& r, const Image&, const RayCache& caches) {
                     out << formatFrameLine(r, job.frames) << std::endl;
                     if (r.frame + 1 != job.frames) return;
                     if (!caches.cachesObject(objectId))
                         throw RuntimeError("object '" + options.object + "' was not cached");
                     const CachingCube& cube = caches.cube(objectId);
                     writeImage(options.show == "depth" ? unfoldCubeDepthCross(cube, maxDepth) : unfoldCubeCross(cube),
                                options.out);
                     const double invalidPercent = 100.0 * static_cast<double>(cube.texelCount() - cube.validCount()) /
                                                   static_cast<double>(cube.texelCount());
                     out << "object " << options.object << ": " << cube.size() << "x" << cube.size()
                         << " texels per face, " << formatFixed(invalidPercent, 1) << "% invalid, "
                         << formatFixed(static_cast<double>(cube.bytes()) / (1024.0 * 1024.0), 2) << " MiB\n"
                         << "wrote " << options.out << "\n";
                 },
                 [&](const std::string& pipeline) { out << pipeline << "\n"; }, job.timeline);
}

}  // namespace raycache
