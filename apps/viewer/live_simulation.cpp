#include "live_simulation.h"

#include <algorithm>
#include <utility>

#include <Eigen/Geometry>

#include "sphys/tools/scene_robots.h"

namespace sphys::viewer {
namespace {

// How far above the highest body a dropped one starts. unit: m
constexpr float kDropClearance = 3.0f;

Quat random_orientation(std::mt19937& random) {
  // A unit quaternion from four normal deviates is uniform over rotations.
  std::normal_distribution<float> normal;
  Quat q(normal(random), normal(random), normal(random), normal(random));
  if (q.norm() < 1e-6f) return Quat::Identity();
  q.normalize();
  return q;
}

}  // namespace

LiveSimulation::LiveSimulation(tools::Scene scene, tools::BuildWorldOptions build)
    : scene_(std::move(scene)), build_(std::move(build)) {
  reset();
}

void LiveSimulation::reset() {
  setup_ = tools::build_world(scene_, build_);
  setup_.world->set_detection_budget(max_sphere_tests_, max_microseconds_);
  const tools::SceneRobots robots = tools::add_scene_robots(scene_, *setup_.world);
  joints_ = tools::recorded_joints(scene_, robots);
  shapes_ = setup_.shapes;
  bodies_ = setup_.bodies;
  body_shape_ = setup_.body_shape;
  for (std::size_t k = 0; k < robots.bodies.size(); ++k) {
    bodies_.push_back(robots.bodies[k]);
    body_shape_.push_back(static_cast<std::uint32_t>(shapes_.size()));
    shapes_.push_back(robots.shapes[k]);
  }
  added_.reset();
  for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
    if (scene_.bodies[i].is_static) continue;
    const RigidBody& body = setup_.world->body(setup_.bodies[i]);
    Added added;
    added.shape = setup_.body_shape[i];
    added.desc.tree = setup_.shapes[added.shape].tree;
    added.desc.mass = body.mass();
    added.desc.inertia = body.inertia_body;
    added.desc.restitution = body.restitution;
    added.desc.friction = body.friction;
    added_ = added;
    break;
  }
  frame_ = 0;
}

const StepStats& LiveSimulation::step() {
  ++frame_;
  return setup_.world->step(static_cast<float>(scene_.time_step));
}

void LiveSimulation::bodies(std::vector<BodyView>& out) const {
  out.clear();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    out.push_back(
        {body_shape_[i], setup_.world->body(bodies_[i]).pose, setup_.world->asleep(bodies_[i])});
  }
}

void LiveSimulation::bounds(std::vector<Aabb>& out) const {
  out.clear();
  for (const BodyId body : bodies_) out.push_back(setup_.world->bounds(body));
  if (setup_.ground) out.push_back(setup_.world->bounds(*setup_.ground));
}

void LiveSimulation::drop_body(std::mt19937& random) {
  float top = static_cast<float>(scene_.ground.height);
  Eigen::AlignedBox2f area;
  for (const tools::BodySpec& body : scene_.bodies)
    area.extend(Eigen::Vector2f(body.position.x(), body.position.z()));
  for (const BodyId body : bodies_)
    top = std::max(top, setup_.world->body(body).pose.translation.y());
  if (area.isEmpty()) area.extend(Eigen::Vector2f::Zero());
  std::uniform_real_distribution<float> along(0.0f, 1.0f);
  const Eigen::Vector2f spot = area.min() +
                               along(random) * Eigen::Vector2f(area.sizes().x(), 0.0f) +
                               along(random) * Eigen::Vector2f(0.0f, area.sizes().y());
  add_body(Vec3(spot.x(), top + kDropClearance, spot.y()), Vec3::Zero(), random);
}

void LiveSimulation::shoot_body(const Vec3& from, const Vec3& velocity, std::mt19937& random) {
  add_body(from, velocity, random);
}

void LiveSimulation::add_body(const Vec3& position, const Vec3& velocity, std::mt19937& random) {
  if (!added_) return;
  BodyDesc desc = added_->desc;
  desc.pose.translation = position;
  desc.pose.rotation = random_orientation(random);
  desc.linear_velocity = velocity;
  bodies_.push_back(setup_.world->add_body(desc));
  body_shape_.push_back(added_->shape);
}

void LiveSimulation::set_detection_budget(std::uint64_t max_sphere_tests, double max_microseconds) {
  setup_.world->set_detection_budget(max_sphere_tests, max_microseconds);
  max_sphere_tests_ = max_sphere_tests;
  max_microseconds_ = max_microseconds;
}

}  // namespace sphys::viewer
