// The test robot plans with plan_arm's checker (OMPL's RRT-Connect over sphys's checks from joint
// values) a path around a settled pile of small bunnies to a reach beside the top one, then plays
// the path out in the same world under position control (World::add_robot, 1 kHz), and turns its
// pan joint on, its hand pushing that bunny off the pile.
//
//   push_bunny [--bunnies N] [--time SECONDS] [--seed K]
//
// Prints JSON: how far the pushed bunny moved and the largest tracking error, on the planned path
// and over the whole run. Exit 0 when a path was found and the bunny moved, 1 when not, 2 for bad
// arguments.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#include "plan_arm/ompl_arm.h"
#include "robot_arm/robot_arm.h"
#include "sphys/error.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/scene.h"
#include "sphys/world_query.h"
#include "support/quintic.h"

namespace {

using sphys::examples::RobotArm;

constexpr float kControlStep = 1e-3f;     // 1 kHz control. unit: s
constexpr double kBunnySize = 0.12;       // a bunny's longest side. unit: m
constexpr float kPileDistance = 0.42f;    // from the arm's base to the pile's axis. unit: m
constexpr double kJointSpeed = 0.5;       // the planned path's top joint speed. unit: rad/s
constexpr double kPushTurn = 0.8;         // how far the pan joint turns to push. unit: rad
constexpr double kFingerOpening = 0.015;  // each finger's position throughout. unit: m
constexpr float kPushDepth = 0.03f;       // how deep the sweep passes into the bunny. unit: m

struct Arguments {
  int bunnies = 3;
  double time = 10.0;  // for planning. unit: s
  unsigned seed = 1;
};

Arguments parse(int argc, char** argv) {
  Arguments out;
  for (const auto& [name, value] :
       sphys::examples::example_options(argc, argv, {"--bunnies", "--time", "--seed"})) {
    if (name == "--bunnies") out.bunnies = std::stoi(value);
    if (name == "--time") out.time = std::stod(value);
    if (name == "--seed") out.seed = static_cast<unsigned>(std::stoul(value));
  }
  if (out.bunnies < 1 || out.bunnies > 10) throw sphys::Error("--bunnies: 1 to 10");
  return out;
}

// A stack of small bunnies on the plane y = 0 at (kPileDistance, 0, 0), stepped until they sleep.
sphys::tools::SimulationSetup settled_pile(int bunnies) {
  sphys::tools::Scene scene;
  scene.name = "push_bunny pile";
  scene.ground.kind = sphys::tools::GroundSpec::Kind::kPlane;
  for (int i = 0; i < bunnies; ++i) {
    sphys::tools::BodySpec bunny;
    bunny.size = kBunnySize;
    bunny.tree.depth = 3;
    bunny.position = sphys::Vec3(kPileDistance, 0.08f + 0.11f * static_cast<float>(i), 0.0f);
    bunny.orientation =
        sphys::Quat(Eigen::AngleAxisf(0.7f * static_cast<float>(i), sphys::Vec3::UnitY()));
    scene.bodies.push_back(bunny);
  }
  sphys::tools::SimulationSetup setup = sphys::tools::build_world(scene);
  for (int step = 0; step < 600; ++step) {
    setup.world->step(1.0f / 60.0f);
    if (std::ranges::all_of(setup.bodies,
                            [&](sphys::BodyId b) { return setup.world->asleep(b); })) {
      break;
    }
  }
  return setup;
}

// The bodies the arm's spheres, each shrunk by `shrink` (unit: m), overlap at the joint values.
std::vector<sphys::BodyId> bodies_touched(const RobotArm& arm, const sphys::WorldQuery& query,
                                          const std::vector<double>& values, float shrink) {
  std::vector<float> spheres(arm.spheres() * 4);
  arm.posed_spheres(values, spheres);
  std::vector<sphys::BodyId> touched;
  for (std::size_t i = 0; i < arm.spheres(); ++i) {
    const sphys::Vec3 centre(spheres[4 * i], spheres[4 * i + 1], spheres[4 * i + 2]);
    const float radius = spheres[4 * i + 3] - shrink;
    if (radius <= 0.0f) continue;
    for (const sphys::BodyId body : query.overlap_sphere(centre, radius)) {
      if (std::ranges::find(touched, body) == touched.end()) touched.push_back(body);
    }
  }
  return touched;
}

// A free reach from which turning the pan joint by kPushTurn sweeps the hand through `target`,
// kPushDepth deep, and through nothing else the world holds, every sphere of the arm but its
// base's above the ground.
std::vector<double> push_start(const RobotArm& arm, sphys::examples::ArmChecker& checker,
                               const sphys::WorldQuery& query, sphys::BodyId target,
                               std::mt19937& rng) {
  const auto base = static_cast<std::int32_t>(
      std::ranges::find(arm.links, arm.robot.root_link, &sphys::tools::LinkSpheres::link) -
      arm.links.begin());
  for (int tries = 0; tries < 20000; ++tries) {
    std::vector<double> start(arm.joints.size(), kFingerOpening);
    for (std::size_t j = 0; j < 3; ++j) {
      start[j] = std::uniform_real_distribution<double>(arm.limits[j][0] + 0.9,
                                                        arm.limits[j][1] - 0.9)(rng);
    }
    if (!checker.free_one(start)) continue;
    std::vector<double> end = start;
    end[0] += kPushTurn;
    bool only_target = false;  // the target reached kPushDepth deep
    bool clean = true;
    for (const std::vector<double>& state :
         sphys::examples::steps_between(start, end, sphys::examples::kMotionStep)) {
      std::vector<float> spheres(arm.spheres() * 4);
      arm.posed_spheres(state, spheres);
      for (std::size_t i = 0; i < arm.spheres(); ++i) {
        clean = clean &&
                (arm.sphere_links[i] == base || spheres[4 * i + 1] - spheres[4 * i + 3] > 0.005f);
      }
      for (const sphys::BodyId body : bodies_touched(arm, query, state, 0.0f)) {
        clean = clean && body == target;
      }
      only_target = only_target || !bodies_touched(arm, query, state, kPushDepth).empty();
    }
    if (clean && only_target) return start;
  }
  throw sphys::Error("no reach beside the top bunny found from which a pan turn pushes it alone");
}

// Plays a motion from `from` to `to` out under position control, its slowest joint at
// kJointSpeed at the top; returns the largest tracking error of a turning joint. unit: rad
double play(sphys::World& world, sphys::RobotId robot, const std::vector<double>& from,
            const std::vector<double>& to, double settle) {
  double longest = 0.0;
  for (std::size_t j = 0; j < from.size(); ++j)
    longest = std::max(longest, std::abs(to[j] - from[j]));
  const double duration = std::max(0.2, sphys::test::kQuinticPeakOverMean * longest / kJointSpeed);
  std::vector<sphys::RobotJointControl> controls(from.size());
  double worst = 0.0;
  const auto steps = static_cast<int>((duration + settle) / double{kControlStep});
  for (int step = 1; step <= steps; ++step) {
    const double t = step * double{kControlStep};
    for (std::size_t j = 0; j < from.size(); ++j) {
      controls[j].mode = sphys::RobotControlMode::kPosition;
      std::tie(controls[j].target_position, controls[j].target_velocity) =
          sphys::test::quintic(from[j], to[j], duration, t);
    }
    world.set_robot_controls(robot, controls);
    world.step(kControlStep);
    const sphys::RobotJointStates states = world.robot_joint_states(robot);
    for (std::size_t j = 0; j < 3; ++j) {
      worst = std::max(worst, std::abs(states.positions[j] - controls[j].target_position));
    }
  }
  return worst;
}

int run(const Arguments& arguments) {
  sphys::tools::SimulationSetup pile = settled_pile(arguments.bunnies);
  sphys::World& world = *pile.world;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sphys-push-bunny-" + std::to_string(getpid()));
  const RobotArm arm = sphys::examples::make_test_robot_arm(dir, 60, sphys::Vec3::Zero());
  std::filesystem::remove_all(dir);
  // The highest bunny where the pile came to rest.
  const sphys::BodyId target = *std::ranges::max_element(
      pile.bodies, {}, [&](sphys::BodyId b) { return world.body(b).pose.translation.y(); });
  const sphys::Vec3 rested = world.body(target).pose.translation;

  // Planned around the pile as it rests.
  std::mt19937 rng(arguments.seed);
  std::vector<double> reach;
  std::vector<std::vector<double>> path;
  {
    const sphys::WorldQuery query(world);
    sphys::examples::ArmChecker checker(arm, query);
    reach = push_start(arm, checker, query, target, rng);
    std::vector<double> start(arm.joints.size(), 0.0);
    for (std::size_t j = 3; j < start.size(); ++j) start[j] = kFingerOpening;
    path = sphys::examples::plan_path(arm, checker, start, reach, arguments.time);
  }
  if (path.empty()) {
    std::printf("{\n  \"solved\": false\n}\n");
    return 1;
  }

  // Played out: the planned path, then the push, then a rest.
  sphys::RobotModel model = sphys::examples::model_of(arm);
  // The fingers' few spheres meet across the gap between them, as an SRDF would say.
  model.allowed_link_pairs.push_back(
      {model.link_index("finger_left_link"), model.link_index("finger_right_link")});
  const sphys::RobotId robot = world.add_robot(model, arm.base);
  world.set_robot_configuration(robot, path.front());
  double path_error = 0.0;
  for (std::size_t w = 0; w + 1 < path.size(); ++w) {
    path_error = std::max(path_error, play(world, robot, path[w], path[w + 1], 0.0));
  }
  std::vector<double> pushed = reach;
  pushed[0] += kPushTurn;
  const double push_error = play(world, robot, reach, pushed, 1.0);
  const float moved = (world.body(target).pose.translation - rested).norm();
  std::printf(
      "{\n  \"solved\": true,\n  \"waypoints\": %zu,\n  \"bunnies\": %d,\n"
      "  \"bunny_moved_m\": %.4f,\n  \"largest_tracking_error_on_path_deg\": %.4f,\n"
      "  \"largest_tracking_error_pushing_deg\": %.4f\n}\n",
      path.size(), arguments.bunnies, moved, path_error * 180.0 / std::numbers::pi,
      std::max(path_error, push_error) * 180.0 / std::numbers::pi);
  return moved > 0.01f ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return sphys::examples::run_example("push_bunny", [&] { return run(parse(argc, argv)); });
}
