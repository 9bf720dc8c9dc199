#pragma once

// An orbit camera: it looks at a target from a distance, turned by yaw about +y and pitched up or
// down; the mouse turns, pans and zooms it.

#include <Eigen/Core>

namespace sphys::viewer {

// The view matrix of an eye at `from` looking along the unit vector `forward`, +y up (forward
// must not be vertical).
[[nodiscard]] Eigen::Matrix4f look_at(const Eigen::Vector3f& from, const Eigen::Vector3f& forward);

struct OrbitCamera {
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  float distance = 20.0f;  // unit: m
  float yaw = 0.6f;        // about +y. unit: rad
  float pitch = 0.35f;     // above the horizon. unit: rad
  float fov_y = 0.8f;      // vertical field of view. unit: rad

  [[nodiscard]] Eigen::Vector3f eye() const;
  [[nodiscard]] Eigen::Matrix4f view() const;
  [[nodiscard]] Eigen::Matrix4f projection(float aspect) const;

  // The unit direction from the eye through pixel (x, y) of a `width` × `height` window (y
  // downwards, as the mouse gives it).
  [[nodiscard]] Eigen::Vector3f ray(float x, float y, float width, float height) const;

  // Mouse drags in pixels of a window `height` tall.
  void turn(float dx, float dy);
  void pan(float dx, float dy, float height);
  void zoom(float wheel_steps);
};

}  // namespace sphys::viewer
