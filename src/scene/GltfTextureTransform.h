#pragma once
// KHR_texture_transform: a texture's offset, rotation and scale in glTF's
// texture space (origin at the image's top left corner, v down), which
// Assimp 5.2 hands on converted to its own aiUVTransform (origin at the
// bottom left, rotation about the centre). raycache's textures have no
// transform of their own, so the transform is baked into each object's
// texture coordinates, in the space Assimp gives them (v up).
#include <array>

struct aiUVTransform;

namespace raycache {

struct GltfTextureTransform {
    std::array<float, 2> offset{0.0f, 0.0f};
    float rotation = 0.0f;  // radians, as the extension writes it
    std::array<float, 2> scale{1.0f, 1.0f};

    // The transform as the extension wrote it, undoing Assimp 5.2's
    // conversion (glTF2Importer.cpp, SetMaterialTextureProperty).
    static GltfTextureTransform fromAssimp(const aiUVTransform& assimp);

    // Texture coordinates as Assimp gives them ((u, 1 - v) of the file's
    // (u, v)) through the transform: uv' = T * R * S * uv in glTF's space.
    std::array<float, 2> apply(const std::array<float, 2>& assimpUv) const;

    bool isIdentity() const {
        return offset == std::array<float, 2>{0, 0} && rotation == 0.0f && scale == std::array<float, 2>{1, 1};
    }
    bool operator==(const GltfTextureTransform&) const = default;
};

}  // namespace raycache
