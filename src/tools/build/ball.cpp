#include "ball.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace sphys::tools::build {
namespace {

// The smallest ball with all of `support` (at most 4 points) on its boundary.
Ball ball_through(std::span<const Vec3d> support) {
  switch (support.size()) {
    case 0:
      return {};
    case 1:
      return {support[0], 0.0};
    case 2:
      return {0.5 * (support[0] + support[1]), 0.5 * (support[1] - support[0]).norm()};
    case 3: {
      // Circumcircle of a triangle, in its plane.
      const Vec3d a = support[1] - support[0];
      const Vec3d b = support[2] - support[0];
      const Vec3d axb = a.cross(b);
      const double denominator = 2.0 * axb.squaredNorm();
      if (denominator <= 0.0) {  // collinear: the two farthest points span the ball
        Ball best = ball_through(support.first(2));
        for (const Ball& c : {ball_through(std::array{support[0], support[2]}),
                              ball_through(std::array{support[1], support[2]})}) {
          if (c.radius > best.radius) best = c;
        }
        return best;
      }
      const Vec3d offset =
          (b.squaredNorm() * axb.cross(a) + a.squaredNorm() * b.cross(axb)) / denominator;
      return {support[0] + offset, offset.norm()};
    }
    default: {
      // Circumsphere of a tetrahedron: solve 2 (p_i - p_0) . x = |p_i - p_0|^2.
      Eigen::Matrix3d m;
      Vec3d rhs;
      for (int i = 0; i < 3; ++i) {
        const Vec3d d = support[static_cast<std::size_t>(i) + 1] - support[0];
        m.row(i) = 2.0 * d.transpose();
        rhs[i] = d.squaredNorm();
      }
      const Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
      if (!lu.isInvertible()) return ball_through(support.first(3));  // coplanar
      const Vec3d offset = lu.solve(rhs);
      return {support[0] + offset, offset.norm()};
    }
  }
}

// Welzl's move-to-front recursion, iterative over the points. Numerical slack keeps points
// that sit on the boundary from triggering endless rebuilds.
Ball welzl(std::vector<Vec3d>& points, std::size_t count, std::vector<Vec3d>& support) {
  Ball ball = ball_through(support);
  if (support.size() == 4) return ball;
  for (std::size_t i = 0; i < count; ++i) {
    const double slack = 1e-12 * (1.0 + ball.radius);
    if (ball.contains(points[i], slack)) continue;
    support.push_back(points[i]);
    ball = welzl(points, i, support);
    support.pop_back();
    // Move to front: points that forced a rebuild are tried first next time.
    std::rotate(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(i),
                points.begin() + static_cast<std::ptrdiff_t>(i) + 1);
  }
  return ball;
}

}  // namespace

Ball min_enclosing_ball(std::span<const Vec3d> points, std::uint64_t seed) {
  std::vector<Vec3d> shuffled(points.begin(), points.end());
  std::mt19937_64 rng(seed);
  // Fisher-Yates with our own index draw: std::shuffle's use of the engine is unspecified.
  for (std::size_t i = shuffled.size(); i > 1; --i) {
    std::swap(shuffled[i - 1], shuffled[rng() % i]);
  }
  std::vector<Vec3d> support;
  support.reserve(4);
  Ball ball = welzl(shuffled, shuffled.size(), support);
  // Guard against rounding: the ball must contain every point.
  for (const Vec3d& p : points) {
    ball.radius = std::max(ball.radius, (p - ball.center).norm());
  }
  return ball;
}

std::vector<Vec3d> evenly_spread_directions(std::size_t count) {
  const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const double n = static_cast<double>(count);
  std::vector<Vec3d> directions(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double kd = static_cast<double>(k);
    const double z = 1.0 - (2.0 * kd + 1.0) / n;
    const double ring = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden_angle * kd;
    directions[k] = Vec3d(ring * std::cos(phi), ring * std::sin(phi), z);
  }
  return directions;
}

}  // namespace sphys::tools::build
