#include "scene/CameraPath.h"

#include <algorithm>

#include "core/Transform.h"

namespace raycache {

namespace {
Vec3 lerp(const Vec3& a, const Vec3& b, float t) { return a + (b - a) * t; }
const Vec3 kYAxis{0.0f, 1.0f, 0.0f};
}  // namespace

Camera CameraPath::cameraAt(const Camera& base, int frame) const {
    Camera cam = base;
    const float degrees = degreesPerFrame * static_cast<float>(frame);
    switch (kind) {
    case CameraPathKind::Static:
        break;
    case CameraPathKind::Orbit: {
        const Transform r = Transform::rotate(kYAxis, degrees);
        cam.position = center + r.applyToVector(base.position - center);
        cam.lookAt = center + r.applyToVector(base.lookAt - center);
        break;
    }
    case CameraPathKind::Pan: {
        const Transform r = Transform::rotate(kYAxis, degrees);
        cam.lookAt = base.position + r.applyToVector(base.lookAt - base.position);
        break;
    }
    case CameraPathKind::Keyframes: {
        if (keyframes.empty()) break;
        const int segments = static_cast<int>(keyframes.size()) - 1;
        const int perSegment = std::max(1, framesPerSegment);
        const int segment = std::min(frame / perSegment, segments);
        if (segment >= segments) return keyframes.back();
        const float t = static_cast<float>(frame - segment * perSegment) / static_cast<float>(perSegment);
        const Camera& a = keyframes[static_cast<std::size_t>(segment)];
        const Camera& b = keyframes[static_cast<std::size_t>(segment) + 1];
        cam.position = lerp(a.position, b.position, t);
        cam.lookAt = lerp(a.lookAt, b.lookAt, t);
        cam.up = normalize(lerp(a.up, b.up, t));
        cam.verticalFovDeg = a.verticalFovDeg + (b.verticalFovDeg - a.verticalFovDeg) * t;
        break;
    }
    }
    return cam;
}

}  // namespace raycache
