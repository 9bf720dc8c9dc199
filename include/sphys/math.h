#pragma once

// Thin names over Eigen for the runtime. The runtime works in float (it is read every step);
// construction and mass properties work in double (see sphys/tools).

#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sphys {

using Vec3 = Eigen::Vector3f;
using Mat3 = Eigen::Matrix3f;
using Quat = Eigen::Quaternionf;

// A rigid transform: rotation then translation, x_world = rotation * x_body + translation.
struct Transform {
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();

  [[nodiscard]] Vec3 apply(const Vec3& body_point) const {
    return rotation * body_point + translation;
  }
};

// Axis-aligned bounding box. A default-constructed box is empty (min > max) so that the first
// extend() sets it.
struct Aabb {
  Vec3 min = Vec3::Constant(std::numeric_limits<float>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<float>::infinity());

  [[nodiscard]] static Aabb around_sphere(const Vec3& center, float radius) {
    return {center.array() - radius, center.array() + radius};
  }
  [[nodiscard]] bool empty() const { return (min.array() > max.array()).any(); }
  void extend(const Vec3& point) {
    min = min.cwiseMin(point);
    max = max.cwiseMax(point);
  }
  void extend(const Aabb& other) {
    min = min.cwiseMin(other.min);
    max = max.cwiseMax(other.max);
  }
  // Closed intervals: boxes that touch overlap.
  [[nodiscard]] bool overlaps(const Aabb& other) const {
    return (min.array() <= other.max.array()).all() && (other.min.array() <= max.array()).all();
  }
  [[nodiscard]] bool contains(const Vec3& point) const {
    return (min.array() <= point.array()).all() && (point.array() <= max.array()).all();
  }
  [[nodiscard]] Vec3 size() const { return max - min; }
  [[nodiscard]] Vec3 center() const { return 0.5f * (min + max); }
};

}  // namespace sphys
