#include "robot/robot_control.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "world/world_state.h"

namespace sphys {
namespace {

Eigen::Isometry3d body_pose(const WorldState& world, BodyId body) {
  return to_isometry(world.store.poses()[body.index]);
}

Eigen::Isometry3d link_pose(const WorldState& world, const SimulatedRobot& robot,
                            std::size_t link) {
  return body_pose(world, robot.bodies[robot.link_body[link]]) * robot.link_in_body[link];
}

// A body's velocity at a world point. unit: m/s
Eigen::Vector3d point_velocity(const WorldState& world, BodyId body, const Eigen::Vector3d& point) {
  const std::uint32_t slot = body.index;
  const Eigen::Vector3d centre = world.store.poses()[slot].translation.cast<double>();
  return world.store.linear_velocities()[slot].cast<double>() +
         world.store.angular_velocities()[slot].cast<double>().cross(point - centre);
}

BodyId parent_body(const SimulatedRobot& robot, std::size_t link) {
  const auto parent = static_cast<std::size_t>(robot.model.links[link].parent);
  return robot.bodies[robot.link_body[parent]];
}

// The motor's speed under PyBullet's position law (RobotControlMode::kPosition), to a target
// within the joint's limits: one beyond them is the limit, which the motor then drives to and
// stops at instead of pressing the limit with its whole effort. unit: rad/s or m/s
double position_law_speed(const RobotJointControl& control, const RobotModel::Joint& model,
                          const JointReading& joint, double dt) {
  const double target = std::clamp(control.target_position, model.lower, model.upper);
  return control.position_gain * (target - joint.position) / dt + joint.speed +
         control.velocity_gain * (control.target_velocity - joint.speed);
}

// Equal and opposite torques (or forces at the moved link's origin) on the joint's two bodies.
void apply_joint_effort(WorldState& world, const SimulatedRobot& robot, std::size_t joint,
                        const JointReading& reading, double effort) {
  const std::size_t link = moved_link(robot, joint);
  const std::uint32_t child = robot.bodies[robot.link_body[link]].index;
  const std::uint32_t parent = parent_body(robot, link).index;
  const Vec3 along = (effort * reading.axis).cast<float>();
  const bool prismatic = robot.model.joints[joint].type == RobotJointType::kPrismatic;
  const Vec3 point = link_pose(world, robot, link).translation().cast<float>();
  for (const auto& [slot, sign] : {std::pair{child, 1.0f}, std::pair{parent, -1.0f}}) {
    if (world.store.is_static(slot)) continue;
    world.wake(slot);
    const Vec3 force = prismatic ? Vec3(sign * along) : Vec3::Zero();
    const Vec3 torque = prismatic
                            ? Vec3((point - world.store.poses()[slot].translation).cross(force))
                            : Vec3(sign * along);
    world.store.add_force(slot, force, torque);
  }
}

}  // namespace

Eigen::Isometry3d to_isometry(const Transform& pose) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = pose.rotation.cast<double>().normalized().toRotationMatrix();
  result.translation() = pose.translation.cast<double>();
  return result;
}

std::size_t moved_link(const SimulatedRobot& robot, std::size_t joint) {
  const auto found = std::ranges::find(robot.model.links, static_cast<std::int32_t>(joint),
                                       &RobotModel::Link::joint);
  return static_cast<std::size_t>(found - robot.model.links.begin());
}

std::vector<Eigen::Isometry3d> simulated_link_poses(const WorldState& world,
                                                    const SimulatedRobot& robot) {
  std::vector<Eigen::Isometry3d> poses(robot.model.links.size());
  for (std::size_t l = 0; l < poses.size(); ++l) poses[l] = link_pose(world, robot, l);
  return poses;
}

JointReading read_robot_joint(const WorldState& world, const SimulatedRobot& robot,
                              std::size_t joint) {
  const RobotModel::Joint& model = robot.model.joints[joint];
  const std::size_t link = moved_link(robot, joint);
  const auto parent = static_cast<std::size_t>(robot.model.links[link].parent);
  const Eigen::Isometry3d child_pose = link_pose(world, robot, link);
  const Eigen::Isometry3d relative = robot.model.links[link].origin.inverse() *
                                     link_pose(world, robot, parent).inverse() * child_pose;
  const BodyId child_body = robot.bodies[robot.link_body[link]];
  const BodyId parent_body_id = robot.bodies[robot.link_body[parent]];
  JointReading reading;
  reading.axis = child_pose.linear() * model.axis;
  if (model.type == RobotJointType::kPrismatic) {
    reading.position = relative.translation().dot(model.axis);
    const Eigen::Vector3d at = child_pose.translation();
    reading.speed =
        (point_velocity(world, child_body, at) - point_velocity(world, parent_body_id, at))
            .dot(reading.axis);
    return reading;
  }
  // The twist of the relative turn about the axis (swing-twist), in (-π, π].
  const Eigen::Quaterniond turn(relative.linear());
  double angle = 2.0 * std::atan2(turn.vec().dot(model.axis), turn.w());
  angle = std::remainder(angle, 2.0 * std::numbers::pi);
  if (model.type == RobotJointType::kContinuous) {
    const double last = robot.positions[joint];
    angle += 2.0 * std::numbers::pi * std::round((last - angle) / (2.0 * std::numbers::pi));
  }
  reading.position = angle;
  const auto spin = [&](BodyId body) {
    return world.store.angular_velocities()[body.index].cast<double>();
  };
  reading.speed = (spin(child_body) - spin(parent_body_id)).dot(reading.axis);
  return reading;
}

void control_robots(WorldState& world, RobotStore& robots, float dt) {
  for (SimulatedRobot& robot : robots.all()) {
    if (!robot.alive) continue;
    for (std::size_t j = 0; j < robot.joints.size(); ++j) {
      // A joint removed by remove_joint drives nothing, nor may its slot's next joint be driven.
      if (!world.joints.alive(robot.joints[j])) continue;
      const RobotJointControl& control = robot.controls[j];
      const RobotModel::Joint& model = robot.model.joints[j];
      const double effort = std::min(control.max_effort, model.effort);
      const JointReading reading = read_robot_joint(world, robot, j);
      robot.positions[j] = reading.position;
      JointMotor motor;
      motor.max_effort = static_cast<float>(std::min(effort, 1e30));
      robot.applied[j] = 0.0;
      switch (control.mode) {
        case RobotControlMode::kPosition:
          motor.enabled = true;
          motor.speed = static_cast<float>(std::clamp(
              position_law_speed(control, model, reading, dt), -model.velocity, model.velocity));
          break;
        case RobotControlMode::kVelocity:
          motor.enabled = true;
          motor.speed = static_cast<float>(control.target_velocity);
          break;
        case RobotControlMode::kTorque:
          robot.applied[j] = std::clamp(control.torque, -effort, effort);
          if (robot.applied[j] != 0.0)
            apply_joint_effort(world, robot, j, reading, robot.applied[j]);
          break;
      }
      world.joints.at(robot.joints[j].index).desc.motor = motor;
    }
  }
}

void place_robot(WorldState& world, SimulatedRobot& robot, std::span<const double> values) {
  RobotModel& model = robot.model;
  const BodyId root = robot.bodies[0];
  model.base = link_pose(world, robot, 0);
  const std::vector<Eigen::Isometry3d> poses = forward_kinematics(model, values);
  for (std::size_t b = 0; b < robot.bodies.size(); ++b) {
    const std::uint32_t slot = robot.bodies[b].index;
    if (robot.bodies[b] == root || world.store.is_static(slot)) continue;
    const auto link =
        static_cast<std::size_t>(std::ranges::find(robot.link_body, b) - robot.link_body.begin());
    const Eigen::Isometry3d pose = poses[link] * robot.link_in_body[link].inverse();
    Transform& placed = world.store.poses()[slot];
    placed.rotation = Quat(pose.linear().cast<float>()).normalized();
    placed.translation = pose.translation().cast<float>();
    world.store.linear_velocities()[slot] = Vec3::Zero();
    world.store.angular_velocities()[slot] = Vec3::Zero();
    world.store.update_world_inertia(slot);
    world.detector.bound_at_pose(slot);
    world.wake(slot);
    world.store.measure_fastest_point_speed(slot);
  }
  if (!world.store.is_static(root.index)) {
    world.store.linear_velocities()[root.index] = Vec3::Zero();
    world.store.angular_velocities()[root.index] = Vec3::Zero();
    world.wake(root.index);
    world.store.measure_fastest_point_speed(root.index);
  }
  robot.positions.assign(values.begin(), values.end());
}

}  // namespace sphys
