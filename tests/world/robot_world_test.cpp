// Robots simulated in a world (World::add_robot): the test robot's links against the one forward
// kinematics, position, velocity and torque control against their targets, limits, a free fall
// and bad input.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/robot_model.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/robot.h"
#include "sphys/tools/robot_model_file.h"
#include "sphys/tools/scene.h"
#include "sphys/tools/scene_file.h"
#include "sphys/tools/scene_robots.h"
#include "sphys/tools/spherize.h"
#include "sphys/world.h"
#include "support/quintic.h"
#include "support/temp_file.h"
#include "support/test_robot.h"
#include "support/test_robot_scene.h"

namespace sphys {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr float kControlStep = 1e-3f;  // 1 kHz control. unit: s

// The test robot (tests/support/test_robot.h) with its links' spheres, made once.
const RobotModel& test_robot() {
  static const RobotModel model = [] {
    const test::TempDir dir;
    const test::TestRobot written = test::write_test_robot(dir.path(), test::standard_test_robot());
    const tools::RobotPackage package = tools::parse_robot_package(written.package_option);
    const tools::Robot robot = tools::load_robot(written.urdf, std::span(&package, 1));
    tools::SpherizeOptions options;
    options.total_spheres = 60;
    // The fingers' few spheres meet across the gap between them, as an SRDF would say.
    const std::array<std::string, 2> fingers = {"finger_left_link", "finger_right_link"};
    return tools::robot_model(robot, tools::spherize(robot, options), std::span(&fingers, 1));
  }();
  return model;
}

// The URDF's z up turned to the world's y up, the base at `height`.
Transform upright_base(float height) {
  return {Quat(Eigen::AngleAxisf(-std::numbers::pi_v<float> / 2, Vec3::UnitX())),
          Vec3(0.0f, height, 0.0f)};
}

Eigen::Isometry3d to_isometry(const Transform& pose) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = pose.rotation.cast<double>().toRotationMatrix();
  result.translation() = pose.translation.cast<double>();
  return result;
}

// Joint values drawn evenly inside the limits, kept `margin` from them. unit: rad or m
std::vector<double> random_configuration(const RobotModel& model, std::mt19937& random,
                                         double margin_share) {
  std::vector<double> values;
  for (const RobotModel::Joint& joint : model.joints) {
    const double margin = margin_share * (joint.upper - joint.lower);
    values.push_back(
        std::uniform_real_distribution<double>(joint.lower + margin, joint.upper - margin)(random));
  }
  return values;
}

// Whether spheres of two links on different bodies that are not joined overlap with the joints
// at `values`: a configuration the robot cannot hold without pushing itself.
bool self_colliding(const RobotModel& model, std::span<const double> values) {
  const std::vector<Eigen::Isometry3d> poses = robot_link_poses(model, values);
  const auto body_of = [&](std::int32_t link) {
    while (link > 0 && model.links[static_cast<std::size_t>(link)].joint < 0) {
      link = model.links[static_cast<std::size_t>(link)].parent;
    }
    return link;
  };
  for (std::size_t a = 0; a < model.spheres.size(); ++a) {
    for (std::size_t b = a + 1; b < model.spheres.size(); ++b) {
      const std::int32_t body_a = body_of(model.sphere_links[a]);
      const std::int32_t body_b = body_of(model.sphere_links[b]);
      if (body_a == body_b ||
          std::ranges::count(model.allowed_link_pairs, std::array{body_a, body_b}) +
                  std::ranges::count(model.allowed_link_pairs, std::array{body_b, body_a}) >
              0 ||
          model.links[static_cast<std::size_t>(body_a)].parent == body_b ||
          model.links[static_cast<std::size_t>(body_b)].parent == body_a ||
          body_of(model.links[static_cast<std::size_t>(body_a)].parent) == body_b ||
          body_of(model.links[static_cast<std::size_t>(body_b)].parent) == body_a) {
        continue;
      }
      const Eigen::Vector3d ca = poses[static_cast<std::size_t>(model.sphere_links[a])] *
                                 model.spheres[a].center.cast<double>();
      const Eigen::Vector3d cb = poses[static_cast<std::size_t>(model.sphere_links[b])] *
                                 model.spheres[b].center.cast<double>();
      if ((ca - cb).norm() < model.spheres[a].radius + model.spheres[b].radius) return true;
    }
  }
  return false;
}

std::vector<RobotJointControl> hold(std::span<const double> targets) {
  std::vector<RobotJointControl> controls(targets.size());
  for (std::size_t j = 0; j < targets.size(); ++j) {
    controls[j].mode = RobotControlMode::kPosition;
    controls[j].target_position = targets[j];
  }
  return controls;
}

WorldSettings arm_world() {
  WorldSettings settings;
  settings.collision.ground_plane_height = 0.0f;
  return settings;
}

// No ground, and no sleep: the controllers work through every step of the test.
WorldSettings awake_world() {
  WorldSettings settings;
  settings.sleep.enabled = false;
  return settings;
}

TEST(RobotWorld, LinksMatchTheForwardKinematics) {
  const RobotModel& model = test_robot();
  World world(arm_world());
  const Transform base = upright_base(0.3f);
  const RobotId robot = world.add_robot(model, base);
  EXPECT_EQ(world.robot_bodies(robot).size(), model.joints.size() + 1);
  EXPECT_EQ(world.robot_joints(robot).size(), model.joints.size());
  RobotModel placed = model;
  placed.base = to_isometry(base);
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<double> values = random_configuration(model, random, 0.0);
    world.set_robot_configuration(robot, values);
    const std::vector<Eigen::Isometry3d> expected = robot_link_poses(placed, values);
    const std::vector<Eigen::Isometry3d> simulated = world.robot_link_poses_in_world(robot);
    ASSERT_EQ(simulated.size(), expected.size());
    for (std::size_t l = 0; l < expected.size(); ++l) {
      EXPECT_LT((simulated[l].translation() - expected[l].translation()).norm(), 1e-5)
          << model.links[l].name;
      EXPECT_LT((simulated[l].linear() - expected[l].linear()).norm(), 1e-5) << model.links[l].name;
    }
    const RobotJointStates states = world.robot_joint_states(robot);
    for (std::size_t j = 0; j < values.size(); ++j) {
      EXPECT_NEAR(states.positions[j], values[j], 1e-5) << model.joints[j].name;
    }
  }
}

TEST(RobotWorld, HoldsRandomConfigurationsUnderGravity) {
  const RobotModel& model = test_robot();
  std::mt19937 random(11);
  double worst_error = 0.0;
  double worst_effort_share = 0.0;
  int held = 0;
  while (held < 20) {
    const std::vector<double> values = random_configuration(model, random, 0.05);
    if (self_colliding(model, values)) continue;
    World world(awake_world());
    const RobotId robot = world.add_robot(model, upright_base(1.0f));
    world.set_robot_configuration(robot, values);
    world.set_robot_controls(robot, hold(values));
    for (int step = 0; step < 2000; ++step) {
      world.step(kControlStep);
      const RobotJointStates states = world.robot_joint_states(robot);
      for (std::size_t j = 0; j < values.size(); ++j) {
        worst_effort_share =
            std::max(worst_effort_share, std::abs(states.efforts[j]) / model.joints[j].effort);
      }
    }
    const RobotJointStates states = world.robot_joint_states(robot);
    for (std::size_t j = 0; j < values.size(); ++j) {
      const double error = std::abs(states.positions[j] - values[j]);
      // 0.5° for a turning joint, 0.5 mm for a sliding one.
      const double unit = model.joints[j].type == RobotJointType::kPrismatic ? 1e-3 : kDegree;
      worst_error = std::max(worst_error, error / unit);
      EXPECT_LT(error, 0.5 * unit) << "configuration " << held << " joint " << model.joints[j].name;
    }
    ++held;
  }
  std::cout << "holding: worst error " << worst_error << " deg (or mm), worst effort "
            << worst_effort_share << " of the URDF's\n";
  EXPECT_LE(worst_effort_share, 1.0 + 1e-3);
}

// Why position control is a motor and not the joint's spring (docs/robots.md): the arm held out
// 0.9 rad from upright under gravity for 2 s, the motor stays on its target within the URDF's
// effort, where a stiff, critically damped spring about the same target sags by the load over its
// stiffness.
TEST(RobotWorld, PositionControlHoldsWhereASpringSags) {
  const RobotModel& model = test_robot();
  const std::vector<double> held = {0.0, 0.9, 0.0, 0.015, 0.015};
  ASSERT_FALSE(self_colliding(model, held));
  const auto worst_error = [&](bool spring) {
    World world(awake_world());
    const RobotId robot = world.add_robot(model, upright_base(1.0f));
    world.set_robot_configuration(robot, held);
    if (spring) {
      for (std::size_t j = 0; j < held.size(); ++j) {
        world.set_joint_spring(world.robot_joints(robot)[j],
                               {true, 10.0f, 1.0f, static_cast<float>(held[j])});
      }
    } else {
      world.set_robot_controls(robot, hold(held));
    }
    for (int step = 0; step < 2000; ++step) world.step(kControlStep);
    const RobotJointStates states = world.robot_joint_states(robot);
    double worst = 0.0;
    for (std::size_t j = 0; j < 3; ++j)
      worst = std::max(worst, std::abs(states.positions[j] - held[j]));
    return worst / kDegree;
  };
  const double motor = worst_error(false);
  const double spring = worst_error(true);
  std::cout << "held out: motor " << motor << " deg, 10 Hz spring " << spring << " deg\n";
  EXPECT_LT(motor, 0.5);
  EXPECT_GT(spring, 10.0 * motor);
}

// One step at time t (unit: s) of the quintics from `from` to `to`, the robot's position
// targets and speeds on them.
void step_on_quintic(World& world, RobotId robot, std::span<const double> from,
                     std::span<const double> to, double duration, double t) {
  std::vector<RobotJointControl> controls = hold(from);
  for (std::size_t j = 0; j < to.size(); ++j) {
    std::tie(controls[j].target_position, controls[j].target_velocity) =
        test::quintic(from[j], to[j], duration, t);
  }
  world.set_robot_controls(robot, controls);
  world.step(kControlStep);
}

TEST(RobotWorld, TracksAQuinticTrajectory) {
  const RobotModel& model = test_robot();
  World world(awake_world());
  const RobotId robot = world.add_robot(model, upright_base(1.0f));
  // Revolute joints swing 0.9 rad and the fingers open 1 cm more: the quintic's top speed,
  // 1.875 times the mean, stays under the URDF's 1 rad/s (1 m/s).
  std::vector<double> from;
  std::vector<double> to;
  for (const RobotModel::Joint& joint : model.joints) {
    const bool finger = joint.type == RobotJointType::kPrismatic;
    from.push_back(finger ? 0.015 : 0.0);
    to.push_back(finger ? 0.025 : 0.9);
  }
  ASSERT_FALSE(self_colliding(model, from));
  ASSERT_FALSE(self_colliding(model, to));
  constexpr double kDuration = 2.0;  // unit: s
  world.set_robot_configuration(robot, from);
  double worst = 0.0;
  for (int step = 1; step <= 2500; ++step) {
    const double t = step * double{kControlStep};
    step_on_quintic(world, robot, from, to, kDuration, t);
    const RobotJointStates states = world.robot_joint_states(robot);
    for (std::size_t j = 0; j < to.size(); ++j) {
      // 1° for a turning joint, 1 mm for a sliding one.
      const double unit = model.joints[j].type == RobotJointType::kPrismatic ? 1e-3 : kDegree;
      const double error =
          std::abs(states.positions[j] - test::quintic(from[j], to[j], kDuration, t).first) / unit;
      worst = std::max(worst, error);
    }
  }
  std::cout << "tracking: worst error " << worst << " deg (or mm)\n";
  EXPECT_LT(worst, 1.0);
}

TEST(RobotWorld, ATargetBeyondALimitStopsAtTheLimit) {
  const RobotModel& model = test_robot();
  World world(WorldSettings{});
  const RobotId robot = world.add_robot(model, upright_base(1.0f));
  // The pan joint turns about the vertical, where nothing of the arm meets anything.
  const std::size_t pan = 0;
  ASSERT_EQ(model.joints[pan].name, "shoulder_pan");
  std::vector<double> start(model.joints.size(), 0.015);
  start[pan] = model.joints[pan].upper - 0.5;
  for (std::size_t j = 1; j < 3; ++j) start[j] = 0.0;
  world.set_robot_configuration(robot, start);
  std::vector<double> targets = start;
  targets[pan] = model.joints[pan].upper + 1.0;
  world.set_robot_controls(robot, hold(targets));
  for (int step = 0; step < 2000; ++step) world.step(kControlStep);
  EXPECT_NEAR(world.robot_joint_states(robot).positions[pan], model.joints[pan].upper, kDegree);
}

TEST(RobotWorld, VelocityControlTurnsAtItsSpeed) {
  const RobotModel& model = test_robot();
  World world(WorldSettings{});
  const RobotId robot = world.add_robot(model, upright_base(1.0f));
  std::vector<RobotJointControl> controls = hold(std::vector<double>(model.joints.size(), 0.0));
  controls[0].mode = RobotControlMode::kVelocity;
  controls[0].target_velocity = 0.5;
  world.set_robot_controls(robot, controls);
  for (int step = 0; step < 1000; ++step) world.step(kControlStep);
  const RobotJointStates states = world.robot_joint_states(robot);
  EXPECT_NEAR(states.speeds[0], 0.5, 0.01);
  EXPECT_NEAR(states.positions[0], 0.5, 0.02);
}

TEST(RobotWorld, TorqueControlTurnsTheJointAndIsBoundedByTheEffort) {
  const RobotModel& model = test_robot();
  World world(awake_world());
  const RobotId robot = world.add_robot(model, upright_base(1.0f));
  std::vector<RobotJointControl> controls = hold(std::vector<double>(model.joints.size(), 0.015));
  controls[0].mode = RobotControlMode::kTorque;
  controls[0].torque = 3.0 * model.joints[0].effort;
  world.set_robot_controls(robot, controls);
  for (int step = 0; step < 20; ++step) world.step(kControlStep);
  const RobotJointStates states = world.robot_joint_states(robot);
  ASSERT_LT(states.positions[0], model.joints[0].upper - 0.5);  // its limit not yet met
  EXPECT_GT(states.speeds[0], 0.1);
  // The torque applied, and the little the hinge's rows across the axis add along it.
  EXPECT_NEAR(states.efforts[0], model.joints[0].effort, 0.01 * model.joints[0].effort);
}

TEST(RobotWorld, AFreeRobotFallsAndRestsOnThePlane) {
  const RobotModel& model = test_robot();
  World world(arm_world());
  const RobotId robot = world.add_robot(model, upright_base(0.5f), RobotBase::kFree);
  double worst_gap = 0.0;
  for (int step = 0; step < 4000; ++step) {
    world.step(kControlStep);
    for (const JointId joint : world.robot_joints(robot)) {
      worst_gap = std::max(worst_gap, double{world.joint_state(joint).gap});
    }
  }
  std::cout << "free fall: worst joint gap " << worst_gap << " m\n";
  EXPECT_LT(worst_gap, 0.01);
  const RobotJointStates states = world.robot_joint_states(robot);
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    EXPECT_GE(states.positions[j], model.joints[j].lower - kDegree) << model.joints[j].name;
    EXPECT_LE(states.positions[j], model.joints[j].upper + kDegree) << model.joints[j].name;
  }
  for (const BodyId body : world.robot_bodies(robot)) {
    const RigidBody state = world.body(body);
    EXPECT_LT(state.linear_velocity.norm(), 0.05f);
    EXPECT_GT(state.pose.translation.y(), -0.01f);
  }
}

TEST(RobotWorld, RemovingARobotRemovesItsBodiesAndJoints) {
  const RobotModel& model = test_robot();
  World world(arm_world());
  const RobotId robot = world.add_robot(model, upright_base(0.0f));
  const std::vector<BodyId> bodies(world.robot_bodies(robot).begin(),
                                   world.robot_bodies(robot).end());
  const std::vector<JointId> joints(world.robot_joints(robot).begin(),
                                    world.robot_joints(robot).end());
  EXPECT_THAT([&] { world.remove_body(bodies[1]); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("remove_robot")));
  // A joint taken out by hand drives nothing from then on, nor does a joint given its slot.
  world.remove_joint(joints[0]);
  JointDesc hinge;
  hinge.type = JointType::kHinge;
  hinge.body_b = bodies[2];
  const JointId other = world.add_joint(hinge);
  world.set_robot_controls(robot, hold(std::vector<double>(joints.size(), 0.5)));
  world.step(kControlStep);
  EXPECT_FALSE(world.joint(other).motor.enabled);
  world.remove_robot(robot);
  EXPECT_FALSE(world.robot_alive(robot));
  for (const BodyId body : bodies) EXPECT_FALSE(world.alive(body));
  for (const JointId joint : joints) EXPECT_FALSE(world.joint_alive(joint));
  EXPECT_FALSE(world.joint_alive(other));  // it went with its body
  EXPECT_THROW((void)world.robot_joint_states(robot), Error);
  world.step(kControlStep);
}

// The deepest overlap of a leaf of body `a` with a leaf of body `b`, now. unit: m
float deepest_leaf_overlap(const World& world, BodyId a, BodyId b) {
  const RigidBody body_a = world.body(a);
  const RigidBody body_b = world.body(b);
  const SphereTree& tree_a = world.tree(a);
  const SphereTree& tree_b = world.tree(b);
  float deepest = -std::numeric_limits<float>::infinity();
  for (const std::uint32_t leaf_a : tree_a.leaves()) {
    const Sphere& sa = tree_a.sphere(leaf_a);
    const Vec3 ca = body_a.pose.apply(sa.center);
    for (const std::uint32_t leaf_b : tree_b.leaves()) {
      const Sphere& sb = tree_b.sphere(leaf_b);
      deepest =
          std::max(deepest, sa.radius + sb.radius - (ca - body_b.pose.apply(sb.center)).norm());
    }
  }
  return deepest;
}

TEST(RobotWorld, TheArmSweepsABunnyAsideAndRecovers) {
  const RobotModel& model = test_robot();
  RobotModel placed = model;
  placed.base = to_isometry(upright_base(0.0f));
  std::vector<double> reach(model.joints.size(), 0.015);
  // Bent down without meeting itself, its lowest sphere 1 to 4 cm over the ground, so that it
  // passes through a lying 15 cm bunny there.
  const auto lowest_sphere = [&](std::span<const double> values) {
    const std::vector<Eigen::Isometry3d> poses = robot_link_poses(placed, values);
    Eigen::Vector3d lowest = Eigen::Vector3d::Constant(1e9);
    for (std::size_t s = 0; s < model.spheres.size(); ++s) {
      const auto link = static_cast<std::size_t>(model.sphere_links[s]);
      if (link == 0) continue;  // the base stands on the ground
      Eigen::Vector3d bottom = poses[link] * model.spheres[s].center.cast<double>();
      bottom.y() -= model.spheres[s].radius;
      if (bottom.y() < lowest.y()) lowest = bottom;
    }
    return lowest;
  };
  bool found = false;
  for (double elbow = 0.5; elbow < 2.4 && !found; elbow += 0.05) {
    for (double lift = 0.0; lift < 1.8 && !found; lift += 0.05) {
      reach[1] = lift;
      reach[2] = elbow;
      const double low = lowest_sphere(reach).y();
      found = low > 0.01 && low < 0.04 && !self_colliding(model, reach);
    }
  }
  ASSERT_TRUE(found);
  reach[0] = 0.0;
  const Eigen::Vector3d hand_at = lowest_sphere(reach);

  tools::Scene scene;
  scene.ground.kind = tools::GroundSpec::Kind::kPlane;
  tools::BodySpec bunny;
  bunny.size = 0.15;
  bunny.tree.depth = 3;
  bunny.position = Vec3(static_cast<float>(hand_at.x()), 0.1f, static_cast<float>(hand_at.z()));
  scene.bodies.push_back(bunny);
  tools::SimulationSetup setup = tools::build_world(scene);
  World& world = *setup.world;
  const BodyId target = setup.bodies.front();
  for (int step = 0; step < 1500; ++step) world.step(kControlStep);
  const Vec3 rested = world.body(target).pose.translation;

  const RobotId robot = world.add_robot(model, upright_base(0.0f));
  std::vector<double> from = reach;
  std::vector<double> to = reach;
  from[0] = -0.8;
  to[0] = 0.8;
  world.set_robot_configuration(robot, from);
  constexpr double kDuration = 3.0;  // the sweep. unit: s
  double worst_share = 0.0;          // a leaf overlap over its link's size
  double last_touch = -1.0;          // unit: s
  std::vector<double> errors;        // per frame, the worst joint's. unit: rad or m
  for (int step = 1; step <= 4500; ++step) {
    const double t = step * double{kControlStep};
    step_on_quintic(world, robot, from, to, kDuration, t);
    for (const BodyId link : world.robot_bodies(robot)) {
      const float overlap = deepest_leaf_overlap(world, link, target);
      if (overlap > -0.002f) last_touch = t;
      worst_share = std::max(worst_share, overlap / (2.0 * world.tree(link).root().radius));
    }
    const RobotJointStates states = world.robot_joint_states(robot);
    double error = 0.0;
    for (std::size_t j = 0; j < to.size(); ++j) {
      error = std::max(
          error, std::abs(states.positions[j] - test::quintic(from[j], to[j], kDuration, t).first));
    }
    errors.push_back(error);
  }
  const float moved = (world.body(target).pose.translation - rested).norm();
  std::cout << "contact: bunny moved " << moved << " m, worst leaf overlap " << worst_share
            << " of the link's size, last touch at " << last_touch << " s\n";
  EXPECT_GT(moved, 0.05f);
  EXPECT_GT(last_touch, 0.0);
  EXPECT_LT(worst_share, 0.05);
  // Within 0.5 s of the last touch, every joint back within 1° of the trajectory, and after. A
  // bunny pushed to rest against the arm's last pose touches it to the end: from 0.5 s after the
  // sweep the arm must then hold that pose within 1° with the bunny leaning on it.
  const double settled_from = std::min(last_touch, kDuration) + 0.5;  // unit: s
  const auto recovered = static_cast<std::size_t>(settled_from / double{kControlStep});
  ASSERT_LT(recovered, errors.size());
  for (std::size_t frame = recovered; frame < errors.size(); ++frame) {
    ASSERT_LT(errors[frame], kDegree) << "frame " << frame;
  }
}

TEST(RobotWorld, AScenesRobotStandsAndHoldsItsTargets) {
  const test::TempDir dir;
  const std::vector<double> held = {0.3, 0.5, 0.4, 0.015, 0.015};
  ASSERT_FALSE(self_colliding(test_robot(), held));
  const tools::Scene scene = tools::parse_scene(
      test::scene_with_test_robot(dir.path(), R"("configuration": [0.3, 0.5, 0.4, 0.015, 0.015],
        "targets": [0.3, 0.5, 0.4, 0.015, 0.015])"),
      dir.path() / "scene.json");
  const tools::SimulationSetup setup = tools::build_world(scene);
  const std::vector<RobotId> robots = tools::add_scene_robots(scene, *setup.world).robots;
  ASSERT_EQ(robots.size(), 1U);
  for (int step = 0; step < 1000; ++step) setup.world->step(kControlStep);
  const RobotJointStates states = setup.world->robot_joint_states(robots[0]);
  for (std::size_t j = 0; j < held.size(); ++j) {
    const double unit = j < 3 ? kDegree : 1e-3;  // 0.5° or 0.5 mm
    EXPECT_NEAR(states.positions[j], held[j], 0.5 * unit) << j;
  }
  EXPECT_NEAR(setup.world->robot_link_poses_in_world(robots[0])[0].translation().y(), 1.0, 1e-6);
}

TEST(RobotWorld, AScenesRobotWithTheWrongTargetsIsNamed) {
  const test::TempDir dir;
  const tools::Scene scene = tools::parse_scene(
      test::scene_with_test_robot(dir.path(), R"("targets": [0.1])"), dir.path() / "scene.json");
  const tools::SimulationSetup setup = tools::build_world(scene);
  EXPECT_THAT([&] { (void)tools::add_scene_robots(scene, *setup.world); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("scene.json: /robots/0: targets")));
}

// A one-joint robot whose moving link has neither an <inertial> nor geometry.
TEST(RobotWorld, ALinkWithNoMassAndNoGeometryIsNamed) {
  RobotModel model;
  model.name = "ghost_arm";
  model.links.push_back({"base", -1, Eigen::Isometry3d::Identity(), -1, 1.0});
  model.links[0].inertia = Eigen::Matrix3d::Identity() * 0.01;
  model.links.push_back({"ghost", 0, Eigen::Isometry3d::Identity(), 0});
  model.joints.push_back({"turn", RobotJointType::kRevolute, Eigen::Vector3d::UnitZ(), -1, 1});
  model.sphere_links = {0};
  model.spheres = {Sphere{Vec3::Zero(), 0.1f}};
  World world(WorldSettings{});
  EXPECT_THAT([&] { (void)world.add_robot(model, Transform{}); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("link 'ghost'")));
  EXPECT_EQ(world.body_slots(), 0u);
}

TEST(RobotWorld, AJointTypeTheWorldCannotSimulateIsNamed) {
  const test::TempDir dir;
  test::RobotSpec spec = test::standard_test_robot();
  spec.joints[1].type = "floating";
  const test::TestRobot written = test::write_test_robot(dir.path(), spec);
  const tools::RobotPackage package = tools::parse_robot_package(written.package_option);
  const tools::Robot robot = tools::load_robot(written.urdf, std::span(&package, 1));
  EXPECT_THAT([&] { (void)tools::robot_model(robot, {}); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("shoulder_lift")));
}

}  // namespace
}  // namespace sphys
