// The world's robots through its public face (sphys/robot_world.h): adding them as bodies and
// joints, controlling, placing and reading them (docs/robots.md).

#include <cmath>
#include <memory>
#include <string>

#include "core/id_errors.h"
#include "robot/robot_bodies.h"
#include "robot/robot_control.h"
#include "sphys/error.h"
#include "sphys/world.h"
#include "world/world_state.h"

namespace sphys {
namespace {

// The world's robots, made with the first.
RobotStore& robots_of(WorldState& world) {
  if (!world.robots) world.robots = std::make_unique<RobotStore>();
  return static_cast<RobotStore&>(*world.robots);
}

// The world's robots as they are: none before the first is added.
const RobotStore* robots_in(const WorldState& world) {
  return static_cast<const RobotStore*>(world.robots.get());
}

// True for a robot in the world; false for a stale or unknown id, or the null one.
bool robot_in(const WorldState& world, RobotId id) {
  return robots_in(world) != nullptr && robots_in(world)->alive(id);
}

// The slot of a robot in the world, for a call that holds its turn.
std::uint32_t checked_robot(const WorldState& world, RobotId id) {
  return slot_named(id, robot_in(world, id), "robot", "RobotId");
}

Transform to_robot_transform(const Eigen::Isometry3d& pose) {
  return {Quat(pose.linear().cast<float>()).normalized(), pose.translation().cast<float>()};
}

// A hinge or slider joining the bodies of joint j's parent and child links where they stand with
// every joint at 0, so that the joint's own angle or position is the model's joint value.
JointDesc robot_joint(const SimulatedRobot& robot, std::size_t joint) {
  const RobotModel& model = robot.model;
  const std::size_t link = moved_link(robot, joint);
  const auto parent = static_cast<std::size_t>(model.links[link].parent);
  const RobotModel::Joint& spec = model.joints[joint];
  const Eigen::Isometry3d joint_in_parent = robot.link_in_body[parent] * model.links[link].origin;
  JointDesc desc;
  desc.type = spec.type == RobotJointType::kPrismatic ? JointType::kSlider : JointType::kHinge;
  desc.body_a = robot.bodies[robot.link_body[parent]];
  desc.body_b = robot.bodies[robot.link_body[link]];
  desc.anchor_a = joint_in_parent.translation().cast<float>();
  desc.anchor_b = robot.link_in_body[link].translation().cast<float>();
  desc.axis_a = (joint_in_parent.linear() * spec.axis).cast<float>();
  desc.axis_b = (robot.link_in_body[link].linear() * spec.axis).cast<float>();
  if (spec.type != RobotJointType::kContinuous) {
    desc.limit = {true, static_cast<float>(spec.lower), static_cast<float>(spec.upper)};
  }
  return desc;
}

}  // namespace

RobotId World::add_robot(const RobotModel& model, const Transform& base, RobotBase base_kind) {
  if (state_->settings.response != ResponseMode::kPlausible) {
    throw Error("add_robot: robots are simulated in plausible mode only");
  }
  check_robot_model(model);
  const RobotPlan plan = plan_robot_bodies(model, base_kind == RobotBase::kFixed);
  SimulatedRobot robot;
  robot.model = model;
  robot.model.base = to_isometry(base);
  robot.base = base_kind;
  robot.link_body = plan.link_body;
  robot.link_in_body = plan.link_in_body;
  const std::vector<double> zeros(model.joints.size(), 0.0);
  const std::vector<Eigen::Isometry3d> poses = forward_kinematics(robot.model, zeros);
  try {
    for (std::size_t b = 0; b < plan.bodies.size(); ++b) {
      const RobotBodyPlan& part = plan.bodies[b];
      const auto link = static_cast<std::size_t>(part.link);
      BodyDesc desc;
      desc.tree = part.tree;
      desc.pose = to_robot_transform(poses[link] * plan.link_in_body[link].inverse());
      desc.is_static = b == 0 && base_kind == RobotBase::kFixed;
      desc.mass = static_cast<float>(part.mass);
      desc.inertia = part.inertia.cast<float>();
      try {
        robot.bodies.push_back(add_body(desc));
      } catch (const Error& error) {
        throw Error("robot '" + model.name + "': link '" + model.links[link].name +
                    "': " + error.what());
      }
    }
    for (std::size_t j = 0; j < model.joints.size(); ++j) {
      robot.joints.push_back(add_joint(robot_joint(robot, j)));
    }
  } catch (...) {
    for (const BodyId body : robot.bodies) remove_body(body);
    throw;
  }
  robot.controls.assign(model.joints.size(), RobotJointControl{});
  robot.applied.assign(model.joints.size(), 0.0);
  robot.positions = zeros;
  std::vector<double> start(model.joints.size());
  for (std::size_t j = 0; j < start.size(); ++j) {
    start[j] = std::clamp(0.0, model.joints[j].lower, model.joints[j].upper);
  }
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "add_robot");
  const RobotId id = robots_of(world).add(std::move(robot));
  world.joints_changed();
  if (start != zeros) place_robot(world, robots_of(world).at(id.index), start);
  return id;
}

void World::remove_robot(RobotId id) {
  std::vector<BodyId> bodies;
  {
    WorldState& world = *state_;
    const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "remove_robot");
    const std::uint32_t slot = checked_robot(world, id);
    bodies = robots_of(world).at(slot).bodies;
    // Its allowed pairs go before its bodies, whose slots a later body may take.
    robots_of(world).remove(slot);
    world.joints_changed();
  }
  for (const BodyId body : bodies) remove_body(body);
}

bool World::robot_alive(RobotId id) const {
  const WorldAccess::Shared turn(state_->access, "robot_alive");
  return robot_in(*state_, id);
}

std::span<const BodyId> World::robot_bodies(RobotId id) const {
  const WorldAccess::Shared turn(state_->access, "robot_bodies");
  return robots_in(*state_)->at(checked_robot(*state_, id)).bodies;
}

std::span<const JointId> World::robot_joints(RobotId id) const {
  const WorldAccess::Shared turn(state_->access, "robot_joints");
  return robots_in(*state_)->at(checked_robot(*state_, id)).joints;
}

const RobotModel& World::robot_model(RobotId id) const {
  const WorldAccess::Shared turn(state_->access, "robot_model");
  return robots_in(*state_)->at(checked_robot(*state_, id)).model;
}

void World::set_robot_controls(RobotId id, std::span<const RobotJointControl> controls) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "set_robot_controls");
  SimulatedRobot& robot = robots_of(world).at(checked_robot(world, id));
  if (controls.size() != robot.joints.size()) {
    throw Error("set_robot_controls: " + std::to_string(controls.size()) + " controls for " +
                std::to_string(robot.joints.size()) + " joints");
  }
  for (std::size_t j = 0; j < controls.size(); ++j) {
    const RobotJointControl& c = controls[j];
    if (!std::isfinite(c.target_position) || !std::isfinite(c.target_velocity) ||
        !std::isfinite(c.position_gain) || !std::isfinite(c.velocity_gain) ||
        !std::isfinite(c.torque) || !(c.max_effort > 0.0)) {
      throw Error("set_robot_controls: joint " + std::to_string(j) + " ('" +
                  robot.model.joints[j].name +
                  "'): targets, gains and torque must be finite, max_effort positive");
    }
  }
  robot.controls.assign(controls.begin(), controls.end());
  for (const BodyId body : robot.bodies) {
    if (!world.store.is_static(body.index)) world.wake(body.index);
  }
}

void World::set_robot_configuration(RobotId id, std::span<const double> values) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange,
                                "set_robot_configuration");
  SimulatedRobot& robot = robots_of(world).at(checked_robot(world, id));
  check_joint_values(robot.model, values, "set_robot_configuration");
  if (values.size() != robot.joints.size()) {
    throw Error("set_robot_configuration: " + std::to_string(values.size()) + " values for " +
                std::to_string(robot.joints.size()) + " joints");
  }
  place_robot(world, robot, values);
}

RobotJointStates World::robot_joint_states(RobotId id) const {
  const WorldAccess::Shared turn(state_->access, "robot_joint_states");
  const SimulatedRobot& robot = robots_in(*state_)->at(checked_robot(*state_, id));
  RobotJointStates states;
  for (std::size_t j = 0; j < robot.joints.size(); ++j) {
    const JointReading reading = read_robot_joint(*state_, robot, j);
    const JointState& state = state_->joints.at(robot.joints[j].index).state;
    const Vec3& along =
        robot.model.joints[j].type == RobotJointType::kPrismatic ? state.force : state.torque;
    states.positions.push_back(reading.position);
    states.speeds.push_back(reading.speed);
    states.efforts.push_back(along.cast<double>().dot(reading.axis) + robot.applied[j]);
  }
  return states;
}

std::vector<Eigen::Isometry3d> World::robot_link_poses_in_world(RobotId id) const {
  const WorldAccess::Shared turn(state_->access, "robot_link_poses_in_world");
  return simulated_link_poses(*state_, robots_in(*state_)->at(checked_robot(*state_, id)));
}

}  // namespace sphys
