// Plans the test robot's arm around a pile of bunnies with OMPL (RRT-Connect), sphys's checks from
// joint values (RobotChecker) serving as OMPL's state-validity checker and motion validator, then
// checks the path it returns with sphys's own overlap queries at ten times finer steps.
//
//   plan_arm [--stacks S] [--per-stack N] [--time SECONDS] [--seed K]
//
// Prints the plan as JSON; exit 0 when a path was found and every state along it is free, 1 when
// not, 2 for bad arguments.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#include "plan_arm/ompl_arm.h"
#include "robot_arm/bunny_pile.h"
#include "robot_arm/robot_arm.h"
#include "sphys/error.h"
#include "sphys/robot_check.h"
#include "sphys/tools/robot_model_file.h"
#include "sphys/world_query.h"

namespace {

using sphys::examples::ArmChecker;
using sphys::examples::kFinerChecks;
using sphys::examples::kMotionStep;
using sphys::examples::RobotArm;
using sphys::examples::steps_between;

struct Arguments {
  int stacks = 3;
  int per_stack = 4;
  double time = 20.0;  // unit: s
  unsigned seed = 1;
};

Arguments parse(int argc, char** argv) {
  Arguments out;
  for (const auto& [name, value] : sphys::examples::example_options(
           argc, argv, {"--stacks", "--per-stack", "--time", "--seed"})) {
    if (name == "--stacks") out.stacks = std::stoi(value);
    if (name == "--per-stack") out.per_stack = std::stoi(value);
    if (name == "--time") out.time = std::stod(value);
    if (name == "--seed") out.seed = static_cast<unsigned>(std::stoul(value));
  }
  return out;
}

int run(const Arguments& arguments) {
  const sphys::examples::BunnyPile pile =
      sphys::examples::settle_bunny_pile(arguments.stacks, arguments.per_stack, 900);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sphys-plan-arm-" + std::to_string(getpid()));
  RobotArm arm = sphys::examples::make_test_robot_arm(dir, 60, sphys::Vec3::Zero());
  std::filesystem::remove_all(dir);
  const sphys::WorldQuery query(*pile.setup.world);
  // At the pile's side, on the plane, so that many of its reaches end in a bunny.
  sphys::examples::place_arm_beside(arm, query, pile.bounds.center(), 0.05f);
  ArmChecker checker(arm, query);
  const std::size_t joints = arm.joints.size();

  // A start and a goal that are free but not joined by a free straight motion: the planner must
  // go around the bunnies.
  std::mt19937 rng(arguments.seed);
  const auto [start, goal] = sphys::examples::blocked_problem(arm, checker, rng);
  const auto begin = std::chrono::steady_clock::now();
  const std::vector<std::vector<double>> path =
      sphys::examples::plan_path(arm, checker, start, goal, arguments.time);
  const bool solved = !path.empty();
  const std::size_t waypoints = path.size();
  std::size_t finer_states = 0;
  std::size_t colliding_states = 0;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  if (solved) {
    // Every state at finer steps, each sphere asked of the world by sphys's overlap query.
    std::vector<float> spheres(arm.spheres() * 4);
    for (std::size_t w = 0; w + 1 < waypoints; ++w) {
      for (const std::vector<double>& v :
           steps_between(path[w], path[w + 1], kMotionStep / kFinerChecks)) {
        arm.posed_spheres(v, spheres);
        ++finer_states;
        for (std::size_t i = 0; i < arm.spheres(); ++i) {
          const sphys::Vec3 centre(spheres[4 * i], spheres[4 * i + 1], spheres[4 * i + 2]);
          if (!query.overlap_sphere(centre, spheres[4 * i + 3]).empty()) {
            ++colliding_states;
            break;
          }
        }
      }
    }
  }
  const bool free_path = solved && colliding_states == 0;
  std::printf(
      "{\n  \"bunnies\": %zu,\n  \"robot_spheres\": %zu,\n  \"joints\": %zu,\n"
      "  \"solved\": %s,\n  \"planning_seconds\": %.3f,\n  \"waypoints\": %zu,\n"
      "  \"configurations_checked\": %zu,\n  \"motions_checked\": %zu,\n"
      "  \"path_states_checked_by_queries\": %zu,\n  \"path_states_colliding\": %zu\n}\n",
      pile.poses.size(), arm.spheres(), joints, solved ? "true" : "false", seconds, waypoints,
      checker.configurations(), checker.motions(), finer_states, colliding_states);
  return free_path ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return sphys::examples::run_example("plan_arm", [&] { return run(parse(argc, argv)); });
}
