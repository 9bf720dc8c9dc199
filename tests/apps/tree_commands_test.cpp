#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "apps/cli.h"
#include "support/temp_file.h"

namespace sphys {
namespace {

using test::expect_bad_input;
using test::sphys_cli;
using testing::HasSubstr;

TEST(TreeCommands, BuildThenMeasureTheBunny) {
  const test::TempDir dir;
  const std::string tree = (dir.path() / "bunny.sph").string();
  const std::string cache = (dir.path() / "cache").string();
  setenv("SPHYS_CACHE_DIR", cache.c_str(), 1);
  const test::CommandResult built =
      sphys_cli({"build-tree", "bunny", "--method", "octree", "--depth", "3", "-o", tree});
  ASSERT_EQ(built.exit_code, 0) << built.err;
  EXPECT_THAT(built.out, HasSubstr("octree tree, branching 8, 3 levels"));
  EXPECT_THAT(built.out, HasSubstr("built in"));

  const test::CommandResult again =
      sphys_cli({"build-tree", "bunny", "--method", "octree", "--depth", "3", "-o", tree});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_THAT(again.out, HasSubstr("loaded from the cache"));

  const test::CommandResult info = sphys_cli({"tree-info", tree, "--mesh", "bunny", "--json"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto json = nlohmann::json::parse(info.out);
  EXPECT_EQ(json["depth"], 3);
  EXPECT_EQ(json["levels"].size(), 3u);
  EXPECT_EQ(json["levels"][0]["spheres"], 1);
  for (const auto& level : json["levels"]) EXPECT_EQ(level["coverage"].get<double>(), 1.0);
  unsetenv("SPHYS_CACHE_DIR");
}

TEST(TreeCommands, BadInputExitsWithCode2) {
  const test::TempDir dir;
  const std::string out = (dir.path() / "t.sph").string();
  expect_bad_input({"build-tree", "bunny", "--method", "voronoi", "-o", out},
                   "unknown sphere-tree method 'voronoi'");
  expect_bad_input({"build-tree", "bunny", "--branching", "9", "--no-cache", "-o", out},
                   "branching factor 9 is outside 2..8");
  expect_bad_input({"build-tree", "bunny", "--depth", "0", "--no-cache", "-o", out}, "depth 0");
  expect_bad_input({"build-tree", "bunny"}, "--output is required");
  const std::string bad = dir.write("bad.sph", "2 8\n0 0 0 1 1\n0 0 zero 1 1\n").string();
  expect_bad_input({"tree-info", bad}, bad + ":3: z is not a number: 'zero'");
  expect_bad_input({"tree-info", (dir.path() / "none.sph").string()}, "no such file");
  expect_bad_input({"tree-info", bad, "--toolkit-shift"}, "--toolkit-shift needs --mesh");
}

}  // namespace
}  // namespace sphys
