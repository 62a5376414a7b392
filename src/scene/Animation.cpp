#include "scene/Animation.h"

#include <algorithm>
#include <cmath>

namespace raycache {

namespace {

float ease(float s, Interpolation interpolation) {
    return interpolation == Interpolation::Smooth ? s * s * (3.0f - 2.0f * s) : s;
}

Vec3 mixKeys(const Vec3& a, const Vec3& b, float s) { return a * (1.0f - s) + b * s; }
Rgb mixKeys(const Rgb& a, const Rgb& b, float s) { return a * (1.0f - s) + b * s; }

// `time` folded into [first, last] by the wrap rule.
float wrapTime(float time, float first, float last, Wrap wrap) {
    if (wrap == Wrap::Clamp || !(last > first)) return std::clamp(time, first, last);
    const float period = last - first;
    float t = std::fmod(time - first, period);
    if (t < 0.0f) t += period;
    return first + t;
}

}  // namespace

namespace {

// The span of `keys` (each with a `time`) around `time`.
template <class Key>
KeySpan keySpanOf(const std::vector<Key>& keys, float time, Interpolation interpolation, Wrap wrap) {
    std::vector<float> times;
    times.reserve(keys.size());
    for (const Key& k : keys) times.push_back(k.time);
    return findKeySpan(times, time, interpolation, wrap);
}

}  // namespace

KeySpan findKeySpan(std::span<const float> keyTimes, float time, Interpolation interpolation, Wrap wrap) {
    const float t = wrapTime(time, keyTimes.front(), keyTimes.back(), wrap);
    // The first key later than t; the span is the key before it and it.
    const auto later = std::upper_bound(keyTimes.begin(), keyTimes.end(), t);
    if (later == keyTimes.begin()) return {0, 0, 0.0f};
    if (later == keyTimes.end()) return {keyTimes.size() - 1, keyTimes.size() - 1, 0.0f};
    const auto to = static_cast<std::size_t>(later - keyTimes.begin());
    const float t0 = keyTimes[to - 1], t1 = keyTimes[to];
    return {to - 1, to, ease((t - t0) / (t1 - t0), interpolation)};
}

Transform TransformTrack::at(float time) const {
    const KeySpan span = keySpanOf(keys, time, interpolation, wrap);
    const TransformKey& a = keys[span.from];
    const TransformKey& b = keys[span.to];
    const float s = span.fraction;
    return Transform::translate(mixKeys(a.translate, b.translate, s)) * slerp(a.rotation, b.rotation, s).toTransform() *
           Transform::scale(mixKeys(a.scale, b.scale, s));
}

Light LightTrack::at(const Light& base, float time) const {
    const KeySpan span = keySpanOf(keys, time, interpolation, wrap);
    const LightKey& a = keys[span.from];
    const LightKey& b = keys[span.to];
    const float s = span.fraction;
    Light posed = base;
    posed.position = mixKeys(a.position, b.position, s);
    const Vec3 direction = mixKeys(a.direction, b.direction, s);
    // Opposite directions blend through zero at the midpoint: keep the nearer key's.
    posed.direction = length(direction) > 1e-6f ? normalize(direction) : (s < 0.5f ? a.direction : b.direction);
    posed.intensity = mixKeys(a.intensity, b.intensity, s);
    return posed;
}

MeshSequence::MeshSequence(std::vector<std::vector<Vec3>> frames, float fps, Wrap wrap)
    : frames_(std::move(frames)), fps_(fps), wrap_(wrap) {}

void MeshSequence::positionsAt(float time, std::span<Vec3> out) const {
    const auto count = static_cast<float>(frames_.size());
    float f = time * fps_;
    // Looping blends the last frame back into the first.
    f = wrap_ == Wrap::Loop ? f - count * std::floor(f / count) : std::clamp(f, 0.0f, count - 1.0f);
    const auto from = std::min(static_cast<std::size_t>(f), frames_.size() - 1);
    const std::size_t to = from + 1 == frames_.size() ? (wrap_ == Wrap::Loop ? 0 : from) : from + 1;
    const float s = f - static_cast<float>(from);
    const std::vector<Vec3>& a = frames_[from];
    const std::vector<Vec3>& b = frames_[to];
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = s == 0.0f ? a[i] : mixKeys(a[i], b[i], s);
}

float SceneAnimation::duration() const {
    float longest = 0.0f;
    for (const ObjectAnimation& a : objects) {
        if (a.transform) longest = std::max(longest, a.transform->keys.back().time);
        if (a.deformation) longest = std::max(longest, a.deformation->duration());
    }
    for (const LightTrack& t : lights) longest = std::max(longest, t.keys.back().time);
    return longest;
}

const ObjectAnimation* SceneAnimation::forObject(int object) const {
    for (const ObjectAnimation& a : objects)
        if (a.object == object) return &a;
    return nullptr;
}

}  // namespace raycache
