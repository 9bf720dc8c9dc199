#pragma once

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Closed, outward-oriented meshes of simple solids, centred at the origin: test subjects with
// known answers, and the ground's box.

// A box with the given full side lengths, 12 triangles.
[[nodiscard]] TriangleMesh make_box(const Vec3d& size);

// An icosphere: the icosahedron subdivided `subdivisions` times (20·4^s triangles), vertices on
// the sphere of the given radius.
[[nodiscard]] TriangleMesh make_icosphere(double radius, int subdivisions);

// A closed cylinder around the z axis (as URDF's), centred at the origin: `sides` quads around,
// each end cap a fan of `sides` triangles. Its vertices lie on the true cylinder, so the true
// surface is at most radius · (1 - cos(π / sides)) outside the mesh.
[[nodiscard]] TriangleMesh make_cylinder(double radius, double length, int sides);

// A torus around the y axis: ring radius `major`, tube radius `minor`, a grid of `rings` by
// `sides` quads split into triangles.
[[nodiscard]] TriangleMesh make_torus(double major, double minor, int rings, int sides);

}  // namespace sphys::tools
