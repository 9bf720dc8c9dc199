#include "camera.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace sphys::viewer {
namespace {

constexpr float kNear = 0.05f;  // unit: m
constexpr float kFar = 500.0f;  // unit: m
constexpr float kPitchLimit = 1.55f;

}  // namespace

Eigen::Vector3f OrbitCamera::eye() const {
  const Eigen::Vector3f direction(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                  std::cos(pitch) * std::cos(yaw));
  return target + distance * direction;
}

Eigen::Matrix4f OrbitCamera::view() const {
  const Eigen::Vector3f from = eye();
  const Eigen::Vector3f forward = (target - from).normalized();
  const Eigen::Vector3f right = forward.cross(Eigen::Vector3f::UnitY()).normalized();
  const Eigen::Vector3f up = right.cross(forward);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = right.transpose();
  m.block<1, 3>(1, 0) = up.transpose();
  m.block<1, 3>(2, 0) = -forward.transpose();
  m(0, 3) = -right.dot(from);
  m(1, 3) = -up.dot(from);
  m(2, 3) = forward.dot(from);
  return m;
}

Eigen::Matrix4f OrbitCamera::projection(float aspect) const {
  const float f = 1.0f / std::tan(fov_y / 2.0f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (kFar + kNear) / (kNear - kFar);
  m(2, 3) = 2.0f * kFar * kNear / (kNear - kFar);
  m(3, 2) = -1.0f;
  return m;
}

Eigen::Vector3f OrbitCamera::ray(float x, float y, float width, float height) const {
  const Eigen::Vector3f forward = (target - eye()).normalized();
  const Eigen::Vector3f right = forward.cross(Eigen::Vector3f::UnitY()).normalized();
  const Eigen::Vector3f up = right.cross(forward);
  const float half_height = std::tan(fov_y / 2.0f);
  const float half_width = half_height * width / height;
  const float across = 2.0f * x / width - 1.0f;
  const float down = 2.0f * y / height - 1.0f;
  return (forward + across * half_width * right - down * half_height * up).normalized();
}

void OrbitCamera::turn(float dx, float dy) {
  yaw -= 0.005f * dx;
  pitch = std::clamp(pitch + 0.005f * dy, -kPitchLimit, kPitchLimit);
}

void OrbitCamera::pan(float dx, float dy, float height) {
  const Eigen::Vector3f from = eye();
  const Eigen::Vector3f forward = (target - from).normalized();
  const Eigen::Vector3f right = forward.cross(Eigen::Vector3f::UnitY()).normalized();
  const Eigen::Vector3f up = right.cross(forward);
  // A drag across the window moves the target by the width of the view at its distance.
  const float metres_per_pixel = 2.0f * distance * std::tan(fov_y / 2.0f) / height;
  target += metres_per_pixel * (-dx * right + dy * up);
}

void OrbitCamera::zoom(float wheel_steps) {
  distance = std::clamp(distance * std::pow(0.9f, wheel_steps), 0.5f, 400.0f);
}

}  // namespace sphys::viewer
