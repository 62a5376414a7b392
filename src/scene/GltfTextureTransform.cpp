#include "scene/GltfTextureTransform.h"

#include <assimp/material.h>

#include <cmath>

namespace raycache {

GltfTextureTransform GltfTextureTransform::fromAssimp(const aiUVTransform& assimp) {
    // Assimp stores rotation' = -rotation, scale as is, and a translation
    // that folds in the change of origin and rotation centre:
    //   t.x = sx/2 (-cos r + sin r + 1) + offset.x
    //   t.y = sy/2 (sin r + cos r - 1) + 1 - sy - offset.y
    GltfTextureTransform t;
    t.rotation = -static_cast<float>(assimp.mRotation);
    t.scale = {static_cast<float>(assimp.mScaling.x), static_cast<float>(assimp.mScaling.y)};
    const float c = std::cos(t.rotation), s = std::sin(t.rotation);
    t.offset[0] = static_cast<float>(assimp.mTranslation.x) - 0.5f * t.scale[0] * (-c + s + 1.0f);
    t.offset[1] = 0.5f * t.scale[1] * (s + c - 1.0f) + 1.0f - t.scale[1] - static_cast<float>(assimp.mTranslation.y);
    return t;
}

std::array<float, 2> GltfTextureTransform::apply(const std::array<float, 2>& assimpUv) const {
    const float u = assimpUv[0], v = 1.0f - assimpUv[1];  // back to glTF's space
    const float c = std::cos(rotation), s = std::sin(rotation);
    // The extension's matrix: translation * rotation(cos, sin; -sin, cos) * scale.
    const float su = scale[0] * u, sv = scale[1] * v;
    const float tu = c * su + s * sv + offset[0];
    const float tv = -s * su + c * sv + offset[1];
    return {tu, 1.0f - tv};
}

}  // namespace raycache
