#pragma once

// Thin names over Eigen for the runtime. The runtime works in float (it is read every step);
// construction and mass properties work in double (see sphys/tools).

#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

namespace sphys {

using Vec3 = Eigen::Vector3f;     // a point, direction or vector quantity, float
using Mat3 = Eigen::Matrix3f;     // a 3×3 matrix (rotations, inertia tensors), float
using Quat = Eigen::Quaternionf;  // a rotation, of unit length, float

// A rigid transform: rotation then translation, x_world = rotation * x_body + translation.
struct Transform {
  Quat rotation = Quat::Identity();  // body axes to world axes
  Vec3 translation = Vec3::Zero();   // where the body origin is in the world. unit: m

  // The world position of a point given in the body frame.
  [[nodiscard]] Vec3 apply(const Vec3& body_point) const {
    return rotation * body_point + translation;
  }
};

// The inverse of a symmetric positive semi-definite 3×3 (an inertia tensor, or a sum of inverse
// inertias), or zero where it has none (a point mass cannot be turned). The matrix is first
// scaled by a power of two to entries near 1: in float the determinant of a 1 km, 10⁹ kg body's
// inertia (about 1e14 kg·m², cubed 1e42) overflows, and a 1 mm, 1 mg body's underflows, where the
// inverse itself fits. Scaling by a power of two is exact, so wherever the plain float inverse
// neither overflows nor underflows this is that inverse, bit for bit.
[[nodiscard]] inline Mat3 inverse_or_zero(const Mat3& matrix) {
  const float largest = matrix.cwiseAbs().maxCoeff();
  if (!(largest > 0.0f) || !std::isfinite(largest)) return Mat3::Zero();
  const float scale = std::ldexp(1.0f, -std::ilogb(largest));
  const Mat3 scaled = matrix * scale;
  if (!(scaled.determinant() > 0.0f)) return Mat3::Zero();
  return scaled.inverse() * scale;
}

// Axis-aligned bounding box. A default-constructed box is empty (min > max) so that the first
// extend() sets it.
struct Aabb {
  Vec3 min = Vec3::Constant(std::numeric_limits<float>::infinity());   // low corner. unit: m
  Vec3 max = Vec3::Constant(-std::numeric_limits<float>::infinity());  // high corner. unit: m

  // The smallest box holding the sphere.
  [[nodiscard]] static Aabb around_sphere(const Vec3& center, float radius) {
    return {center.array() - radius, center.array() + radius};
  }
  // True when min > max on some axis: the box holds no point.
  [[nodiscard]] bool empty() const { return (min.array() > max.array()).any(); }
  // Grows the box to hold `point`.
  void extend(const Vec3& point) {
    min = min.cwiseMin(point);
    max = max.cwiseMax(point);
  }
  // Grows the box to hold `other`.
  void extend(const Aabb& other) {
    min = min.cwiseMin(other.min);
    max = max.cwiseMax(other.max);
  }
  // Closed intervals: boxes that touch overlap.
  [[nodiscard]] bool overlaps(const Aabb& other) const {
    return (min.array() <= other.max.array()).all() && (other.min.array() <= max.array()).all();
  }
  // Closed: a point on a face is inside.
  [[nodiscard]] bool contains(const Vec3& point) const {
    return (min.array() <= point.array()).all() && (point.array() <= max.array()).all();
  }
  // Edge lengths, max - min. unit: m
  [[nodiscard]] Vec3 size() const { return max - min; }
  // The midpoint of min and max. unit: m
  [[nodiscard]] Vec3 center() const { return 0.5f * (min + max); }
};

}  // namespace sphys
