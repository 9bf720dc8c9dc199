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

}  // namespace
}  // namespace sphys
