#pragma once

#include <cmath>

#include "sphys/math.h"

namespace sphys {

// A fixed tangent basis of a unit normal, so that the friction impulses kept in world space
// project back onto the same directions from step to step.
inline void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
  // 1/√3: some coordinate of a unit vector is at least this large, so the cross product below
  // never degenerates.
  if (std::abs(n.x()) >= 0.57735f) {
    t1 = Vec3(n.y(), -n.x(), 0.0f).normalized();
  } else {
    t1 = Vec3(0.0f, n.z(), -n.y()).normalized();
  }
  t2 = n.cross(t1);
}

}  // namespace sphys
