#include "surface_samples.h"

#include <algorithm>
#include <cmath>

namespace sphys::tools::build {
namespace {

// A triangle is sampled in rows (add_rows) when it is longer than kSliverAspect times its width
// (its height over the longest edge, or the spacing when that is larger) and than kLongLattice
// spacings (a lattice of more than about 2,000 points); the triangles of ordinary meshes are
// sampled on the lattice.
constexpr double kSliverAspect = 2.0;
constexpr double kLongLattice = 64.0;

int divisions(const Vec3d& a, const Vec3d& b, const Vec3d& c, double spacing) {
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return std::max(1, static_cast<int>(std::ceil(longest / spacing)));
}

// The grid points of the triangle split n ways along every edge: pieces have edges of at most
// `spacing`, so every point of the triangle is within spacing/√3 of a grid point.
void add_lattice(const Vec3d& a, const Vec3d& b, const Vec3d& c, std::uint32_t triangle,
                 double spacing, SurfaceSamples& samples) {
  const int n = divisions(a, b, c, spacing);
  const Vec3d du = (b - a) / n;
  const Vec3d dv = (c - a) / n;
  for (int u = 0; u <= n; ++u) {
    for (int v = 0; u + v <= n; ++v) {
      samples.points.push_back(a + u * du + v * dv);
      samples.triangle.push_back(triangle);
    }
  }
}

// A sliver (a wire's side, a thin plate's rim) split n ways along every edge would bring n²
// points for n ≈ length / spacing. It is sampled in rows parallel to its longest edge p-q
// instead, rows at most `spacing` apart up to the opposite corner r, points at most `spacing`
// apart along each row: every point of it is within spacing/√2 of a sample, and the samples
// grow with its area.
void add_rows(const Vec3d& p, const Vec3d& q, const Vec3d& r, double height, std::uint32_t triangle,
              double spacing, SurfaceSamples& samples) {
  const int rows = std::max(1, static_cast<int>(std::ceil(height / spacing)));
  for (int row = 0; row <= rows; ++row) {
    const double t = static_cast<double>(row) / rows;
    const Vec3d from = p + t * (r - p);
    const Vec3d to = q + t * (r - q);
    const int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / spacing)));
    for (int step = 0; step <= (row == rows ? 0 : steps); ++step) {
      samples.points.push_back(from + (to - from) * step / steps);
      samples.triangle.push_back(triangle);
    }
  }
}

}  // namespace

SurfaceSamples sample_surface(const TriangleMesh& mesh, std::size_t target_count) {
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) area += 0.5 * mesh.area_normal(t).norm();
  // A triangle split into pieces of side s brings about one grid point per piece area s²·√3/4.
  const double per_sample = area / static_cast<double>(std::max<std::size_t>(target_count, 1));
  SurfaceSamples samples;
  samples.spacing = std::sqrt(per_sample * 4.0 / std::sqrt(3.0));

  // Points on shared edges appear once per triangle; the repetition is harmless and keeps
  // triangles independent.
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto index = static_cast<std::uint32_t>(t);
    int k = 0;  // the longest edge runs from corner k to corner k + 1
    double longest = 0.0;
    for (int e = 0; e < 3; ++e) {
      const double length = (mesh.corner(t, (e + 1) % 3) - mesh.corner(t, e)).norm();
      if (length > longest) {
        longest = length;
        k = e;
      }
    }
    const double height = longest > 0.0 ? mesh.area_normal(t).norm() / longest : 0.0;
    if (longest > kLongLattice * samples.spacing &&
        longest > kSliverAspect * std::max(height, samples.spacing)) {
      add_rows(mesh.corner(t, k), mesh.corner(t, (k + 1) % 3), mesh.corner(t, (k + 2) % 3), height,
               index, samples.spacing, samples);
    } else {
      add_lattice(mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2), index, samples.spacing,
                  samples);
    }
  }
  return samples;
}

}  // namespace sphys::tools::build
