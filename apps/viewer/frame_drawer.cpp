#include "frame_drawer.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>

#include <Eigen/Geometry>

namespace sphys::viewer {
namespace {

// The whole scene as it starts: the ground's box (or the bodies' spread) and the stacks' height,
// seen from the orbit camera's usual angle.
OrbitCamera whole_scene(const tools::Scene& scene) {
  OrbitCamera camera = frame_scene(scene);
  if (scene.bodies.empty()) return camera;
  Eigen::AlignedBox3f box;
  for (const tools::BodySpec& body : scene.bodies) box.extend(body.position);
  box.extend(
      Eigen::Vector3f(box.center().x(), static_cast<float>(scene.ground.height), box.center().z()));
  camera.target.y() = box.center().y();
  // Far enough that the box's height fits the view with a margin.
  const float fit = 0.65f * box.sizes().y() / std::tan(0.5f * camera.fov_y);
  camera.distance = std::max(camera.distance, fit);
  return camera;
}

}  // namespace

FrameDrawer::FrameDrawer(const tools::Scene& scene, const tools::SimulationSetup& setup, int width,
                         int height)
    : setup_(&setup),
      window_(width, height, std::nullopt, false),
      drawer_(renderer_, scene, setup.shapes),
      start_camera_(whole_scene(scene)),
      ground_camera_(frame_scene(scene)) {}

void FrameDrawer::draw(bool first) {
  bodies_.clear();
  const World& world = *setup_->world;
  for (std::size_t i = 0; i < setup_->bodies.size(); ++i) {
    bodies_.push_back({setup_->body_shape[i], world.body(setup_->bodies[i]).pose,
                       world.asleep(setup_->bodies[i])});
  }
  glViewport(0, 0, window_.width(), window_.height());
  drawer_.draw(renderer_, lines_, first ? start_camera_ : ground_camera_, window_.aspect(),
               {bodies_, {}, {}, {}}, Overlays{});
  glFinish();
}

void FrameDrawer::save(const std::filesystem::path& png) const {
  write_png(png, window_.width(), window_.height());
}

}  // namespace sphys::viewer
