// The viewer's orbit camera: the ray through a pixel lands on that pixel when projected back.

#include "viewer/camera.h"

#include <utility>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace sphys::viewer {
namespace {

TEST(OrbitCamera, TheRayThroughAPixelProjectsBackOntoIt) {
  OrbitCamera camera;
  camera.target = Eigen::Vector3f(1.0f, 2.0f, -3.0f);
  camera.distance = 17.0f;
  camera.yaw = 2.1f;
  camera.pitch = -0.4f;
  const float width = 800.0f;
  const float height = 450.0f;
  const Eigen::Matrix4f view_projection = camera.projection(width / height) * camera.view();
  for (const auto& [x, y] : {std::pair{400.0f, 225.0f}, std::pair{0.0f, 0.0f},
                             std::pair{800.0f, 450.0f}, std::pair{123.0f, 401.0f}}) {
    const Eigen::Vector3f ray = camera.ray(x, y, width, height);
    EXPECT_NEAR(ray.norm(), 1.0f, 1e-5f);
    const Eigen::Vector3f point = camera.eye() + 10.0f * ray;
    const Eigen::Vector4f clip = view_projection * point.homogeneous();
    EXPECT_NEAR(clip.x() / clip.w(), 2.0f * x / width - 1.0f, 1e-4f) << x << ", " << y;
    EXPECT_NEAR(clip.y() / clip.w(), 1.0f - 2.0f * y / height, 1e-4f) << x << ", " << y;
  }
  // The middle of the window looks at the target.
  EXPECT_TRUE(camera.ray(width / 2, height / 2, width, height)
                  .isApprox((camera.target - camera.eye()).normalized(), 1e-5f));
}

}  // namespace
}  // namespace sphys::viewer
