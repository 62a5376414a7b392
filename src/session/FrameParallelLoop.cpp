#include "session/FrameParallelLoop.h"

#include <chrono>

#include "session/RenderSession.h"

namespace raycache {

namespace {

// The statistics of a frame whole frames can carry (no caches, no Render Cache).
void packStats(Bytes& out, const FrameResult& r) {
    appendBytes(out, r.milliseconds);
    appendBytes(out, r.stats.rays);
    const auto optional = [&](const auto& value) {
        appendBytes(out, static_cast<std::uint8_t>(value.has_value()));
        if (value) appendBytes(out, *value);
    };
    optional(r.stats.phases);
    optional(r.stats.stages);
    optional(r.stats.sceneUpdate);
}

void unpackStats(ByteReader& in, FrameResult& r) {
    r.milliseconds = in.read<double>();
    r.stats.rays = in.read<RayCounts>();
    const auto optional = [&](auto& value) {
        if (in.read<std::uint8_t>()) value = in.read<typename std::remove_reference_t<decltype(value)>::value_type>();
    };
    optional(r.stats.phases);
    optional(r.stats.stages);
    optional(r.stats.sceneUpdate);
}

}  // namespace

bool framesAreIndependent(const Scene& scene, const RenderSettings& settings) {
    if (settings.pipeline == PipelineKind::RenderCache) return false;
    for (const SceneObject& object : scene.objects)
        if (RayCache::techniqueFor(object, settings.cache) != CacheTechnique::None) return false;
    return true;
}

void renderFramesAcrossProcesses(const Scene& scene, const CameraPath& path, const RenderSettings& settings,
                                 int frameCount, const ProcessGroup& group, const FrameCallback& onFrame,
                                 const std::function<bool(int frame)>& needsFilm, const PipelineCallback& onPipeline,
                                 const FrameTimeline& timeline) {
    RenderSession session(scene, settings);
    if (onPipeline) onPipeline(session.description());
    Image film(settings.width, settings.height);
    const int processes = group.size();
    Bytes part;
    GatheredBytes parts;  // process 0: every process's frame, buffers kept from round to round
    for (int first = 0; first < frameCount; first += processes) {
        // Each round, process r renders frame first + r.
        const int frame = first + group.rank();
        part.clear();
        if (frame < frameCount) {
            const auto start = std::chrono::steady_clock::now();
            session.setTime(timeline.timeOf(frame));
            FrameResult result;
            result.frame = frame;
            result.stats = session.render(path.cameraAt(scene.camera, frame), film);
            result.milliseconds =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            packStats(part, result);
            if (needsFilm(frame)) appendBytes(part, std::span<const Rgb>(film.pixels()));
        }
        group.gatherToRoot(part, parts);
        if (!group.isRoot()) continue;
        const Image own = film;  // process 0's frame, before the others' overwrite the film
        for (int r = 0; r < processes && first + r < frameCount; ++r) {
            ByteReader reader(parts.of(static_cast<std::size_t>(r)));
            FrameResult result;
            result.frame = first + r;
            unpackStats(reader, result);
            ClusterStats cluster;
            cluster.processes = processes;
            cluster.assignment = "whole frames";
            const bool withFilm = needsFilm(result.frame);
            if (r == 0) {
                film = own;
            } else if (withFilm) {
                reader.readInto(std::span<Rgb>(film.pixels()));
                cluster.imageBytes = film.pixels().size() * sizeof(Rgb);
            }
            cluster.controlBytes = parts.of(static_cast<std::size_t>(r)).size() - cluster.imageBytes;
            if (r == 0) cluster.controlBytes = 0;
            result.stats.cluster = cluster;
            onFrame(result, film, session.cache());
        }
    }
}

}  // namespace raycache
