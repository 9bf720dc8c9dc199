#include <cmath>
#include <numbers>
#include <string>

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

// A cube of side 1 centred at the origin, as an OFF file.
constexpr const char* kCubeOff =
    "OFF\n8 12 0\n"
    "-0.5 -0.5 -0.5\n0.5 -0.5 -0.5\n-0.5 0.5 -0.5\n0.5 0.5 -0.5\n"
    "-0.5 -0.5 0.5\n0.5 -0.5 0.5\n-0.5 0.5 0.5\n0.5 0.5 0.5\n"
    "3 0 4 6\n3 0 6 2\n3 1 3 7\n3 1 7 5\n3 0 1 5\n3 0 5 4\n"
    "3 2 6 7\n3 2 7 3\n3 0 2 3\n3 0 3 1\n3 4 5 7\n3 4 7 6\n";

TEST(TreeCommands, MeasuresAHandMadeTreeAgainstTheAnalyticAnswer) {
  // One sphere of radius r = 0.9 around the unit cube (a = 1/2, corners at 0.866): outside
  // volume (4/3 π r³ - 8a³) / 8a³, worst protrusion (r - a) over the diagonal √3, all covered.
  const test::TempDir dir;
  const std::string mesh = dir.write("cube.off", kCubeOff).string();
  const std::string tree = dir.write("one.sph", "1 2\n0 0 0 0.9 1\n").string();
  const test::CommandResult info = sphys_cli({"tree-info", tree, "--mesh", mesh, "--json"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto level = nlohmann::json::parse(info.out)["levels"][0];
  constexpr double kR = 0.9;
  const double outside = 4.0 / 3.0 * std::numbers::pi * kR * kR * kR - 1.0;
  // Five standard errors of the 400,000 Monte Carlo points in the sphere's box.
  const double box = 8.0 * kR * kR * kR;
  const double p = outside / box;
  EXPECT_NEAR(level["outside_volume"].get<double>(), outside,
              5.0 * box * std::sqrt(p * (1.0 - p) / 400000.0));
  // The 400 points on the sphere miss its point over a face centre by at most r(1 - cos 0.18).
  const double protrusion = (kR - 0.5) / std::sqrt(3.0);
  EXPECT_LE(level["worst_protrusion"].get<double>(), protrusion + 1e-9);
  EXPECT_GE(level["worst_protrusion"].get<double>(), protrusion - 0.01);
  EXPECT_EQ(level["coverage"].get<double>(), 1.0);
}

TEST(TreeCommands, ReadsToolkitFilesWithGapsAndFlatSphereSets) {
  const test::TempDir dir;
  // Unused slots between used children (slots 1 and 3 of the root's four).
  const std::string gaps =
      dir.write("gaps.sph",
                "2 4\n0 0 0 1 1\n0 0 0 -1 1\n0.25 0 0 0.5 1\n0 0 0 -0.000001 1\n-0.25 0 0 0.5 1\n"
                "Options : \n    Algorithm : Merge\nEvaluation : \n")
          .string();
  const test::CommandResult read = sphys_cli({"tree-info", gaps});
  ASSERT_EQ(read.exit_code, 0) << read.err;
  EXPECT_THAT(read.out, HasSubstr("branching 4, 2 levels, 3 spheres"));
  EXPECT_THAT(read.out, HasSubstr("level 1: 2 spheres"));

  // 64 spheres in one level, a 4 x 4 x 4 grid of cells of the unit cube, each in its
  // circumscribed sphere: the whole surface is covered.
  std::string set = "2 64\n0 0 0 0.9\n";
  for (int i = 0; i < 64; ++i) {
    const auto centre = [&](int k) { return std::to_string(-0.375 + 0.25 * ((i >> (2 * k)) & 3)); };
    set += centre(0) + " " + centre(1) + " " + centre(2) + " 0.2166\n";
  }
  const std::string mesh = dir.write("cube.off", kCubeOff).string();
  const test::CommandResult info =
      sphys_cli({"tree-info", dir.write("set.sph", set).string(), "--mesh", mesh, "--json"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto json = nlohmann::json::parse(info.out);
  EXPECT_EQ(json["branching"], 64);
  EXPECT_EQ(json["levels"][1]["spheres"], 64);
  EXPECT_EQ(json["levels"][1]["coverage"].get<double>(), 1.0);
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
