#include "shrinking_ball.h"

#include <cmath>

namespace sphys::tools::build {
namespace {

// Bisection steps on the radius: 2^-30 of max_radius, far below any sample spacing.
constexpr int kBisectionSteps = 30;
// A ball counts as empty while the surface is no nearer its centre than its radius less this
// fraction of it: the tangent point itself is at the radius, up to rounding.
constexpr double kTouchTolerance = 1e-6;

}  // namespace

std::optional<MedialSphere> shrinking_ball(const Vec3d& point, const Vec3d& outward_normal,
                                           std::uint32_t point_index, double max_radius,
                                           const ErrorMeasure& measure) {
  const Vec3d inward = -outward_normal.stableNormalized();
  if (inward.isZero() || !(max_radius > 0.0)) return std::nullopt;
  const auto empty = [&](double radius) {
    const Vec3d center = point + radius * inward;
    return (measure.closest_point(center) - center).norm() >= radius * (1.0 - kTouchTolerance);
  };
  double low = 0.0;  // empty (a ball of radius 0 holds nothing)
  double high = max_radius;
  if (empty(high)) {
    low = high;
  } else {
    for (int step = 0; step < kBisectionSteps; ++step) {
      const double middle = 0.5 * (low + high);
      (empty(middle) ? low : high) = middle;
    }
  }
  if (!(low > 0.0)) return std::nullopt;
  const Vec3d center = point + low * inward;
  const double signed_distance = measure.signed_distance(center);
  if (!(signed_distance < 0.0)) return std::nullopt;
  MedialSphere sphere;
  sphere.ball = {center, low};
  sphere.error = low + signed_distance;
  sphere.generators = {point_index, point_index, point_index, point_index};
  return sphere;
}

}  // namespace sphys::tools::build
