// sphys-plan-bench: OMPL's RRT-Connect plans the test robot's arm around the kept pile of 100
// bunnies, sphys's checks from joint values as its validity checker and motion validator, for a
// fixed set of problems (free start and goal with no free straight motion between them, drawn
// from a seed); each path OMPL returns is then checked against the meshes by FCL at ten times
// finer steps. Prints a table per problem and the medians (docs/queries.md).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#include <CLI/CLI.hpp>

#include "plan_arm/ompl_arm.h"
#include "query/other_engines.h"
#include "robot_arm/bunny_pile.h"
#include "robot_arm/robot_arm.h"
#include "sphys/error.h"
#include "sphys/tools/median.h"

namespace sphys::plan_bench {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Clock = std::chrono::steady_clock;

struct Options {
  int problems = 20;
  double time = 10.0;  // per problem. unit: s
  unsigned seed = 1;
  int tree_depth = 0;  // the bunnies' levels the checks ask (0: the world's)
  std::filesystem::path pile = examples::kept_bunny_pile();
};

// The kept pile's trees: built to this many levels, the world using the first two, as the
// queries' benchmark reads it.
constexpr int kTreeDepth = 4;   // unit: levels
constexpr int kLevelsUsed = 2;  // unit: levels

struct Outcome {
  bool solved = false;
  double plan_ms = 0.0;      // RRT-Connect's solve
  double simplify_ms = 0.0;  // OMPL's path simplification after it
  std::size_t configurations = 0;
  std::size_t motions = 0;
  std::size_t waypoints = 0;
  std::size_t finer_states = 0;     // the path's states FCL checked
  std::size_t mesh_collisions = 0;  // of them, where a link mesh touches a bunny's
};

int run(const Options& options) {
  const examples::BunnyPile pile = examples::read_bunny_pile(options.pile, kTreeDepth, kLevelsUsed);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sphys-plan-bench-" + std::to_string(getpid()));
  examples::RobotArm arm = examples::make_test_robot_arm(dir, 60, Vec3::Zero());
  std::filesystem::remove_all(dir);
  const WorldQuery query(*pile.setup.world);
  examples::place_arm_beside(arm, query, pile.bounds.center(), 0.05f);
  const query_bench::FclScene fcl(pile.mesh(), pile.poses, arm.link_meshes());
  RobotCheckSettings settings;
  settings.tree_depth = options.tree_depth;
  const std::size_t joints = arm.joints.size();

  // The problems first, from their own checker, so that each plan counts its own checks alone.
  std::mt19937 rng(options.seed);
  std::vector<examples::ArmProblem> problems;
  {
    examples::ArmChecker drawing(arm, query, settings);
    for (int p = 0; p < options.problems; ++p) {
      problems.push_back(examples::blocked_problem(arm, drawing, rng));
    }
  }
  ompl::RNG::setSeed(options.seed);

  std::vector<Outcome> outcomes;
  std::vector<Transform> link_poses(arm.links.size());
  for (const examples::ArmProblem& problem : problems) {
    examples::ArmChecker checker(arm, query, settings);
    og::SimpleSetup setup(examples::arm_space(arm));
    const ob::SpaceInformationPtr si = setup.getSpaceInformation();
    setup.setStateValidityChecker([&](const ob::State* state) {
      return checker.free_one(examples::values_of(state, joints));
    });
    si->setMotionValidator(std::make_shared<examples::SphysMotionValidator>(si, checker, joints));
    ob::ScopedState<> start(setup.getStateSpace());
    ob::ScopedState<> goal(setup.getStateSpace());
    for (std::size_t j = 0; j < joints; ++j) {
      start[static_cast<unsigned>(j)] = problem.start[j];
      goal[static_cast<unsigned>(j)] = problem.goal[j];
    }
    setup.setStartAndGoalStates(start, goal);
    setup.setPlanner(std::make_shared<og::RRTConnect>(si));
    setup.setup();
    Outcome outcome;
    const auto begin = Clock::now();
    // Timed by a condition read between iterations: solve(seconds) starts a thread to time it,
    // which costs more than an easy problem's whole plan.
    outcome.solved = setup.solve(ob::timedPlannerTerminationCondition(options.time)) ==
                     ob::PlannerStatus::EXACT_SOLUTION;
    const auto planned = Clock::now();
    outcome.configurations = checker.configurations();
    outcome.motions = checker.motions();
    outcome.plan_ms = std::chrono::duration<double, std::milli>(planned - begin).count();
    if (outcome.solved) {
      setup.simplifySolution();
      outcome.simplify_ms =
          std::chrono::duration<double, std::milli>(Clock::now() - planned).count();
      const og::PathGeometric& path = setup.getSolutionPath();
      outcome.waypoints = path.getStateCount();
      for (std::size_t w = 0; w + 1 < outcome.waypoints; ++w) {
        const auto states = examples::steps_between(
            examples::values_of(path.getState(static_cast<unsigned>(w)), joints),
            examples::values_of(path.getState(static_cast<unsigned>(w + 1)), joints),
            examples::kMotionStep / examples::kFinerChecks);
        for (const std::vector<double>& values : states) {
          arm.link_poses(values, link_poses);
          ++outcome.finer_states;
          outcome.mesh_collisions += fcl.collides(link_poses) ? 1 : 0;
        }
      }
    }
    outcomes.push_back(outcome);
  }

  std::printf(
      "## Planning: RRT-Connect, the test robot (%zu spheres, %zu joints) beside %zu bunnies at "
      "rest, %zu problems (seed %u), checks at %d levels of the bunnies' %d\n\n",
      arm.spheres(), joints, pile.poses.size(), problems.size(), options.seed,
      options.tree_depth == 0 ? kLevelsUsed : options.tree_depth, kTreeDepth);
  std::printf(
      "| problem | solved | planning ms | simplifying ms | configurations checked | motions "
      "checked | checks per second | waypoints | path states FCL checked | of them colliding "
      "with the meshes |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  std::vector<double> plan_ms;
  std::vector<double> rates;
  std::size_t solved = 0;
  std::size_t colliding_paths = 0;
  for (std::size_t p = 0; p < outcomes.size(); ++p) {
    const Outcome& o = outcomes[p];
    const double rate = double(o.configurations + o.motions) / (o.plan_ms / 1e3);
    std::printf("| %zu | %s | %.3f | %.3f | %zu | %zu | %.0f | %zu | %zu | %zu |\n", p,
                o.solved ? "yes" : "no", o.plan_ms, o.simplify_ms, o.configurations, o.motions,
                rate, o.waypoints, o.finer_states, o.mesh_collisions);
    plan_ms.push_back(o.plan_ms);
    rates.push_back(rate);
    solved += o.solved ? 1 : 0;
    colliding_paths += o.mesh_collisions > 0 ? 1 : 0;
  }
  std::printf(
      "\nSolved %zu of %zu within %.0f s each. Median planning time %.3f ms; median checks "
      "(configurations and motions) per second %.0f. Paths that touch a bunny's mesh, checked by "
      "FCL at %d times finer steps than the planner's: %zu of %zu.\n",
      solved, outcomes.size(), options.time, tools::median(plan_ms), tools::median(rates),
      examples::kFinerChecks, colliding_paths, solved);
  return solved == outcomes.size() && colliding_paths == 0 ? 0 : 1;
}

}  // namespace
}  // namespace sphys::plan_bench

int main(int argc, char** argv) {
  sphys::plan_bench::Options options;
  CLI::App app("sphys-plan-bench: OMPL plans the test robot around a pile with sphys's checks");
  app.add_option("--problems", options.problems, "Start and goal pairs planned")
      ->check(CLI::Range(1, 100000));
  app.add_option("--time", options.time, "Planning time allowed per problem (s)")
      ->check(CLI::PositiveNumber);
  app.add_option("--seed", options.seed, "Seed of the problems and of OMPL's sampling");
  app.add_option("--tree-depth", options.tree_depth,
                 "Levels of the bunnies' trees the checks ask (0: the world's 2; up to 4)")
      ->check(CLI::Range(0, 4));
  app.add_option("--pile", options.pile, "The pile, a scene of bunnies at rest");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help is a "parse error" of exit code 0; a bad option is bad input, exit 2.
    return app.exit(error) == 0 ? 0 : 2;
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  try {
    return sphys::plan_bench::run(options);
  } catch (const sphys::Error& error) {
    std::fprintf(stderr, "sphys-plan-bench: error: %s\n", error.what());
    return 2;
  }
}
