#include "sphys/tools/primitives.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "sphys/error.h"

namespace sphys::tools {
namespace {

// 20·4^8 = 1.3 million triangles: more is a typo, not a test subject.
constexpr int kMaxSubdivisions = 8;

bool positive_finite(double value) { return std::isfinite(value) && value > 0.0; }

// Appends the quad (a, b, c, d), counter-clockwise seen from outside, as two triangles.
void add_quad(std::vector<Triangle>& triangles, std::uint32_t a, std::uint32_t b, std::uint32_t c,
              std::uint32_t d) {
  triangles.push_back({a, b, c});
  triangles.push_back({a, c, d});
}

// The regular icosahedron on the unit sphere. Its 12 vertices are the cyclic permutations of
// (0, ±1, ±φ); its 20 faces are the triples of vertices that are pairwise neighbours (edge length
// 2), each turned so that its normal points away from the centre.
TriangleMesh make_icosahedron() {
  const double phi = std::numbers::phi;
  TriangleMesh mesh;
  for (const double a : {-1.0, 1.0}) {
    for (const double b : {-phi, phi}) {
      mesh.vertices.emplace_back(0.0, a, b);
      mesh.vertices.emplace_back(a, b, 0.0);
      mesh.vertices.emplace_back(b, 0.0, a);
    }
  }
  const auto neighbours = [&](std::uint32_t i, std::uint32_t j) {
    return std::abs((mesh.vertices[i] - mesh.vertices[j]).squaredNorm() - 4.0) < 1e-9;
  };
  const auto n = static_cast<std::uint32_t>(mesh.vertices.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      for (std::uint32_t k = j + 1; k < n; ++k) {
        if (!neighbours(i, j) || !neighbours(j, k) || !neighbours(k, i)) continue;
        mesh.triangles.push_back({i, j, k});
        if (mesh.area_normal(mesh.triangles.size() - 1).dot(mesh.vertices[i]) < 0.0) {
          std::swap(mesh.triangles.back()[1], mesh.triangles.back()[2]);
        }
      }
    }
  }
  for (Vec3d& v : mesh.vertices) v.normalize();
  return mesh;
}

// Splits every triangle into four at its edge midpoints, pushed out onto the unit sphere. A
// midpoint is made once per edge, so neighbouring triangles share it and the mesh stays welded.
void subdivide_on_unit_sphere(TriangleMesh& mesh) {
  std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
  const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
    const auto [it, inserted] =
        midpoints.try_emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
    if (inserted) mesh.vertices.push_back((mesh.vertices[a] + mesh.vertices[b]).normalized());
    return it->second;
  };
  std::vector<Triangle> finer;
  finer.reserve(4 * mesh.triangles.size());
  for (const auto& [a, b, c] : mesh.triangles) {
    const std::uint32_t ab = midpoint(a, b);
    const std::uint32_t bc = midpoint(b, c);
    const std::uint32_t ca = midpoint(c, a);
    finer.push_back({a, ab, ca});
    finer.push_back({b, bc, ab});
    finer.push_back({c, ca, bc});
    finer.push_back({ab, bc, ca});
  }
  mesh.triangles = std::move(finer);
}

}  // namespace

TriangleMesh make_box(const Vec3d& size) {
  if (!positive_finite(size.x()) || !positive_finite(size.y()) || !positive_finite(size.z())) {
    throw Error("make_box: side lengths must be positive and finite");
  }
  TriangleMesh mesh;
  mesh.name = "box";
  // Vertex i has the corner's sign pattern in its bits: bit 0 is +x, bit 1 is +y, bit 2 is +z.
  for (int i = 0; i < 8; ++i) {
    const Vec3d sign((i & 1) != 0 ? 1.0 : -1.0, (i & 2) != 0 ? 1.0 : -1.0,
                     (i & 4) != 0 ? 1.0 : -1.0);
    mesh.vertices.push_back(0.5 * sign.cwiseProduct(size));
  }
  add_quad(mesh.triangles, 0, 4, 6, 2);  // -x
  add_quad(mesh.triangles, 1, 3, 7, 5);  // +x
  add_quad(mesh.triangles, 0, 1, 5, 4);  // -y
  add_quad(mesh.triangles, 2, 6, 7, 3);  // +y
  add_quad(mesh.triangles, 0, 2, 3, 1);  // -z
  add_quad(mesh.triangles, 4, 5, 7, 6);  // +z
  return mesh;
}

TriangleMesh make_icosphere(double radius, int subdivisions) {
  if (!positive_finite(radius)) throw Error("make_icosphere: radius must be positive and finite");
  if (subdivisions < 0 || subdivisions > kMaxSubdivisions) {
    throw Error("make_icosphere: subdivisions must be between 0 and " +
                std::to_string(kMaxSubdivisions));
  }
  TriangleMesh mesh = make_icosahedron();
  for (int level = 0; level < subdivisions; ++level) subdivide_on_unit_sphere(mesh);
  for (Vec3d& v : mesh.vertices) v *= radius;
  mesh.name = "icosphere";
  return mesh;
}

TriangleMesh make_cylinder(double radius, double length, int sides) {
  if (!positive_finite(radius) || !positive_finite(length)) {
    throw Error("make_cylinder: radius and length must be positive and finite");
  }
  if (sides < 3) throw Error("make_cylinder: sides must be at least 3");
  TriangleMesh mesh;
  mesh.name = "cylinder";
  // Vertex 2k is on the bottom rim (z = -length/2), 2k + 1 above it; the caps' centres come last.
  for (int k = 0; k < sides; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / sides;
    for (const double z : {-0.5 * length, 0.5 * length}) {
      mesh.vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
    }
  }
  const auto bottom = [&](int k) { return static_cast<std::uint32_t>(2 * (k % sides)); };
  const auto top = [&](int k) { return bottom(k) + 1; };
  const auto bottom_centre = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, -0.5 * length);
  mesh.vertices.emplace_back(0.0, 0.0, 0.5 * length);
  const std::uint32_t top_centre = bottom_centre + 1;
  for (int k = 0; k < sides; ++k) {
    add_quad(mesh.triangles, bottom(k), bottom(k + 1), top(k + 1), top(k));
    mesh.triangles.push_back({bottom_centre, bottom(k + 1), bottom(k)});
    mesh.triangles.push_back({top_centre, top(k), top(k + 1)});
  }
  return mesh;
}

TriangleMesh make_torus(double major, double minor, int rings, int sides) {
  if (!positive_finite(minor) || !std::isfinite(major) || major <= minor) {
    throw Error("make_torus: radii must be finite with 0 < minor < major");
  }
  if (rings < 3 || sides < 3) throw Error("make_torus: rings and sides must be at least 3");
  TriangleMesh mesh;
  mesh.name = "torus";
  // Ring angle u turns about the y axis; side angle v turns around the tube.
  for (int i = 0; i < rings; ++i) {
    const double u = 2.0 * std::numbers::pi * i / rings;
    for (int j = 0; j < sides; ++j) {
      const double v = 2.0 * std::numbers::pi * j / sides;
      const double rho = major + minor * std::cos(v);
      mesh.vertices.emplace_back(rho * std::cos(u), minor * std::sin(v), rho * std::sin(u));
    }
  }
  const auto index = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % rings) * sides + (j % sides));
  };
  // ∂p/∂v × ∂p/∂u points out of the tube, so stepping v before u is counter-clockwise outside.
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      add_quad(mesh.triangles, index(i, j), index(i, j + 1), index(i + 1, j + 1), index(i + 1, j));
    }
  }
  return mesh;
}

}  // namespace sphys::tools
