#include "render/RenderSession.h"

namespace raycache {

RenderSession::RenderSession(const Scene& scene, const RenderSettings& settings)
    : scene_(scene), settings_(settings), cache_(scene, settings.cache),
      ownTracer_(std::make_unique<TraceScene>(scene)), ownParallel_(std::make_unique<Parallel>(settings.threads)),
      tracer_(ownTracer_.get()), parallel_(ownParallel_.get()),
      pipeline_(makeFramePipeline(scene, *tracer_, settings_, *parallel_, &cache_)) {}

RenderSession::RenderSession(const Scene& scene, const RenderSettings& settings, const TraceScene& tracer,
                             const Parallel& parallel)
    : scene_(scene), settings_(settings), cache_(scene, settings.cache), tracer_(&tracer), parallel_(&parallel),
      pipeline_(makeFramePipeline(scene, tracer, settings_, parallel, &cache_)) {}

RenderSession::~RenderSession() = default;

FrameStats RenderSession::render(const Camera& camera, Image& film) { return pipeline_->render(camera, film); }

void RenderSession::resize(int width, int height) {
    if (width == settings_.width && height == settings_.height) return;
    settings_.width = width;
    settings_.height = height;
    pipeline_ = makeFramePipeline(scene_, *tracer_, settings_, *parallel_, &cache_);
}

}  // namespace raycache
