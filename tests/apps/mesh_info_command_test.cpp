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

constexpr const char* kTetObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST(MeshInfoCommand, PrintsTetrahedronMassPropertiesAsJson) {
  const test::TempDir dir;
  const auto path = dir.write("tet.obj", kTetObj);
  const test::CommandResult r = sphys_cli({"mesh-info", path.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  EXPECT_EQ(info["triangles"], 4);
  EXPECT_EQ(info["vertices"], 4);
  EXPECT_EQ(info["watertight"], true);
  EXPECT_EQ(info["mass_method"], "polyhedral");
  // Unit right tetrahedron: V = 1/6, centroid (1/4, 1/4, 1/4).
  EXPECT_NEAR(info["volume"].get<double>(), 1.0 / 6.0, 1e-12);
  EXPECT_NEAR(info["mass"].get<double>(), 1000.0 / 6.0, 1e-9);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(info["center_of_mass"][k].get<double>(), 0.25, 1e-12);
}

TEST(MeshInfoCommand, BunnyTextReport) {
  const test::CommandResult r = sphys_cli({"mesh-info", "bunny"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("mesh              bunny"));
  EXPECT_THAT(r.out, HasSubstr("watertight        yes"));
  EXPECT_THAT(r.out, HasSubstr("principal moments"));
}

TEST(MeshInfoCommand, SizeNormalizesTheModel) {
  const test::CommandResult r = sphys_cli({"mesh-info", "bunny", "--size", "1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  double longest = 0;
  for (int k = 0; k < 3; ++k) {
    longest = std::max(
        longest, info["bounds"]["max"][k].get<double>() - info["bounds"]["min"][k].get<double>());
    EXPECT_NEAR(info["center_of_mass"][k].get<double>(), 0.0, 1e-9);
  }
  EXPECT_NEAR(longest, 1.0, 1e-9);
}

TEST(MeshInfoCommand, BadInputExitsWithCode2) {
  const test::TempDir dir;
  const std::string missing = (dir.path() / "missing.obj").string();
  expect_bad_input({"mesh-info", missing}, "sphys: error: " + missing + ": no such file");
  const std::string empty = dir.write("empty.stl", "").string();
  expect_bad_input({"mesh-info", empty}, empty + ": file is empty");
  const std::string garbage = dir.write("garbage.obj", std::string(500, '\x9c')).string();
  expect_bad_input({"mesh-info", garbage}, garbage + ": no mesh found");
  const std::string nan = dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n").string();
  expect_bad_input({"mesh-info", nan}, nan + ": a vertex has a non-finite coordinate");
  const std::string range =
      dir.write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").string();
  expect_bad_input({"mesh-info", range}, range + ":6: face index 3 is out of range");
  const std::string lines = dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n").string();
  expect_bad_input({"mesh-info", lines}, lines + ": the mesh has no triangles");
}

TEST(MeshInfoCommand, BadParametersExitWithCode2) {
  const test::TempDir dir;
  const std::string tet = dir.write("tet.obj", kTetObj).string();
  expect_bad_input({"mesh-info", tet, "--density", "-5"}, "--density");
  expect_bad_input({"mesh-info", tet, "--density", "nan"}, "density");
  expect_bad_input({"mesh-info", tet, "--size", "abc"}, "--size");
  expect_bad_input({"mesh-info"}, "mesh is required");
  expect_bad_input({"no-such-command"}, "no-such-command");
  expect_bad_input({}, "no command given");
}

TEST(MeshInfoCommand, HelpExitsWithZero) {
  const test::CommandResult r = sphys_cli({"mesh-info", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--triangles"));
}

}  // namespace
}  // namespace sphys
