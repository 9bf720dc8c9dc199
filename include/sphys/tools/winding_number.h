#pragma once

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Signed solid angle that triangle (a, b, c), given relative to the viewpoint, subtends there
// (Van Oosterom & Strackee 1983), in (-2π, 2π]; positive when the viewpoint is behind the
// triangle (on the side its counter-clockwise normal points away from); 0 when the viewpoint is
// a corner or in the triangle's plane.
[[nodiscard]] double triangle_solid_angle(const Vec3d& a, const Vec3d& b, const Vec3d& c);

// Generalized winding number (Jacobson, Kavan & Sorkine-Hornung 2013): the signed solid angle the
// surface subtends at p, over 4π. Exactly 1 inside and 0 outside a closed, outward-oriented mesh;
// for a mesh with small holes it degrades smoothly (near 1 deep inside, near 0 far outside, about
// 1/2 across a hole), which makes "w >= 1/2" a robust inside test where ray parity is not.
// Each triangle's angle is Van Oosterom & Strackee's (1983) closed form. On the surface it reads
// the fraction of directions that look inside (1/2 on a face, 1/4 on a box edge): a triangle
// whose plane or corner holds p counts 0, so points on or at vertices never give NaN. Linear in
// the triangle count.
[[nodiscard]] double winding_number(const TriangleMesh& mesh, const Vec3d& p);

// The robust inside test: winding_number(mesh, p) >= 1/2.
[[nodiscard]] inline bool is_inside(const TriangleMesh& mesh, const Vec3d& p) {
  return winding_number(mesh, p) >= 0.5;
}

}  // namespace sphys::tools
