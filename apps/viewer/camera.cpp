#include "camera.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace sphys::viewer {
namespace {

constexpr float kNear = 0.05f;  // unit: m
constexpr float kFar = 500.0f;  // unit: m
constexpr float kPitchLimit = 1.55f;

// The screen's axes in the world for an eye looking along `forward` (unit), +y up.
struct Basis {
  Eigen::Vector3f forward;
  Eigen::Vector3f right;
  Eigen::Vector3f up;
};

Basis basis(const Eigen::Vector3f& forward) {
  const Eigen::Vector3f right = forward.cross(Eigen::Vector3f::UnitY()).normalized();
  return {forward, right, right.cross(forward)};
}

}  // namespace

Eigen::Matrix4f look_at(const Eigen::Vector3f& from, const Eigen::Vector3f& forward) {
  const Basis b = basis(forward);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = b.right.transpose();
  m.block<1, 3>(1, 0) = b.up.transpose();
  m.block<1, 3>(2, 0) = -b.forward.transpose();
  m(0, 3) = -b.right.dot(from);
  m(1, 3) = -b.up.dot(from);
  m(2, 3) = b.forward.dot(from);
  return m;
}

Eigen::Vector3f OrbitCamera::eye() const {
  const Eigen::Vector3f direction(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                  std::cos(pitch) * std::cos(yaw));
  return target + distance * direction;
}

Eigen::Matrix4f OrbitCamera::view() const {
  const Eigen::Vector3f from = eye();
  return look_at(from, (target - from).normalized());
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
  const Basis b = basis((target - eye()).normalized());
  const float half_height = std::tan(fov_y / 2.0f);
  const float half_width = half_height * width / height;
  const float across = 2.0f * x / width - 1.0f;
  const float down = 2.0f * y / height - 1.0f;
  return (b.forward + across * half_width * b.right - down * half_height * b.up).normalized();
}

void OrbitCamera::turn(float dx, float dy) {
  yaw -= 0.005f * dx;
  pitch = std::clamp(pitch + 0.005f * dy, -kPitchLimit, kPitchLimit);
}

void OrbitCamera::pan(float dx, float dy, float height) {
  const Basis b = basis((target - eye()).normalized());
  // A drag across the window moves the target by the width of the view at its distance.
  const float metres_per_pixel = 2.0f * distance * std::tan(fov_y / 2.0f) / height;
  target += metres_per_pixel * (-dx * b.right + dy * b.up);
}

void OrbitCamera::zoom(float wheel_steps) {
  distance = std::clamp(distance * std::pow(0.9f, wheel_steps), 0.5f, 400.0f);
}

}  // namespace sphys::viewer
