#include "scene/ObjectBounds.h"

#include <algorithm>

namespace raycache {

Box3 worldBounds(const SceneObject& object) {
    Box3 box;
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
        const Vec3 r{sphere->radius, sphere->radius, sphere->radius};
        box.add(sphere->center - r);
        box.add(sphere->center + r);
    } else if (const auto* mesh = std::get_if<MeshShape>(&object.shape); mesh && mesh->mesh) {
        for (const Vec3& p : mesh->mesh->positions) box.add(p);
    }
    return box;
}

float relativeMargin(const Box3& box, float fraction) {
    const float extent = std::max({maxComponent(max(-box.lo, box.lo)), maxComponent(max(-box.hi, box.hi)), 1.0f});
    return fraction * extent;
}

namespace {

Box3 grownRelative(const Box3& box, float fraction) { return box.grown(relativeMargin(box, fraction)); }

}  // namespace

PartedBounds PartedBounds::grownRelative(float fraction) const {
    PartedBounds out;
    out.whole = raycache::grownRelative(whole, fraction);
    if (isBall()) {
        // Grown by the same margin as its box.
        out.ballCentre = ballCentre;
        out.ballRadius = ballRadius + relativeMargin(whole, fraction);
    }
    for (const Box3& part : parts) out.parts.push_back(raycache::grownRelative(part, fraction));
    for (const Box3& group : groups) out.groups.push_back(raycache::grownRelative(group, fraction));
    return out;
}

PartedBounds PartedBounds::shifted(const Vec3& offset) const {
    PartedBounds out = *this;
    out.whole = whole.shifted(offset);
    out.ballCentre = ballCentre + offset;
    for (Box3& part : out.parts) part = part.shifted(offset);
    for (Box3& group : out.groups) group = group.shifted(offset);
    return out;
}

PartedBounds partedBounds(const SceneObject& object, int trianglesPerPart) {
    PartedBounds out{worldBounds(object), {}};
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
        out.ballCentre = sphere->center;
        out.ballRadius = sphere->radius;
    }
    const auto* mesh = std::get_if<MeshShape>(&object.shape);
    if (!mesh || !mesh->mesh || trianglesPerPart <= 0) return out;
    const auto& triangles = mesh->mesh->triangles;
    const auto& positions = mesh->mesh->positions;
    const auto per = static_cast<std::size_t>(trianglesPerPart);
    if (triangles.size() <= per) return out;
    for (std::size_t begin = 0; begin < triangles.size(); begin += per) {
        Box3 part;
        for (std::size_t t = begin; t < std::min(begin + per, triangles.size()); ++t)
            for (const std::uint32_t v : triangles[t]) part.add(positions[v]);
        out.parts.push_back(part);
    }
    for (std::size_t p = 0; p < out.parts.size(); ++p) {
        if (p % PartedBounds::kPartsPerGroup == 0) out.groups.emplace_back();
        out.groups.back().add(out.parts[p]);
    }
    return out;
}

}  // namespace raycache
