#pragma once

#include <span>

#include "ball.h"
#include "sphys/tools/mesh_query.h"

namespace sphys::tools::build {

// Bradshaw's error of a sphere (Bradshaw & O'Sullivan 2004, §3.2): how far it pokes out of the
// object, approximated from its centre as radius + signed distance (radius - depth inside,
// radius + distance outside).
class ErrorMeasure {
 public:
  explicit ErrorMeasure(const MeshQuery& query);

  [[nodiscard]] Vec3d closest_point(const Vec3d& p) const { return query_.closest_point(p); }
  // Negative inside. unit: m
  [[nodiscard]] double signed_distance(const Vec3d& p) const;
  [[nodiscard]] double error(const Ball& ball) const {
    return ball.radius + signed_distance(ball.center);
  }
  // The ball around `points` with the least error: its centre moved by pattern search (from
  // `start` or from the points' smallest enclosing ball, whichever is better) to trade radius
  // against depth.
  [[nodiscard]] Ball optimise(const Ball& start, std::span<const Vec3d> points) const;
  [[nodiscard]] Box3d bounds() const { return bounds_; }

 private:
  const MeshQuery& query_;
  Box3d bounds_;
};

}  // namespace sphys::tools::build
