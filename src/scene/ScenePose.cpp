#include "scene/ScenePose.h"

#include <algorithm>
#include <cmath>

#include "scene/VertexNormals.h"

namespace raycache {

namespace {

bool sameLight(const Light& a, const Light& b) {
    return a.position == b.position && a.direction == b.direction && a.intensity == b.intensity;
}

bool sameShape(const std::variant<Sphere, MeshShape>& a, const std::variant<Sphere, MeshShape>& b) {
    if (a.index() != b.index()) return false;
    if (const auto* sa = std::get_if<Sphere>(&a)) {
        const Sphere& sb = std::get<Sphere>(b);
        return sa->center == sb.center && sa->radius == sb.radius;
    }
    const TriangleMesh& ma = *std::get<MeshShape>(a).mesh;
    const TriangleMesh& mb = *std::get<MeshShape>(b).mesh;
    return ma.positions == mb.positions;
}

}  // namespace

std::variant<Sphere, MeshShape> posedShape(const ObjectAnimation& animation, float time, const Transform& placement) {
    if (const auto* rest = std::get_if<Sphere>(&animation.restShape)) {
        // The loader admits only translation, rotation and uniform scale for
        // spheres, so the length of any transformed unit vector is the scale.
        return Sphere{placement.applyToPoint(rest->center),
                      rest->radius * length(placement.applyToVector(Vec3{1.0f, 0.0f, 0.0f}))};
    }
    const TriangleMesh& rest = *std::get<MeshShape>(animation.restShape).mesh;
    auto mesh = std::make_shared<TriangleMesh>(rest);
    if (animation.deformation) {
        animation.deformation->positionsAt(time, mesh->positions);
        // A deformed mesh's stored normals no longer fit it.
        if (!mesh->normals.empty()) mesh->normals = areaWeightedNormals(*mesh);
    }
    for (Vec3& p : mesh->positions) p = placement.applyToPoint(p);
    for (Vec3& n : mesh->normals) {
        const Vec3 m = placement.applyToNormal(n);
        const float l = length(m);
        n = l > 0.0f ? m * (1.0f / l) : n;
    }
    return MeshShape{std::move(mesh)};
}

SceneChanges poseScene(const Scene& scene, float time, Scene& posed) {
    SceneChanges changes;
    for (const ObjectAnimation& animation : scene.animation.objects) {
        SceneObject& object = posed.objects[static_cast<std::size_t>(animation.object)];
        const Transform placement = animation.placementAt(time);
        // A rigid object's shape follows from its placement alone (an
        // object starts as its rest shape with the identity placement): an
        // unchanged placement needs no copy of the mesh to tell.
        if (!animation.deformation && placement == object.placement) continue;
        std::variant<Sphere, MeshShape> shape = posedShape(animation, time, placement);
        const Vec3 origin = placement.applyToPoint(animation.restOrigin);
        if (placement == object.placement && origin == object.origin && sameShape(shape, object.shape)) continue;
        object.shape = std::move(shape);
        object.placement = placement;
        object.origin = origin;
        changes.objects.push_back(animation.object);
    }
    for (const LightTrack& track : scene.animation.lights) {
        const auto index = static_cast<std::size_t>(track.light);
        const Light light = track.at(scene.lights[index], time);
        if (sameLight(light, posed.lights[index])) continue;
        posed.lights[index] = light;
        changes.lights.push_back(track.light);
    }
    std::sort(changes.objects.begin(), changes.objects.end());
    std::sort(changes.lights.begin(), changes.lights.end());
    return changes;
}

}  // namespace raycache
