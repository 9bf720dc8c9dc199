#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "apps/cli.h"
#include "sphys/tools/recording.h"
#include "support/temp_file.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;
using test::expect_bad_input;
using test::sphys_cli;
using testing::HasSubstr;
using testing::StartsWith;

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, separator);) fields.push_back(field);
  return fields;
}

std::vector<std::string> read_lines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A scene file's text: the header, then `members` (JSON object members, comma-separated).
std::string scene_text(const std::string& members) {
  return R"({"format": "sphys-scene", "version": 1, )" + members + "}";
}

// One bunny with a quick tree, for scenes where the tree does not matter.
constexpr const char* kQuickBody =
    R"({"position": [0, 1, 0], "sphere_tree": {"method": "octree", "depth": 1}})";

TEST(SimulateCommand, PresetRunWritesFramesAndRecording) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "run";
  const test::CommandResult r =
      sphys_cli({"simulate", "stacks:1x2", "--depth", "2", "--frames", "5", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("stacks:1x2 (2 bodies)"));
  EXPECT_THAT(r.out, HasSubstr("combined, branching 8, depth 2"));
  EXPECT_THAT(r.out, HasSubstr("frames              5 "));
  EXPECT_THAT(r.out, HasSubstr((out / "frames.csv").string()));

  // frames.csv: a header, then frames 1..5 at t = frame / 60.
  const std::vector<std::string> lines = read_lines(out / "frames.csv");
  ASSERT_EQ(lines.size(), 6u);
  const std::vector<std::string> header = split(lines[0], ',');
  EXPECT_THAT(lines[0], StartsWith("frame,time_s,step_ms,"));
  const auto contacts_column = std::find(header.begin(), header.end(), "contacts") - header.begin();
  ASSERT_LT(contacts_column, static_cast<std::ptrdiff_t>(header.size()));
  for (int frame = 1; frame <= 5; ++frame) {
    const std::vector<std::string> row = split(lines[static_cast<std::size_t>(frame)], ',');
    ASSERT_EQ(row.size(), header.size()) << lines[static_cast<std::size_t>(frame)];
    EXPECT_EQ(std::stoi(row[0]), frame);
    EXPECT_NEAR(std::stod(row[1]), frame / 60.0, 1e-12);
    EXPECT_GE(std::stod(row[2]), 0.0);
    EXPECT_GE(std::stod(row[static_cast<std::size_t>(contacts_column)]), 0.0);
  }

  // recording.sphysrec: the initial poses, then one frame per step; the scene rides along.
  const tools::Recording recording = tools::read_recording(out / "recording.sphysrec");
  EXPECT_EQ(recording.frame_count, 6u);
  EXPECT_EQ(recording.body_count, 2u);
  EXPECT_DOUBLE_EQ(recording.time_step, 1.0 / 60.0);
  const auto first = recording.frame(0);
  EXPECT_EQ(first[0].position, Vec3(0.0f, 1.0f, 0.0f));
  EXPECT_FLOAT_EQ(first[1].position.y(), 2.2f);
  // The first bunny's yaw: cos and sin of π·u for the first SplitMix64(2008) draw.
  EXPECT_FLOAT_EQ(first[0].orientation.w(), 0.7238755822181702f);
  EXPECT_FLOAT_EQ(first[0].orientation.y(), 0.6899305582046509f);
  // Five steps of gravity bring the bunnies down.
  for (int b = 0; b < 2; ++b) {
    EXPECT_LT(recording.frame(5)[static_cast<std::uint32_t>(b)].position.y(),
              first[static_cast<std::uint32_t>(b)].position.y());
  }
  const auto scene = nlohmann::json::parse(recording.metadata);
  EXPECT_EQ(scene["format"], "sphys-scene");
  EXPECT_EQ(scene["frames"], 5);
  EXPECT_EQ(scene["bodies"].size(), 2u);
}

TEST(SimulateCommand, FreeFallFollowsSemiImplicitEuler) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path scene =
      dir.write("fall.json", scene_text(R"("gravity": [0, -6, 0], "time_step": 0.1, "frames": 4,
                                "ground": {"type": "none"}, "bodies": [)" +
                                        std::string(kQuickBody) + "]"));
  const fs::path out = dir.path() / "out";
  const test::CommandResult r = sphys_cli({"simulate", scene.string(), "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tools::Recording recording = tools::read_recording(out / "recording.sphysrec");
  ASSERT_EQ(recording.frame_count, 5u);
  EXPECT_DOUBLE_EQ(recording.time_step, 0.1);
  // v_n = −g·n·dt, then y_n = y_{n−1} + v_n·dt: y_n = 1 − g·dt²·n(n+1)/2 = 1 − 0.03·n(n+1).
  for (std::uint32_t n = 0; n <= 4; ++n) {
    EXPECT_NEAR(recording.frame(n)[0].position.y(), 1.0 - 0.03 * n * (n + 1), 1e-5) << n;
  }
  EXPECT_EQ(read_lines(out / "frames.csv").size(), 5u);
}

TEST(SimulateCommand, JsonSummaryParses) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "run";
  const test::CommandResult r = sphys_cli(
      {"simulate", "stacks:1x2", "--depth", "2", "--frames", "5", "--out", out.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["scene"], "stacks:1x2");
  EXPECT_EQ(json["frames"], 5);
  EXPECT_EQ(json["bodies"], 2);
  EXPECT_EQ(json["response"], "paper");
  EXPECT_EQ(json["time_step_s"].get<double>(), 1.0 / 60.0);
  EXPECT_GE(json["contacts_per_frame"]["mean"].get<double>(), 0.0);
  EXPECT_GE(json["contacts_per_frame"]["max"].get<double>(),
            json["contacts_per_frame"]["mean"].get<double>());
  EXPECT_GT(json["steps_per_s"].get<double>(), 0.0);
  EXPECT_GE(json["step_ms"]["mean"].get<double>(), 0.0);
  EXPECT_GE(json["deepest_penetration_m"].get<double>(), 0.0);
  EXPECT_EQ(json["bodies_below_ground"], 0);
  EXPECT_EQ(json["csv"], (out / "frames.csv").string());
  EXPECT_EQ(json["recording"], (out / "recording.sphysrec").string());
  double shares = 0.0;
  for (const auto& [phase, share] : json["time_share_percent"].items()) {
    EXPECT_GE(share.get<double>(), 0.0) << phase;
    shares += share.get<double>();
  }
  EXPECT_LE(shares, 100.0 + 1e-9);
}

TEST(SimulateCommand, BadSceneFilesExitWithCode2AndTheJsonPath) {
  const test::TempDir dir;
  const auto write = [&dir](const std::string& name, const std::string& members) {
    return dir.write(name, scene_text(members)).string();
  };
  const std::string misspelt =
      write("misspelt.json", R"("bodies": [{"position": [0, 1, 0], "densty": 5}])");
  expect_bad_input({"simulate", misspelt, "--no-cache"},
                   misspelt + ": /bodies/0/densty: unknown key");
  const std::string negative =
      write("negative.json", R"("bodies": [{"position": [0, 1, 0]}, {"density": -2}])");
  expect_bad_input({"simulate", negative, "--no-cache"},
                   negative + ": /bodies/1/density: must be positive");
  const std::string still = write("still.json", R"("time_step": 0, "bodies": [])");
  expect_bad_input({"simulate", still, "--no-cache"}, still + ": /time_step: must be positive");
  const std::string gone = write("gone.json", R"("bodies": [{"mesh": "meshes/gone.obj"}])");
  expect_bad_input(
      {"simulate", gone, "--no-cache"},
      gone + ": /bodies/0/mesh: no such file: " + (dir.path() / "meshes" / "gone.obj").string());
  expect_bad_input({"simulate", (dir.path() / "absent.json").string(), "--no-cache"},
                   "absent.json: no such file");
}

TEST(SimulateCommand, BadOptionsExitWithCode2) {
  const test::TempDir dir;
  const std::string out = (dir.path() / "out").string();
  expect_bad_input({"simulate", "stacks:4", "--out", out}, "unknown preset 'stacks:4'");
  expect_bad_input({"simulate", "stacks:0x5", "--out", out}, "unknown preset 'stacks:0x5'");
  expect_bad_input({"simulate", "stacks:1x1", "--frames", "0", "--out", out},
                   "--frames must be at least 1");
  expect_bad_input({"simulate", "stacks:1x1", "--frames", "-3", "--out", out},
                   "--frames must be at least 1");
  expect_bad_input({"simulate", "stacks:1x1", "--depth", "7", "--no-cache", "--out", out},
                   "depth must be 1 to 6, got 7");
  expect_bad_input({"simulate", "stacks:1x1", "--mode", "bogus", "--no-cache", "--out", out},
                   "unknown response mode 'bogus'");
  // Nothing was simulated, so nothing was written.
  EXPECT_FALSE(fs::exists(fs::path(out) / "frames.csv"));
}

// Runs a scene under gravity near the top of the single-precision range (-1e38 m/s²) with one
// bunny at `position`, and returns the result; the frames go to `out`.
test::CommandResult run_blowing_up(const test::TempDir& dir, const std::string& position,
                                   const fs::path& out) {
  const fs::path scene =
      dir.write("blowup.json",
                scene_text(R"("gravity": [0, -1e38, 0], "frames": 400, "ground": {"depth": 2},
                    "bodies": [{"position": )" +
                           position + R"(, "sphere_tree": {"method": "octree", "depth": 1}}])"));
  return sphys_cli({"simulate", scene.string(), "--out", out.string()});
}

TEST(SimulateCommand, ASceneThatBlowsUpNamesTheBodyAndTheFrame) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "out";
  // Beside the ground, so nothing but gravity acts: the speed and the height overflow to
  // infinity at frame 157. The octree ground is the world's body 0, so the scene's
  // body 0 is the world's body 1 and the message has to map the index back.
  const test::CommandResult r = run_blowing_up(dir, "[50, 1, 0]", out);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("non-finite: body 0 (/bodies/0) at frame "));

  // The frames before the failure are kept: the CSV has one row per completed frame and the
  // recording holds the initial poses and each of them.
  const std::string marker = "at frame ";
  const std::size_t at = r.err.find(marker);
  ASSERT_NE(at, std::string::npos) << r.err;
  const int failed = std::stoi(r.err.substr(at + marker.size()));
  // y_n = 1 − 1e38·n(n+1)/(2·60²) passes −3.4e38, the largest float, between n = 156 and 157;
  // the speed 1e38·n/60 would only at n = 205.
  EXPECT_GE(failed, 156);
  EXPECT_LE(failed, 157);
  EXPECT_EQ(read_lines(out / "frames.csv").size(), static_cast<std::size_t>(failed));
  const tools::Recording recording = tools::read_recording(out / "recording.sphysrec");
  EXPECT_EQ(recording.frame_count, static_cast<std::uint32_t>(failed));
}

TEST(SimulateCommand, AnImpactTooViolentForSinglePrecisionIsReportedAsNonFinite) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  // Onto the ground at 1.7e36 m/s in the first step: the impulse spins the bunny so fast that its
  // orientation cannot be renormalised in single precision. The run must stop as a simulation
  // that went non-finite, naming the body, not fail later while writing the recording.
  const test::CommandResult r = run_blowing_up(dir, "[0, 1, 0]", dir.path() / "out");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("non-finite: body 0 (/bodies/0) at frame "));
}

}  // namespace
}  // namespace sphys
