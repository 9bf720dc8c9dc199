#include "surface_samples.h"

#include <algorithm>
#include <cmath>

namespace sphys::tools::build {
namespace {

int divisions(const TriangleMesh& mesh, std::size_t t, double spacing) {
  double longest = 0.0;
  for (int k = 0; k < 3; ++k) {
    longest = std::max(longest, (mesh.corner(t, (k + 1) % 3) - mesh.corner(t, k)).norm());
  }
  return std::max(1, static_cast<int>(std::ceil(longest / spacing)));
}

}  // namespace

SurfaceSamples sample_surface(const TriangleMesh& mesh, std::size_t target_count) {
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) area += 0.5 * mesh.area_normal(t).norm();
  // A triangle split into pieces of side s brings about one grid point per piece area s²·√3/4.
  const double per_sample = area / static_cast<double>(std::max<std::size_t>(target_count, 1));
  SurfaceSamples samples;
  samples.spacing = std::sqrt(per_sample * 4.0 / std::sqrt(3.0));

  // The grid points of each triangle split n ways along every edge: pieces have edges of at most
  // `spacing`, so every surface point is within spacing/√3 of a grid point. Points on shared
  // edges appear once per triangle; the repetition is harmless and keeps triangles independent.
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int n = divisions(mesh, t, samples.spacing);
    const Vec3d a = mesh.corner(t, 0);
    const Vec3d du = (mesh.corner(t, 1) - a) / n;
    const Vec3d dv = (mesh.corner(t, 2) - a) / n;
    for (int u = 0; u <= n; ++u) {
      for (int v = 0; u + v <= n; ++v) {
        samples.points.push_back(a + u * du + v * dv);
        samples.triangle.push_back(static_cast<std::uint32_t>(t));
      }
    }
  }
  return samples;
}

}  // namespace sphys::tools::build
