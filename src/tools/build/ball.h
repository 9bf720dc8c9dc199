#pragma once

#include <span>

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

// The smallest ball containing every point (Welzl's algorithm, expected linear time; the points
// are visited in a shuffled order fixed by `seed`). An empty set gives a zero ball at the origin.
[[nodiscard]] Ball min_enclosing_ball(std::span<const Vec3d> points, std::uint64_t seed = 1);

}  // namespace sphys::tools::build
