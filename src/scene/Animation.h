#pragma once
// How a scene changes with time: keyframed object transforms and lights,
// and deforming meshes. Times are in seconds; a frame's time is its index
// divided by the frames per second (Scene::fps, `--fps`).
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/Quaternion.h"
#include "core/Rgb.h"
#include "core/Transform.h"
#include "core/Vec3.h"
#include "scene/Light.h"
#include "scene/SceneObject.h"
#include "scene/TriangleMesh.h"

namespace raycache {

// Longest stretch of animation time a file or option may name, seconds.
inline constexpr float kMaxAnimationSeconds = 1.0e6f;

// Between two keys: Linear moves at a constant rate; Smooth eases in and
// out of every key (smoothstep on the fraction), so motion starts and stops
// without a jolt and never overshoots a key.
enum class Interpolation { Linear, Smooth };
// Past the last key: Loop starts again from the first key, Clamp holds the last.
enum class Wrap { Loop, Clamp };

// The two keys around `time` and how far it lies from the first to the
// second (0..1, already eased). `keyTimes` is sorted, non-empty.
struct KeySpan {
    std::size_t from = 0, to = 0;
    float fraction = 0.0f;
};
KeySpan findKeySpan(std::span<const float> keyTimes, float time, Interpolation interpolation, Wrap wrap);

struct TransformKey {
    float time = 0.0f;
    Vec3 translate{0.0f, 0.0f, 0.0f};
    Quaternion rotation;
    Vec3 scale{1.0f, 1.0f, 1.0f};
};

// Translation and scale interpolate per component, rotation by slerp (the
// shorter way between two keys: a full turn needs keys less than 180° apart).
struct TransformTrack {
    std::vector<TransformKey> keys;  // sorted by time; at least one
    Interpolation interpolation = Interpolation::Linear;
    Wrap wrap = Wrap::Loop;

    // translate * rotation * scale at `time`.
    Transform at(float time) const;
};

struct LightKey {
    float time = 0.0f;
    Vec3 position;
    Vec3 direction;
    Rgb intensity;
};

struct LightTrack {
    int light = 0;  // index into Scene::lights
    std::vector<LightKey> keys;  // sorted by time; at least one; every field set
    Interpolation interpolation = Interpolation::Linear;
    Wrap wrap = Wrap::Loop;

    // `base` with position, direction (renormalized) and intensity at `time`.
    Light at(const Light& base, float time) const;
};

// A mesh whose vertices move (same triangles throughout).
class MeshDeformation {
public:
    virtual ~MeshDeformation() = default;
    virtual std::size_t vertexCount() const = 0;
    // Seconds after which the motion repeats (or stops changing).
    virtual float duration() const = 0;
    // Vertex positions at `time` in the object's own space, before its
    // keyframed transform; out.size() == vertexCount().
    virtual void positionsAt(float time, std::span<Vec3> out) const = 0;
};

// A sequence of meshes with one topology, one per frame at `fps`, blended
// linearly between frames.
class MeshSequence final : public MeshDeformation {
public:
    // Every frame has the same vertex count (the loader checks); at least one.
    MeshSequence(std::vector<std::vector<Vec3>> frames, float fps, Wrap wrap);
    std::size_t vertexCount() const override { return frames_.front().size(); }
    float duration() const override { return static_cast<float>(frames_.size()) / fps_; }
    void positionsAt(float time, std::span<Vec3> out) const override;

private:
    std::vector<std::vector<Vec3>> frames_;
    float fps_;
    Wrap wrap_;
};

// One animated object: its shape at rest in its own space and what moves it.
// Its world shape at time t is the rest shape deformed at t, then placed by
// transform.at(t) (identity without keys).
struct ObjectAnimation {
    int object = 0;  // index into Scene::objects
    std::optional<TransformTrack> transform;
    std::shared_ptr<const MeshDeformation> deformation;  // meshes only
    std::variant<Sphere, MeshShape> restShape;
    Vec3 restOrigin;  // the caching cube's centre before the transform

    Transform placementAt(float time) const { return transform ? transform->at(time) : Transform{}; }
};

struct SceneAnimation {
    std::vector<ObjectAnimation> objects;  // one per animated object, by object index
    std::vector<LightTrack> lights;

    bool empty() const { return objects.empty() && lights.empty(); }
    // The latest key time or deformation length: the span worth scrubbing through.
    float duration() const;
    const ObjectAnimation* forObject(int object) const;
};

}  // namespace raycache
