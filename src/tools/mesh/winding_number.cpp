#include "sphys/tools/winding_number.h"

#include <cmath>
#include <cstddef>
#include <numbers>

namespace sphys::tools {

// Signed solid angle that triangle (a, b, c), given relative to the viewpoint, subtends there, by
// Van Oosterom & Strackee, "The Solid Angle of a Plane Triangle" (IEEE Trans. Biomed. Eng. 30,
// 1983): tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|). atan2 keeps the
// quadrant, so Ω spans (-2π, 2π]; it is positive when the viewpoint is behind the triangle (on
// the side its counter-clockwise normal points away from).
double triangle_solid_angle(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double la = a.norm();
  const double lb = b.norm();
  const double lc = c.norm();
  // The viewpoint is a corner: the angle has no limit there, and 0 keeps the sum finite.
  if (la == 0.0 || lb == 0.0 || lc == 0.0) return 0.0;
  const double triple = a.dot(b.cross(c));
  // In the triangle's plane: 0 is right outside the triangle, and on it 0 is the mean of the ±2π
  // on either side, so a closed surface reads 1/2 on itself instead of 0 or 1 by rounding.
  if (triple == 0.0) return 0.0;
  const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2.0 * std::atan2(triple, denominator);
}

double winding_number(const TriangleMesh& mesh, const Vec3d& p) {
  double total = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    total +=
        triangle_solid_angle(mesh.corner(t, 0) - p, mesh.corner(t, 1) - p, mesh.corner(t, 2) - p);
  }
  return total / (4.0 * std::numbers::pi);
}

}  // namespace sphys::tools
