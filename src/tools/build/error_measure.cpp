#include "error_measure.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sphys::tools::build {
namespace {

// Pattern search of ErrorMeasure::optimise: first step a quarter of the radius, stop at a
// thousandth of it or after this many evaluations.
constexpr double kFirstStep = 0.25;
constexpr double kLastStep = 1e-3;
constexpr int kMaxEvaluations = 64;

}  // namespace

ErrorMeasure::ErrorMeasure(const MeshQuery& query)
    : query_(query), bounds_(query.mesh().bounds()) {}

double ErrorMeasure::signed_distance(const Vec3d& p) const {
  const double distance = (query_.closest_point(p) - p).norm();
  return query_.inside(p) ? -distance : distance;
}

Ball ErrorMeasure::optimise(const Ball& start, std::span<const Vec3d> points) const {
  if (points.empty()) return start;
  struct State {
    Vec3d center;
    double radius = 0.0;
    Vec3d far_point;
    Vec3d inward;
    double error = 0.0;
  };
  const auto evaluate = [&](const Vec3d& c) {
    State s{c, 0.0, c, Vec3d::Zero(), 0.0};
    double farthest = 0.0;
    for (const Vec3d& p : points) {
      const double d = (p - c).squaredNorm();
      if (d > farthest) {
        farthest = d;
        s.far_point = p;
      }
    }
    s.radius = std::sqrt(farthest);
    const Vec3d away = c - query_.closest_point(c);
    const double distance = away.norm();
    const bool inside = query_.inside(c);
    if (distance > 0.0) s.inward = (inside ? away : Vec3d(-away)) / distance;
    s.error = s.radius + (inside ? -distance : distance);
    return s;
  };
  State best = evaluate(start.center);
  if (const State enclosing = evaluate(min_enclosing_ball(points).center);
      enclosing.error < best.error) {
    best = enclosing;
  }
  double step = kFirstStep * best.radius;
  const double last_step = kLastStep * best.radius;
  int evaluations = 2;
  while (step > last_step && evaluations < kMaxEvaluations) {
    // The two forces at play first, radius (toward the farthest point) and depth (inward), then
    // their sum, then the axes for where both are blocked.
    const Vec3d toward_far = (best.far_point - best.center).stableNormalized();
    const std::array<Vec3d, 9> directions = {
        toward_far,      best.inward,     (toward_far + best.inward).stableNormalized(),
        Vec3d::UnitX(),  -Vec3d::UnitX(), Vec3d::UnitY(),
        -Vec3d::UnitY(), Vec3d::UnitZ(),  -Vec3d::UnitZ()};
    bool improved = false;
    for (const Vec3d& d : directions) {
      if (d.isZero() || evaluations >= kMaxEvaluations) continue;
      const State trial = evaluate(best.center + step * d);
      ++evaluations;
      if (trial.error < best.error) {
        best = trial;
        improved = true;
        break;
      }
    }
    if (!improved) step *= 0.5;
  }
  return {best.center, best.radius};
}

}  // namespace sphys::tools::build
