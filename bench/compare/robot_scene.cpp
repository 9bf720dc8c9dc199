#include "robot_scene.h"

#include <algorithm>
#include <filesystem>
#include <numbers>
#include <span>
#include <sstream>
#include <unistd.h>

#include "engine.h"
#include "engine_rows.h"
#include "robot_arm/robot_arm.h"
#include "sphys/error.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/robot_model_file.h"
#include "sphys/tools/tree_cache.h"
#include "sphys/world.h"
#include "support/quintic.h"

namespace sphys::compare {
namespace {

constexpr int kMaxBunnies = 200;
constexpr int kPileDepth = 3;             // of the bunnies' sphere-trees. unit: levels
constexpr double kBunnySize = 0.12;       // a bunny's longest side. unit: m
constexpr float kPileDistance = 0.45f;    // from the arm's base to the pile's axis. unit: m
constexpr float kDropSpacing = 0.13f;     // of the bunnies dropped 3 × 3 a layer. unit: m
constexpr int kArmSpheres = 60;           // covering the arm's links, as the planning examples
constexpr double kControlStep = 1e-3;     // 1 kHz. unit: s
constexpr int kSettleFrames = 1200;       // at most, of 1/60 s, for the pile to fall asleep
constexpr double kSlumpTime = 2.0;        // of the pile in MuJoCo before the run. unit: s
constexpr double kFingerOpening = 0.015;  // each finger's position throughout. unit: m
// The first sweep's shoulder lift: by default the hand brushes the pile's top; at most it
// ploughs through the pile's upper layer. unit: rad
constexpr double kShallowLift = 0.9;
constexpr double kDeepestLift = 1.1;
// arm-drag:M: the lone bunny, its distance from the arm's base (under the hand's path with the
// shoulder lifted by kDragLift) and its heaviest.
constexpr double kLoneBunnySize = 0.15;      // its longest side. unit: m
constexpr float kLoneBunnyDistance = 0.45f;  // unit: m
constexpr double kDragLift = 1.0;            // unit: rad
constexpr double kMaxLoneBunnyMass = 100.0;  // unit: kg

// B bunnies dropped in layers of 3 × 3 around the pile's axis, each turned about the vertical.
BenchScene dropped_pile(const std::string& name, int bunnies) {
  tools::Scene pile;
  pile.name = name;
  for (int i = 0; i < bunnies; ++i) {
    tools::BodySpec bunny;
    bunny.size = kBunnySize;
    bunny.tree.depth = kPileDepth;
    const auto x = static_cast<float>(i % 3 - 1) * kDropSpacing;
    const auto z = static_cast<float>(i / 3 % 3 - 1) * kDropSpacing;
    bunny.position = Vec3(kPileDistance + x, 0.08f + 0.12f * static_cast<float>(i / 9), z);
    bunny.orientation = Quat(Eigen::AngleAxisf(0.7f * static_cast<float>(i), Vec3::UnitY()));
    pile.bodies.push_back(bunny);
  }
  return bunny_bench_scene(name, std::move(pile), kPileDepth);
}

// The scene's bunnies (its first bodies) start at these poses.
void place_bunnies(BenchScene& bench, std::span<const Transform> poses) {
  for (std::size_t b = 0; b < bench.scene.bodies.size(); ++b) {
    bench.scene.bodies[b].position = poses[b].translation;
    bench.scene.bodies[b].orientation = poses[b].rotation;
    bench.start[b] = poses[b];
  }
}

// The bunnies stepped in sphys (1/60 s steps) beside the robot held at its motion's start, until
// every one sleeps.
void settle_in_sphys(BenchScene& bench, const BenchRobot& robot) {
  tools::BuildWorldOptions build;
  build.cache_dir = tools::default_cache_dir();
  const tools::SimulationSetup setup = tools::build_world(bench.scene, build);
  World& world = *setup.world;
  const RobotId arm = world.add_robot(robot.model, robot.base);
  const std::vector<double>& start = robot.motion.waypoints.front();
  world.set_robot_configuration(arm, start);
  std::vector<RobotJointControl> hold(start.size(), robot.gains);
  for (std::size_t j = 0; j < hold.size(); ++j) {
    hold[j].mode = RobotControlMode::kPosition;
    hold[j].target_position = start[j];
  }
  world.set_robot_controls(arm, hold);
  for (int frame = 0; frame < kSettleFrames; ++frame) {
    world.step(static_cast<float>(bench.scene.time_step));
    if (std::ranges::all_of(setup.bodies, [&](BodyId b) { return world.asleep(b); })) break;
  }
  std::vector<Transform> poses;
  for (const BodyId bunny : setup.bodies) poses.push_back(world.body(bunny).pose);
  place_bunnies(bench, poses);
}

// The whole scene stepped for kSlumpTime in MuJoCo, the robot held at its motion's start: MuJoCo's
// softer contacts and friction let a pile that rests in sphys slump at first (its top bunnies
// slide off), and the run starts the bunnies where it left them, so that the arm meets the same
// pile in both engines.
void slump_in_mujoco(BenchScene& bench) {
  BenchScene held = bench;
  held.robot->motion = {{bench.robot->motion.waypoints.front()}, {0.0}};
  const std::unique_ptr<Engine> mujoco = make_mujoco_engine(held);
  for (int step = 0; step < static_cast<int>(kSlumpTime / held.time_step); ++step) mujoco->step();
  std::vector<BodyState> slumped;
  mujoco->read(slumped);
  std::vector<Transform> poses;
  for (const BodyState& body : slumped) poses.push_back(body.pose);
  place_bunnies(bench, poses);
}

// The test robot with its 60 spheres, standing at the origin, its fingers' few spheres meeting
// across the gap between them allowed to touch (as an SRDF would say).
RobotModel test_robot_model(Transform& base) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sphys-compare-arm-" + std::to_string(getpid()));
  const examples::RobotArm arm = examples::make_test_robot_arm(dir, kArmSpheres, Vec3::Zero());
  std::filesystem::remove_all(dir);
  RobotModel model = tools::robot_model(arm.robot, arm.links);
  model.allowed_link_pairs.push_back(
      {model.link_index("finger_left_link"), model.link_index("finger_right_link")});
  base = arm.base;
  model.base = Eigen::Isometry3d::Identity();
  model.base.translate(base.translation.cast<double>());
  model.base.rotate(base.rotation.cast<double>());
  return model;
}

// The robot's body of each link, as World::add_robot makes them: the root's first, then the link
// each joint moves; a link fixed to its parent is in its parent's body.
std::vector<std::size_t> link_bodies(const RobotModel& model) {
  std::vector<std::size_t> body(model.links.size(), 0);
  for (std::size_t l = 1; l < model.links.size(); ++l) {
    const RobotModel::Link& link = model.links[l];
    body[l] = link.joint >= 0 ? static_cast<std::size_t>(link.joint) + 1
                              : body[static_cast<std::size_t>(link.parent)];
  }
  return body;
}

// The robot's bodies and joints as sphys's add_robot makes them, appended to the scene.
void add_robot_parts(BenchScene& bench, BenchRobot& robot) {
  World world;
  const RobotId id = world.add_robot(robot.model, robot.base);
  const std::span<const BodyId> bodies = world.robot_bodies(id);
  robot.first_body = bench.start.size();
  robot.body_count = bodies.size();
  const auto scene_index = [&](BodyId body) {
    return robot.first_body +
           static_cast<std::size_t>(std::ranges::find(bodies, body) - bodies.begin());
  };
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const RigidBody& body = world.body(bodies[b]);
    const std::shared_ptr<const SphereTree> tree = world.shared_tree(bodies[b]);
    BenchShape shape;
    shape.name = "link body " + std::to_string(b);
    shape.mass = body.mass();
    shape.inertia = body.inertia_body;
    for (const std::uint32_t leaf : tree->leaves()) {
      const Sphere& sphere = tree->sphere(leaf);
      shape.leaves.push_back(sphere);
      shape.max_vertex_distance =
          std::max(shape.max_vertex_distance, sphere.center.norm() + sphere.radius);
    }
    shape.tree = tree;
    bench.shape_of.push_back(static_cast<std::uint32_t>(bench.shapes.size()));
    bench.shapes.push_back(std::move(shape));
    bench.start.push_back(body.pose);
  }
  robot.first_joint = bench.joints.size();
  for (const JointId joint : world.robot_joints(id)) {
    tools::JointSpec spec;
    spec.desc = world.joint(joint);
    spec.body_a = scene_index(spec.desc.body_a);
    spec.body_b = scene_index(spec.desc.body_b);
    bench.joints.push_back(spec);
  }
  const std::vector<std::size_t> body_of = link_bodies(robot.model);
  for (const auto& [a, b] : robot.model.allowed_link_pairs) {
    const std::size_t body_a = body_of[static_cast<std::size_t>(a)];
    const std::size_t body_b = body_of[static_cast<std::size_t>(b)];
    if (body_a != body_b) {
      robot.apart.push_back({robot.first_body + body_a, robot.first_body + body_b});
    }
  }
}

// From upright, over the pile to its near side, then a sweep of the pan joint through the pile
// with the shoulder lifted by `lift` (unit: rad; kShallowLift brushes the pile's top), a lift of
// the hand and a sweep back higher, then a hold. The quintics' top speeds stay under the URDF's
// 1 rad/s. Joints: pan, lift, elbow (rad), the two fingers (m).
RobotMotion sweeps(double lift) {
  const auto at = [](double pan, double shoulder, double elbow) {
    return std::vector<double>{pan, shoulder, elbow, kFingerOpening, kFingerOpening};
  };
  RobotMotion motion;
  motion.waypoints = {at(0.0, 0.0, 0.0),  at(-0.65, lift, 1.3), at(0.65, lift, 1.3),
                      at(0.65, 0.8, 1.3), at(-0.65, 0.8, 1.3),  at(-0.65, 0.8, 1.3)};
  motion.arrivals = {0.0, 2.5, 5.5, 6.5, 9.0, 10.0};
  return motion;
}

// One 15 cm bunny of `mass` (unit: kg) lying on the plane across the hand's path at the deepest
// sweep (the pan at 0), as the pile's bunnies are made.
BenchScene lone_bunny(const std::string& name, double mass) {
  tools::Scene scene;
  scene.name = name;
  tools::BodySpec bunny;
  bunny.size = kLoneBunnySize;
  bunny.tree.depth = kPileDepth;
  bunny.mass = mass;
  bunny.position = Vec3(kLoneBunnyDistance, 0.1f, 0.0f);
  scene.bodies.push_back(bunny);
  return bunny_bench_scene(name, std::move(scene), kPileDepth);
}

// The test robot beside `bench`'s bunnies, which settle by it, sweeping with the shoulder lifted
// by `lift` (unit: rad).
BenchScene arm_scene(BenchScene bench, double lift) {
  BenchRobot robot;
  robot.model = test_robot_model(robot.base);
  robot.motion = sweeps(lift);
  if (robot.motion.waypoints.front().size() != robot.model.joints.size()) {
    throw Error("arm scene: the motion's waypoints do not match the test robot's joints");
  }
  settle_in_sphys(bench, robot);
  bench.scene.time_step = kControlStep;
  bench.time_step = kControlStep;
  add_robot_parts(bench, robot);
  bench.frames = static_cast<int>(robot.motion.arrivals.back() / kControlStep + 0.5);
  bench.robot = std::move(robot);
  slump_in_mujoco(bench);
  return bench;
}

}  // namespace

void RobotMotion::targets(double t, std::vector<double>& positions,
                          std::vector<double>& speeds) const {
  const auto next = std::ranges::upper_bound(arrivals, t);
  const std::size_t to = std::min<std::size_t>(next - arrivals.begin(), arrivals.size() - 1);
  const std::size_t from = to == 0 ? 0 : to - 1;
  const double duration = arrivals[to] - arrivals[from];
  positions.resize(waypoints[to].size());
  speeds.resize(waypoints[to].size());
  for (std::size_t j = 0; j < positions.size(); ++j) {
    std::tie(positions[j], speeds[j]) =
        duration > 0.0
            ? test::quintic(waypoints[from][j], waypoints[to][j], duration, t - arrivals[from])
            : std::pair{waypoints[to][j], 0.0};
  }
}

bool is_robot_scene(const std::string& name) {
  return name.starts_with("arm:") || name.starts_with("arm-drag:");
}

BenchScene make_robot_scene(const std::string& name) {
  if (name.starts_with("arm-drag:")) {
    std::istringstream mass_text(name.substr(9));
    double mass = 0.0;
    if (!(mass_text >> mass) || !(mass > 0.0) || mass > kMaxLoneBunnyMass ||
        mass_text.peek() != std::char_traits<char>::eof()) {
      throw Error("arm scene '" + name + "': the form is arm-drag:M, M the bunny's mass in kg, " +
                  formatted("above 0 and at most %g", kMaxLoneBunnyMass));
    }
    return arm_scene(lone_bunny(name, mass), kDragLift);
  }
  std::istringstream in(name.substr(std::min<std::size_t>(name.size(), 4)));
  int bunnies = 0;
  double lift = kShallowLift;
  bool valid = is_robot_scene(name) && in >> bunnies && bunnies >= 1 && bunnies <= kMaxBunnies;
  if (valid && in.peek() == ':') {
    in.get();
    valid = in >> lift && lift >= kShallowLift && lift <= kDeepestLift;
  }
  if (!valid || in.peek() != std::char_traits<char>::eof()) {
    throw Error("arm scene '" + name + "': the forms are arm:B and arm:B:L, B bunnies from 1 to " +
                std::to_string(kMaxBunnies) + ", L the sweep's shoulder lift from " +
                formatted("%.2f to %.2f rad", kShallowLift, kDeepestLift));
  }
  return arm_scene(dropped_pile(name, bunnies), lift);
}

}  // namespace sphys::compare
