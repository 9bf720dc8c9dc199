#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools::build {

// A sphere in double precision, as the builders work with it.
struct Ball {
  Vec3d center = Vec3d::Zero();
  double radius = 0.0;

  [[nodiscard]] bool contains(const Vec3d& p, double slack = 0.0) const {
    return (p - center).squaredNorm() <= (radius + slack) * (radius + slack);
  }
};

// A radius a hair larger, so that a point at exactly `radius` from the centre passes
// Ball::contains despite rounding.
[[nodiscard]] inline double padded_radius(double radius) { return radius * (1.0 + 1e-12) + 1e-15; }

// The smallest ball containing every point (Welzl's algorithm, expected linear time; the points
// are visited in a shuffled order fixed by `seed`). An empty set gives a zero ball at the origin.
[[nodiscard]] Ball min_enclosing_ball(std::span<const Vec3d> points, std::uint64_t seed = 1);

// `count` unit vectors spread evenly over the sphere (a spherical Fibonacci lattice): the largest
// protrusion found at them misses a ball's true one by no more than their spacing allows, which
// random directions would not promise.
[[nodiscard]] std::vector<Vec3d> evenly_spread_directions(std::size_t count);

}  // namespace sphys::tools::build
