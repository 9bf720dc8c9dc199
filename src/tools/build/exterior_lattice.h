#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "ball.h"
#include "sphys/tools/mesh_query.h"

namespace sphys::tools::build {

// The space around a mesh as a regular lattice of points, each with its signed distance to the
// surface: what the outside-volume pass counts. A lattice point stands for a cube of side
// spacing(), so the number of lattice points outside the mesh inside a union of balls, times
// spacing()³, estimates the union's volume outside the mesh, and how far it pokes out is read
// from the distances between the points.
class ExteriorLattice {
 public:
  // About `target_points` points over the mesh's bounding box grown by `margin` on every side
  // (unit: m). Balls reaching farther than `margin` from the mesh are seen only up to it.
  ExteriorLattice(const MeshQuery& query, std::size_t target_points, double margin);

  // The same with each point's position: visit(index, position).
  template <typename Visit>
  void for_each_outside_at(const Ball& ball, const Visit& visit) const {
    const auto nx = static_cast<std::size_t>(dims_[0]);
    const auto ny = static_cast<std::size_t>(dims_[1]);
    for_each_outside(ball, [&](std::size_t index, double) {
      visit(index, origin_ + spacing_ * Vec3d(static_cast<double>(index % nx),
                                              static_cast<double>(index / nx % ny),
                                              static_cast<double>(index / (nx * ny))));
    });
  }

  // Calls visit(index, signed_distance) for every lattice point inside `ball` that lies outside
  // the mesh. Indices are below size().
  template <typename Visit>
  void for_each_outside(const Ball& ball, const Visit& visit) const {
    int lo[3];
    int hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = std::max(0, static_cast<int>(std::ceil(
                                 (ball.center[axis] - ball.radius - origin_[axis]) / spacing_)));
      hi[axis] = std::min(dims_[axis] - 1,
                          static_cast<int>(std::floor(
                              (ball.center[axis] + ball.radius - origin_[axis]) / spacing_)));
    }
    const double r2 = ball.radius * ball.radius;
    for (int z = lo[2]; z <= hi[2]; ++z) {
      const double dz = origin_[2] + z * spacing_ - ball.center[2];
      for (int y = lo[1]; y <= hi[1]; ++y) {
        const double dy = origin_[1] + y * spacing_ - ball.center[1];
        const double rest = r2 - dz * dz - dy * dy;
        if (rest < 0.0) continue;
        // The row's chord through the ball, so that only points inside are visited.
        const double half = std::sqrt(rest);
        const int x0 = std::max(
            lo[0], static_cast<int>(std::ceil((ball.center[0] - half - origin_[0]) / spacing_)));
        const int x1 = std::min(
            hi[0], static_cast<int>(std::floor((ball.center[0] + half - origin_[0]) / spacing_)));
        const std::size_t row = (static_cast<std::size_t>(z) * static_cast<std::size_t>(dims_[1]) +
                                 static_cast<std::size_t>(y)) *
                                static_cast<std::size_t>(dims_[0]);
        for (int x = x0; x <= x1; ++x) {
          const std::size_t index = row + static_cast<std::size_t>(x);
          const float distance = distance_[index];
          if (distance > 0.0F) visit(index, static_cast<double>(distance));
        }
      }
    }
  }

  // The part of this lattice around `region`, with `factor` times as many points along each
  // axis, their distances interpolated from this lattice's (distance_at): a fine lattice for the
  // small balls of one node, costing no distance query.
  [[nodiscard]] ExteriorLattice refined(int factor, const Box3d& region) const;

  // The signed distance at p, interpolated from the 8 lattice points around it (trilinear); +∞
  // beyond the lattice. unit: m
  [[nodiscard]] double distance_at(const Vec3d& p) const;
  // How far the ball pokes out of the mesh: the largest interpolated distance over its boundary at
  // the given unit directions. unit: m
  [[nodiscard]] double protrusion(const Ball& ball, std::span<const Vec3d> directions) const;

  [[nodiscard]] std::size_t size() const { return distance_.size(); }
  [[nodiscard]] double spacing() const { return spacing_; }  // unit: m
  [[nodiscard]] double margin() const { return margin_; }    // unit: m

 private:
  ExteriorLattice() = default;

  Vec3d origin_;
  double spacing_ = 0.0;
  double margin_ = 0.0;
  int dims_[3] = {1, 1, 1};
  std::vector<float> distance_;  // signed, per point, x fastest. unit: m
};

}  // namespace sphys::tools::build
