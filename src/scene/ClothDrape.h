#pragma once
// A square sheet that falls onto a sphere, drapes over it and the floor, and
// lifts again: the procedural deforming mesh of the built-in `cloth` scene.
#include "scene/Animation.h"

namespace raycache {

struct ClothDrapeShape {
    Vec3 sphereCenter{0.0f, 1.0f, 0.0f};
    float sphereRadius = 1.0f;
    float halfSize = 2.5f;    // the sheet spans ±halfSize in x and z around the sphere's centre
    float height = 3.2f;      // where the flat sheet hangs
    float floorY = 0.0f;      // the draped sheet spreads out on this plane
    int cells = 212;          // cells per side: 2 * 212² = 89 888 triangles
    float period = 4.0f;      // seconds from flat to draped and back
};

class ClothDrape final : public MeshDeformation {
public:
    explicit ClothDrape(const ClothDrapeShape& shape);
    // The flat sheet (with normals and uvs), the shape at time 0.
    TriangleMesh restMesh() const;
    std::size_t vertexCount() const override;
    float duration() const override { return shape_.period; }
    void positionsAt(float time, std::span<Vec3> out) const override;

private:
    // Where the sheet point at (x, z) from the centre lies when fully draped:
    // over the sphere along its arc length, then straight down, then out
    // along the floor, so every radial line keeps its length.
    Vec3 drapedPoint(float x, float z) const;

    ClothDrapeShape shape_;
};

}  // namespace raycache
