#pragma once
// The check every loaded or repaired mesh gets: one normal per vertex, each
// finite and of unit length. Counts the bad ones and names the first, so that
// a mesh of a million vertices fails with one message, not a million.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

#include "scene/TriangleMesh.h"

namespace raycache {

inline void expectUnitNormals(const TriangleMesh& mesh, float tolerance = 1e-5f) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    std::size_t bad = 0, firstBad = 0;
    for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
        const Vec3& n = mesh.normals[v];
        if (isFinite(n) && std::fabs(length(n) - 1.0f) < tolerance) continue;
        if (bad++ == 0) firstBad = v;
    }
    EXPECT_EQ(bad, 0u) << "normals not finite or not of unit length, the first at vertex " << firstBad;
}

}  // namespace raycache
