// `sphys query`: the library's answers, as JSON, about a scene the test writes; bad input exits 2
// naming the option.

#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "apps/cli.h"
#include "sphys/robot_check.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"
#include "sphys/world_query.h"
#include "support/temp_file.h"

namespace sphys {
namespace {

using test::expect_bad_input;
using test::sphys_cli;

// Three bunnies in a row along x at y = 1 with quick trees over the exact plane (no body), and
// no gravity.
std::string write_row_scene(const test::TempDir& dir) {
  const std::string path = (dir.path() / "row.json").string();
  std::ofstream(path) << R"({"format": "sphys-scene", "version": 1, "gravity": [0, 0, 0],
    "ground": {"type": "plane"}, "defaults": {"sphere_tree": {"method": "octree", "depth": 2}},
    "bodies": [{"position": [0, 1, 0]}, {"position": [2, 1, 0]}, {"position": [4, 1, 0]}]})";
  return path;
}

nlohmann::json run_query(const std::vector<std::string>& args) {
  const test::CommandResult r = sphys_cli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(QueryCommand, AnswersAreTheLibrarysAsJson) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const std::string scene = write_row_scene(dir);
  // The same world built here, asked the same questions through the library.
  const tools::SimulationSetup setup = tools::build_world(tools::load_scene(scene));
  const WorldQuery query(*setup.world);

  const nlohmann::json down = run_query({"query", scene, "--ray", "2", "5", "0", "0", "-1", "0"});
  const std::optional<RayHit> expected_down = query.cast_ray({Vec3(2, 5, 0), Vec3(0, -1, 0)});
  ASSERT_TRUE(expected_down.has_value());
  EXPECT_EQ(down["query"], "ray");
  EXPECT_EQ(down["hit"]["body"], 1);
  EXPECT_FLOAT_EQ(down["hit"]["distance"].get<float>(), expected_down->distance);
  EXPECT_EQ(down["hit"]["leaf"], expected_down->leaf);

  const nlohmann::json along =
      run_query({"query", scene, "--ray", "-5", "1", "0", "1", "0", "0", "--all"});
  ASSERT_EQ(along["hits"].size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(along["hits"][i]["body"], i);
  const nlohmann::json skipped =
      run_query({"query", scene, "--ray", "-5", "1", "0", "1", "0", "0", "--skip", "0", "1"});
  EXPECT_EQ(skipped["hit"]["body"], 2);
  const nlohmann::json short_ray =
      run_query({"query", scene, "--ray", "-5", "1", "0", "1", "0", "0", "--max-distance", "1"});
  EXPECT_TRUE(short_ray["hit"].is_null());

  EXPECT_EQ(run_query({"query", scene, "--sphere", "2", "1", "0", "0.05"})["bodies"],
            nlohmann::json::array({1}));
  EXPECT_EQ(run_query({"query", scene, "--aabb", "-1", "0", "-1", "2.1", "2", "1"})["bodies"],
            nlohmann::json::array({0, 1}));
  EXPECT_EQ(run_query({"query", scene, "--box", "4", "1", "0", "0.1", "0.1", "0.1", "--orientation",
                       "0", "0.7071068", "0", "0.7071068"})["bodies"],
            nlohmann::json::array({2}));

  const nlohmann::json gap = run_query({"query", scene, "--distance", "0", "2"});
  const DistanceResult expected_gap = query.distance(setup.bodies[0], setup.bodies[2]);
  EXPECT_FLOAT_EQ(gap["result"]["distance"].get<float>(), expected_gap.distance);
  EXPECT_TRUE(gap["result"]["exact"].get<bool>());
  EXPECT_GT(expected_gap.distance, 2.0f);

  const nlohmann::json to_point =
      run_query({"query", scene, "--point-distance", "1", "2", "9", "0"});
  EXPECT_FLOAT_EQ(to_point["result"]["distance"].get<float>(),
                  query.distance(setup.bodies[1], Vec3(2, 9, 0)).distance);
}

TEST(QueryCommand, BadInputExitsTwoNamingTheOption) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const std::string scene = write_row_scene(dir);
  expect_bad_input({"query", scene, "--ray", "0", "5", "0", "0", "0", "0"},
                   "--ray: ray.direction: zero length");
  expect_bad_input({"query", scene, "--ray", "nan", "5", "0", "0", "1", "0"},
                   "--ray: ray.origin: not finite");
  expect_bad_input({"query", scene, "--ray", "0", "5", "0"}, "--ray");
  expect_bad_input({"query", scene, "--distance", "0", "7"},
                   "--distance: no body 7 in the scene (bodies 0..2)");
  expect_bad_input({"query", scene, "--distance", "1", "1"}, "--distance: body_b: the same body");
  expect_bad_input({"query", scene, "--sphere", "0", "0", "0", "-1"}, "--sphere: radius");
  expect_bad_input({"query", scene, "--skip", "5", "--sphere", "0", "0", "0", "1"},
                   "--skip: no body 5");
  expect_bad_input({"query", scene}, "give exactly one of --ray");
  expect_bad_input({"query", scene, "--sphere", "0", "0", "0", "1", "--distance", "0", "1"},
                   "(got 2)");
}

// A one-joint robot beside the row: "turn" about y from its base, one sphere of 0.1 m 1 m out on
// x; its files (URDF, cuRobo's sphere YAML) and, by hand, the model they describe.
struct Swing {
  explicit Swing(const test::TempDir& dir)
      : urdf((dir.path() / "swing.urdf").string()), spheres((dir.path() / "swing.yml").string()) {
    std::ofstream(urdf) << R"(<?xml version="1.0"?>
<robot name="swing">
  <link name="base_link"/>
  <link name="arm"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="turn" type="revolute">
    <parent link="base_link"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-3.14" upper="3.14" effort="1" velocity="1"/>
  </joint>
</robot>
)";
    std::ofstream(spheres) << "collision_spheres:\n  arm:\n    - center: [1.0, 0.0, 0.0]\n"
                              "      radius: 0.1\n";
    model.name = "swing";
    model.links = {{"base_link", -1, Eigen::Isometry3d::Identity(), -1},
                   {"arm", 0, Eigen::Isometry3d::Identity(), 0}};
    model.joints = {{"turn", RobotJointType::kRevolute, Eigen::Vector3d::UnitY(), -3.14, 3.14}};
    model.sphere_links = {1};
    model.spheres = {{Vec3(1.0f, 0.0f, 0.0f), 0.1f}};
    model.base = Eigen::Isometry3d::Identity();
    model.base.translate(Eigen::Vector3d(1, 1, 0));  // the --base the test gives
  }
  std::string urdf;
  std::string spheres;
  RobotModel model;
};

TEST(QueryCommand, ARobotsAnswersAreTheRobotCheckersAsJson) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const std::string scene = write_row_scene(dir);
  const Swing swing(dir);
  const tools::SimulationSetup setup = tools::build_world(tools::load_scene(scene));
  const WorldQuery query(*setup.world);
  const RobotChecker checker(query, swing.model);
  const std::vector<std::string> robot = {
      "query",       scene,    "--robot", swing.urdf, "--spheres-from",
      swing.spheres, "--base", "1",       "1",        "0",
      "0",           "0",      "0",       "1"};
  const auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = robot;
    args.insert(args.end(), more.begin(), more.end());
    return run_query(args);
  };
  // The sphere in the middle bunny, below the row, in the first bunny.
  std::size_t free = 0;
  for (const double turn : {0.0, 1.5707, 3.0}) {
    const nlohmann::json answer = with({"--joint", "turn=" + std::to_string(turn)});
    std::vector<ConfigurationResult> expected(1);
    checker.check(std::vector{turn}, expected);
    EXPECT_EQ(answer["query"], "robot");
    EXPECT_EQ(answer["joints"], nlohmann::json::array({"turn"}));
    EXPECT_EQ(answer["free"], expected[0].free) << turn;
    if (expected[0].free) {
      ++free;
      EXPECT_TRUE(answer["collision"].is_null());
      continue;
    }
    EXPECT_EQ(answer["collision"]["sphere"], 0);
    EXPECT_EQ(answer["collision"]["link"], "arm");
    EXPECT_EQ(answer["collision"]["body"], turn < 1.0 ? 1 : 0);  // the bunny at x = 2, or 0
  }
  EXPECT_EQ(free, 1u);
  // A motion from below the row up into the middle bunny.
  const nlohmann::json motion =
      with({"--joint", "turn=1.5707", "--to", "turn=0", "--resolution", "0.05"});
  const MotionResult expected = checker.check_motion(std::vector{1.5707}, std::vector{0.0}, 0.05);
  EXPECT_EQ(motion["query"], "robot-motion");
  EXPECT_FALSE(expected.free);
  EXPECT_EQ(motion["free"], expected.free);
  EXPECT_EQ(motion["states"], expected.states);
  EXPECT_EQ(motion["first_collision"], expected.first_collision);
  EXPECT_EQ(motion["last_free"], expected.last_free);
  EXPECT_EQ(motion["collision"]["body"], 1);
}

TEST(QueryCommand, BadJointValuesExitTwoNamingTheJoint) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const std::string scene = write_row_scene(dir);
  const Swing swing(dir);
  const std::vector<std::string> robot = {"query",          scene,        "--robot", swing.urdf,
                                          "--spheres-from", swing.spheres};
  const auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = robot;
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  expect_bad_input(with({"--joint", "turn=4"}),
                   "--joint: configuration 0, joint 'turn': 4.000000 is outside its limits");
  expect_bad_input(with({"--joint", "turn=nan"}), "--joint: configuration 0, joint 'turn': nan");
  expect_bad_input(with({"--joint", "turn=0", "--to", "turn=-inf"}),
                   "--to: configuration 0, joint 'turn': -inf is not finite");
  expect_bad_input(with({"--joint", "twist=1"}),
                   "--joint: robot 'swing' has no moving joint 'twist' (its moving joints: turn)");
  expect_bad_input(with({"--joint", "turn=1", "--joint", "turn=2"}),
                   "--joint: joint 'turn' is given twice");
  expect_bad_input(with({"--joint", "turn"}), "--joint: expected NAME=VALUE");
  expect_bad_input(with({"--joint", "turn=0", "--to", "turn=1", "--resolution", "0"}),
                   "--resolution: resolution must be positive");
  expect_bad_input(with({"--base", "0", "0", "0", "0", "0", "0", "2"}), "--base: the rotation");
  expect_bad_input({"query", scene, "--robot", swing.urdf}, "give its spheres with --spheres-from");
  expect_bad_input({"query", scene, "--ray", "0", "0", "0", "1", "0", "0", "--joint", "turn=0"},
                   "only with --robot");
}

}  // namespace
}  // namespace sphys
