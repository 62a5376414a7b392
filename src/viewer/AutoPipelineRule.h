#pragma once
// `view --pipeline auto`: which of two ways of making the next frame to
// show. Full frames (the ray pipeline: every pixel traced) while they keep
// the display rate, and whenever the camera is still (so a still camera
// shows exactly the full render); the Render Cache while the camera moves
// and a full frame at the moving size would miss the target frame time, if
// it is measurably faster there. Decided from the render times of the frames
// already shown, per pixel, so a change of size needs no new measurement.
// Pure: no clock, no window (docs/viewer.md, "--pipeline auto").
#include <cstdint>

namespace raycache {

enum class ShownPipeline { FullFrame, RenderCache };

const char* shownPipelineName(ShownPipeline shown);

class AutoPipelineRule {
public:
    // A full frame that takes longer than this while the camera moves does not
    // keep the display rate. The Render Cache is taken only when its frames
    // are estimated below kSwitchShare of a full frame's (so two nearly equal
    // estimates do not flip from frame to frame), and left when they no
    // longer beat one.
    static constexpr double kSwitchShare = 0.8;
    // Weight of a new measurement in the running estimate of each way's cost.
    static constexpr double kNewWeight = 0.25;

    explicit AutoPipelineRule(double targetFrameMs) : targetMs_(targetFrameMs) {}

    // A frame was shown: made by `shown` in `renderMs` with `pixels` pixels.
    // Frames of the Render Cache that traced every pixel (its first, or a cut)
    // say nothing of its reconstruction: leave them out.
    void observe(ShownPipeline shown, double renderMs, std::int64_t pixels);

    // The way to make the next frame. `fullPixels`: the size a full frame
    // takes now (smaller while moving); `renderCachePixels`: the Render
    // Cache's (never reduced). `renderCacheAllowed`: false for scenes that
    // move (the Render Cache is for still scenes in the viewer).
    ShownPipeline choose(bool moving, bool renderCacheAllowed, std::int64_t fullPixels,
                         std::int64_t renderCachePixels);

    ShownPipeline current() const { return current_; }
    // Estimated milliseconds of a frame of `pixels` made either way; < 0 before any measurement.
    double estimateMs(ShownPipeline way, std::int64_t pixels) const;
    double targetMs() const { return targetMs_; }

private:
    double targetMs_;
    double fullMsPerPixel_ = -1.0;
    double renderCacheMsPerPixel_ = -1.0;
    ShownPipeline current_ = ShownPipeline::FullFrame;
};

}  // namespace raycache
