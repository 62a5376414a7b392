#pragma once
// Procedural meshes in object space, used by built-in scenes and by scene
// files ("shape": "box", ...). All are closed (except the plane and the
// bowl) and wound counter-clockwise seen from outside.
#include "scene/TriangleMesh.h"

namespace raycache {

// Square in the xz plane, centred at the origin, side 1, normal +y; uv = (x, z) + 0.5.
TriangleMesh makePlane();
// Axis-aligned cube centred at the origin, side 1.
TriangleMesh makeBox();
// Cylinder along y, radius 0.5, from y = -0.5 to 0.5, with caps.
TriangleMesh makeCylinder(int segments = 64);
// Cone along y, base radius 0.5 at y = -0.5, apex at y = 0.5, with a base cap.
TriangleMesh makeCone(int segments = 64);
// Torus around the y axis: ring radius `major`, tube radius `minor`.
TriangleMesh makeTorus(float major = 0.35f, float minor = 0.15f, int ringSegments = 64, int tubeSegments = 32);
// Hemispherical bowl of radius 0.5 opening toward +y (a concave object), with a
// thin wall so it is closed.
TriangleMesh makeBowl(float wallThickness = 0.05f, int segments = 64);

}  // namespace raycache
