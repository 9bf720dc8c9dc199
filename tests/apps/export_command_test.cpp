#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "apps/cli.h"
#include "support/temp_file.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;
using test::sphys_cli;
using testing::HasSubstr;

// A short recording of `stacks:2x3` (depth 2) on the given ground, in `dir`.
fs::path record(const test::TempDir& dir, const std::string& ground, int frames) {
  const fs::path out = dir.path() / ground;
  const test::CommandResult r =
      sphys_cli({"simulate", "stacks:2x3", "--depth", "2", "--ground", ground, "--frames",
                 std::to_string(frames), "--out", out.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return out / "recording.sphysrec";
}

TEST(ExportCommand, TheKhronosValidatorFindsNoErrorOrWarning) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path plane = record(dir, "plane", 90);
  const fs::path octree = record(dir, "octree", 30);
  const std::vector<std::pair<std::vector<std::string>, std::string>> exports = {
      {{plane.string(), "--gltf", (dir.path() / "plane.glb").string()},
       "6 bodies (1 distinct meshes), 91 frames"},
      {{plane.string(), "--gltf", (dir.path() / "thin.glb").string(), "--frames", "10:80",
        "--every", "7"},
       "6 bodies (1 distinct meshes), 11 frames"},
      {{octree.string(), "--gltf", (dir.path() / "octree.glb").string(), "--frames", ":0"},
       "6 bodies (1 distinct meshes), 1 frames"},
  };
  std::vector<std::string> files;
  for (const auto& [args, summary] : exports) {
    std::vector<std::string> command = {"export"};
    command.insert(command.end(), args.begin(), args.end());
    const test::CommandResult r = sphys_cli(command);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr(summary));
    files.push_back(args[2]);
  }
  // The validator (npm gltf-validator, installed by scripts/setup) in Node.js.
  std::vector<std::string> args = {SPHYS_GLTF_VALIDATE_JS};
  args.insert(args.end(), files.begin(), files.end());
  const test::CommandResult validated = test::run_command("node", args);
  EXPECT_EQ(validated.exit_code, 0) << validated.out << validated.err;
  EXPECT_THAT(validated.out, HasSubstr("plane.glb: 0 errors, 0 warnings"));
  EXPECT_THAT(validated.out, HasSubstr("thin.glb: 0 errors, 0 warnings"));
  EXPECT_THAT(validated.out, HasSubstr("octree.glb: 0 errors, 0 warnings"));
}

TEST(ExportCommand, BadInputExitsWithCode2) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path recording = record(dir, "plane", 5);
  const std::string out = (dir.path() / "out.glb").string();
  test::expect_bad_input({"export", (dir.path() / "absent.sphysrec").string(), "--gltf", out},
                         "absent.sphysrec");
  const fs::path garbage = dir.write("garbage.sphysrec", "not a recording");
  test::expect_bad_input({"export", garbage.string(), "--gltf", out}, "garbage.sphysrec");
  test::expect_bad_input({"export", recording.string(), "--gltf", out, "--frames", "3-4"},
                         "--frames: expected FIRST:LAST with frame numbers from 0, got '3-4'");
  test::expect_bad_input({"export", recording.string(), "--gltf", out, "--frames", "a:4"},
                         "--frames: expected FIRST:LAST");
  test::expect_bad_input({"export", recording.string(), "--gltf", out, "--frames", "2:9"},
                         "frames 2 to 9 are not in the recording, which has frames 0 to 5");
  test::expect_bad_input({"export", recording.string(), "--gltf", out, "--every", "0"},
                         "--every must be at least 1");
  test::expect_bad_input(
      {"export", recording.string(), "--gltf", (dir.path() / "no" / "such" / "x.glb").string()},
      "x.glb");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace sphys
