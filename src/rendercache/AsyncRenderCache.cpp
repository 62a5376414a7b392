#include "rendercache/AsyncRenderCache.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>

#include "core/Elapsed.h"
#include "rendercache/ReshadeBudget.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

// Pixels traced between two hand-overs: small enough that a first frame
// fills in visibly, large enough for full waves on every trace thread.
constexpr std::size_t kBatchPixels = 4096;
// Samples age by the requests completed since the last display frame; more
// than this at once (a very slow display) ages them no further.
constexpr int kMaxAgeStep = 64;

// Batch `i` of `count`, in bit-reversed order: consecutive batches lie far
// apart in the request, so the image fills evenly as they come.
std::vector<std::size_t> spreadOrder(std::size_t count) {
    std::vector<std::size_t> order;
    order.reserve(count);
    const unsigned bits = count > 1 ? static_cast<unsigned>(std::bit_width(count - 1)) : 0u;
    for (std::size_t i = 0; i < (std::size_t{1} << bits); ++i) {
        std::size_t reversed = 0;
        for (unsigned b = 0; b < bits; ++b)
            if (i & (std::size_t{1} << b)) reversed |= std::size_t{1} << (bits - 1 - b);
        if (reversed < count) order.push_back(reversed);
    }
    return order;
}

}  // namespace

AsyncRenderCacheThreads splitRenderCacheThreads(int threads, int traceThreads, int displayThreads) {
    const int all = threads > 0 ? threads : Parallel::hardwareThreads();
    AsyncRenderCacheThreads split;
    split.trace = traceThreads > 0 ? traceThreads : std::max(1, all / 2);
    split.display = displayThreads > 0 ? displayThreads : all;
    return split;
}

AsyncRenderCache::AsyncRenderCache(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                                   RayCache* cache, AsyncRenderCacheThreads threads, std::function<void()> onSamples)
    : threads_(threads), pixels_(settings.width * settings.height), minimumShare_(settings.renderCache.budget),
      displayParallel_(threads.display), traceParallel_(threads.trace),
      pipeline_(scene, tracer, settings, displayParallel_, cache), onSamples_(std::move(onSamples)),
      thread_([this] { traceLoop(); }) {}

AsyncRenderCache::~AsyncRenderCache() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

bool AsyncRenderCache::samplesWaiting() const {
    std::lock_guard lock(mutex_);
    return !ready_.empty();
}

AsyncTraceCounts AsyncRenderCache::counts() const {
    std::lock_guard lock(mutex_);
    return counts_;
}

FrameStats AsyncRenderCache::reconstruct(const Camera& camera, Image& film) {
    const auto start = Clock::now();
    merging_.clear();
    double raysPerSecond = 0.0;
    {
        std::lock_guard lock(mutex_);
        if (error_) std::rethrow_exception(error_);
        std::swap(merging_, ready_);
        if (counts_.busySeconds > 0.0) raysPerSecond = static_cast<double>(counts_.samples) / counts_.busySeconds;
    }
    int completed = 0;
    for (const SampleBatch& batch : merging_)
        if (batch.endsRequest) {
            ++completed;
            requestOutstanding_ = false;
        }
    // What the tracer traces in requestFrames_ display frames, at least the
    // settings' budget (0 leaves the choice to the pipeline: before the
    // first measurement).
    int budget = 0;
    if (raysPerSecond > 0.0 && reconstructSeconds_ > 0.0 && requestFrames_ > 0.0) {
        const double wanted = raysPerSecond * reconstructSeconds_ * requestFrames_;
        budget = static_cast<int>(std::clamp(wanted, static_cast<double>(minimumShare_) * pixels_,
                                             static_cast<double>(pixels_)));
    }
    SampleRequest request;
    std::int64_t merged = 0;
    const bool issues = !requestOutstanding_;
    FrameStats stats = pipeline_.reconstruct(camera, film, merging_, std::min(completed, kMaxAgeStep), budget,
                                             issues ? &request : nullptr, merged);
    {
        std::lock_guard lock(mutex_);
        counts_.merged += merged;
        if (issues) request_ = std::move(request);
    }
    if (issues) {
        requestOutstanding_ = true;
        wake_.notify_all();
    }
    reconstructSeconds_ = millisecondsSince(start) / 1000.0;
    const bool moved = lastCamera_ && !(*lastCamera_ == camera);
    lastCamera_ = camera;
    if (moved && stats.renderCache)
        pipeline_.setReshadeInterval(
            reshadeIntervalWithin(reshadeBudgetMs_, pipeline_.reshadeInterval(), stats.renderCache->reshadeMs));
    return stats;
}

bool AsyncRenderCache::tracePart(const Camera& camera, const std::vector<PixelCoord>& pixels, bool endsRequest) {
    const std::size_t batches = std::max<std::size_t>(1, (pixels.size() + kBatchPixels - 1) / kBatchPixels);
    const std::vector<std::size_t> order = spreadOrder(batches);
    for (std::size_t n = 0; n < order.size(); ++n) {
        {
            std::lock_guard lock(mutex_);
            if (stop_) return false;
        }
        const auto start = Clock::now();
        const std::size_t begin = std::min(pixels.size(), order[n] * kBatchPixels);
        const std::size_t end = std::min(pixels.size(), begin + kBatchPixels);
        SampleBatch batch;
        batch.camera = camera;
        batch.pixels.assign(pixels.begin() + static_cast<std::ptrdiff_t>(begin),
                            pixels.begin() + static_cast<std::ptrdiff_t>(end));
        batch.samples.resize(batch.pixels.size());
        batch.endsRequest = endsRequest && n + 1 == order.size();
        pipeline_.traceSamples(camera, batch.pixels, traceParallel_, traceScratch_, batch.samples);
        const double seconds = millisecondsSince(start) / 1000.0;
        {
            std::lock_guard lock(mutex_);
            if (stop_) return false;
            counts_.samples += static_cast<std::int64_t>(batch.samples.size());
            counts_.busySeconds += seconds;
            ++counts_.batches;
            if (batch.endsRequest) ++counts_.requests;
            ready_.push_back(std::move(batch));
        }
        if (onSamples_) onSamples_();
    }
    return true;
}

void AsyncRenderCache::traceLoop() {
    try {
        for (;;) {
            SampleRequest request;
            {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, [&] { return stop_ || request_.has_value(); });
                if (stop_) return;
                request = std::move(*request_);
                request_.reset();
            }
            // This camera's pixels first: the predicted camera's are for later.
            if (!tracePart(request.camera, request.pixels, request.predicted.empty())) return;
            if (!request.predicted.empty() && !tracePart(request.nextCamera, request.predicted, true)) return;
        }
    } catch (...) {
        {
            std::lock_guard lock(mutex_);
            error_ = std::current_exception();
        }
        if (onSamples_) onSamples_();
    }
}

}  // namespace raycache
