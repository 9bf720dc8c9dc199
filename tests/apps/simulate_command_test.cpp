#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "apps/cli.h"
#include "sphys/settings_table.h"
#include "sphys/solver_settings.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/setting_text.h"
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

using test::read_lines;

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
  // The plausibility figures of each frame close the line.
  EXPECT_THAT(lines[0],
              testing::EndsWith(
                  ",deepest_penetration_m,mean_penetration_m,bodies_at_rest,"
                  "bodies_asleep,jitter_m_per_s,warm_started,islands,collision_passes,serial_ms,"
                  "broad_phase_serial_ms,narrow_phase_serial_ms,contacts_serial_ms,"
                  "response_serial_ms,integration_serial_ms,sleep_serial_ms"));
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
                                "max_collision_passes": 1, "solver": {"soft_substeps": 4},
                                "ground": {"type": "none"}, "bodies": [)" +
                                        std::string(kQuickBody) + "]"));
  const fs::path out = dir.path() / "out";
  const test::CommandResult r = sphys_cli({"simulate", scene.string(), "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tools::Recording recording = tools::read_recording(out / "recording.sphysrec");
  ASSERT_EQ(recording.frame_count, 5u);
  EXPECT_DOUBLE_EQ(recording.time_step, 0.1);
  // The soft step integrates in 4 substeps of h = dt/4 per frame: v_k = −g·k·h, then
  // y_k = y_{k−1} + v_k·h, so y_k = 1 − g·h²·k(k+1)/2, and frame n is substep k = 4n:
  // y = 1 − 6 · 0.025² · 4n(4n+1) / 2 = 1 − 0.0075·n(4n+1).
  for (std::uint32_t n = 0; n <= 4; ++n) {
    EXPECT_NEAR(recording.frame(n)[0].position.y(), 1.0 - 0.0075 * n * (4 * n + 1), 1e-5) << n;
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
  // The runtime's defaults: a preset does not choose.
  EXPECT_EQ(json["response"], "plausible");
  EXPECT_EQ(json["contact_set"], "reduced");
  // The lanes auto resolved to: never "auto" itself.
  EXPECT_TRUE(json["solver_lanes"] == "avx2" || json["solver_lanes"] == "sse2" ||
              json["solver_lanes"] == "portable")
      << json["solver_lanes"];
  EXPECT_EQ(json["collision_passes"], 1);
  EXPECT_EQ(json["time_step_s"].get<double>(), 1.0 / 60.0);
  EXPECT_GE(json["contacts_per_frame"]["mean"].get<double>(), 0.0);
  EXPECT_GE(json["contacts_per_frame"]["max"].get<double>(),
            json["contacts_per_frame"]["mean"].get<double>());
  EXPECT_GT(json["steps_per_s"].get<double>(), 0.0);
  EXPECT_GE(json["step_ms"]["mean"].get<double>(), 0.0);
  EXPECT_GE(json["deepest_penetration_m"].get<double>(), 0.0);
  EXPECT_GE(json["mean_penetration_m"].get<double>(), 0.0);
  EXPECT_LE(json["mean_penetration_m"].get<double>(), json["deepest_penetration_m"].get<double>());
  // Two 1 m bunnies: penetrations are also given per cent of 1 m.
  EXPECT_DOUBLE_EQ(json["largest_body_size_m"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(json["deepest_penetration_percent_of_size"].get<double>(),
                   100.0 * json["deepest_penetration_m"].get<double>());
  EXPECT_EQ(json["movable_bodies"], 2);
  EXPECT_LE(json["bodies_at_rest"].get<int>(), 2);
  EXPECT_LE(json["bodies_asleep"].get<int>(), json["bodies_at_rest"].get<int>());
  // Five frames of falling: nothing rests yet.
  EXPECT_TRUE(json["all_at_rest_from_frame"].is_null());
  EXPECT_TRUE(json["all_at_rest_from_s"].is_null());
  EXPECT_GT(json["final_kinetic_energy_J"].get<double>(), 0.0);
  EXPECT_GE(json["jitter_m_per_s"].get<double>(), 0.0);
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

// A scene file's joints reach the world: a 10 cm bunny hinged 1 m below a pivot on the world,
// let go 30° from the vertical, swings through the vertical to the other side within the first
// second (a simple pendulum's half period is π √(1/9.81) = 1.003 s) on its 1 m rod.
TEST(SimulateCommand, APendulumFromASceneFileSwings) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const Vec3 pivot(0.0f, 2.0f, 0.0f);
  const fs::path scene = dir.write("pendulum.json", scene_text(R"("frames": 60,
      "ground": {"type": "none"}, "sleep": {"enabled": false},
      "bodies": [{"size": 0.1, "position": [0.5, 1.1339746, 0],
                  "sphere_tree": {"method": "octree", "depth": 1}}],
      "joints": [{"type": "hinge", "body_a": null, "body_b": 0, "anchor_a": [0, 2, 0],
                  "anchor_b": [-0.5, 0.8660254, 0], "axis_a": [0, 0, 1], "axis_b": [0, 0, 1]}])"));
  const fs::path out = dir.path() / "out";
  const test::CommandResult r = sphys_cli({"simulate", scene.string(), "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tools::Recording recording = tools::read_recording(out / "recording.sphysrec");
  ASSERT_EQ(recording.frame_count, 61u);
  float lowest_x = 1.0f;
  float worst_rod = 0.0f;
  for (std::uint32_t n = 0; n < recording.frame_count; ++n) {
    const Vec3 bob = recording.frame(n)[0].position;
    lowest_x = std::min(lowest_x, bob.x());
    worst_rod = std::max(worst_rod, std::abs((bob - pivot).norm() - 1.0f));
  }
  std::cout << "scene-file pendulum: lowest x " << lowest_x << " m, rod length off by at most "
            << worst_rod << " m\n";
  EXPECT_FLOAT_EQ(recording.frame(0)[0].position.x(), 0.5f);
  // The recording keeps the joint, for the viewer to draw.
  const std::vector<tools::RecordedJoint> joints = {
      {JointType::kHinge, std::nullopt, 0, pivot, Vec3(-0.5f, 0.8660254f, 0.0f)}};
  EXPECT_EQ(recording.joints, joints);
  EXPECT_LT(lowest_x, -0.4f);  // swung to the other side, near its start's mirror at -0.5
  EXPECT_LT(worst_rod, 0.01f);
}

TEST(SimulateCommand, BadJointsExitWithCode2AndTheJsonPath) {
  const test::TempDir dir;
  const std::string missing = dir.write("missing.json", scene_text(R"("bodies": [{}],
      "joints": [{"type": "ball", "body_a": 0, "body_b": 7}])"))
                                  .string();
  expect_bad_input({"simulate", missing, "--no-cache"},
                   missing + ": /joints/0/body_b: no body 7; /bodies has 1");
  const std::string paper = dir.write("paper.json", scene_text(R"("response": "paper",
      "ground": {"type": "none"},
      "bodies": [{"sphere_tree": {"method": "octree", "depth": 1}}],
      "joints": [{"type": "ball", "body_a": 0, "body_b": null}])"))
                                .string();
  expect_bad_input({"simulate", paper, "--no-cache"},
                   "/joints/0: add_joint (ball): joints are solved in plausible mode only");
}

// The options that set the world's settings say what the settings table says of them.
TEST(SimulateCommand, HelpTakesTheSettingsFromTheTable) {
  const test::CommandResult r = test::sphys_cli({"simulate", "--help"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const char* field :
       {"response", "solver.contacts", "collision_passes", "paper_passes", "threads"}) {
    EXPECT_THAT(r.out, HasSubstr(option_help(setting_of(field)))) << field;
  }
  EXPECT_THAT(r.out, HasSubstr("Valid: 1 to 64; unit: collision passes."));
}

TEST(SimulateCommand, BadOptionsExitWithCode2) {
  const test::TempDir dir;
  const std::string out = (dir.path() / "out").string();
  expect_bad_input({"simulate", "stacks:4", "--out", out}, "unknown preset 'stacks:4'");
  expect_bad_input({"simulate", "stacks:0x5", "--out", out}, "unknown preset 'stacks:0x5'");
  // An option and its bad value on stacks:1x1, and what the message says.
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--frames", "0"}, "--frames must be at least 1"},
      {{"--frames", "-3"}, "--frames must be at least 1"},
      {{"--depth", "7"}, "depth must be 1 to 6, got 7"},
      {{"--mode", "bogus"},
       "--mode: unknown response mode 'bogus'; response modes: paper, plausible"},
      {{"--contacts", "some"},
       "--contacts: unknown contact set 'some'; contact sets: all, reduced"},
      {{"--collision-passes", "0"}, "--collision-passes must be between 1 and 64, got 0"},
      {{"--collision-passes", "65"}, "--collision-passes must be between 1 and 64, got 65"},
      {{"--collision-passes", "two"}, "--collision-passes"},
      {{"--substeps", "2"}, "--substeps was renamed --collision-passes"},
      {{"--set", "substep_travel=0.2"},
       "--set substep_travel was removed: renamed collision_pass_travel"},
      {{"--passes", "0"}, "--passes must be between 1 and 1000, got 0"},
      {{"--passes", "1001"}, "--passes must be between 1 and 1000, got 1001"},
      {{"--ground", "box"}, "--ground must be octree or plane, got 'box'"},
      {{"--set", "solver.soft_substeps"}, "--set takes FIELD=VALUE, got 'solver.soft_substeps'"},
      {{"--set", "solver.nope=1"}, "--set: no setting solver.nope"},
      {{"--set", "solver.method=soft_step"},
       "--set solver.method was removed: the soft step is the only solver; delete the setting"},
      {{"--set", "solver.velocity_iterations=20"},
       "--set solver.velocity_iterations was removed: the soft step solves and relaxes each "
       "contact once per substep; set solver.soft_substeps"},
      {{"--set", "sleep.enabled=yes"}, "--set sleep.enabled: must be true or false"},
      {{"--set", "solver.soft_substeps=2.5"},
       "--set solver.soft_substeps: must be a whole number from 0, got '2.5'"},
      {{"--set", "solver.contact_hertz=fast"},
       "--set solver.contact_hertz: must be a finite number, got 'fast'"},
      {{"--set", "gravity=1"}, "--set gravity: a vector is set in a scene file"},
      {{"--set", "solver.soft_substeps=0"},
       "solver.soft_substeps must be between 1 and 64, got 0 substeps"},
  };
  for (const auto& [option, message] : cases) {
    std::vector<std::string> args = {"simulate", "stacks:1x1", "--no-cache", "--out", out};
    args.insert(args.end(), option.begin(), option.end());
    expect_bad_input(args, message);
  }
  // Nothing was simulated, so nothing was written.
  EXPECT_FALSE(fs::exists(fs::path(out) / "frames.csv"));
}

TEST(SimulateCommand, GravityThatWouldBlowTheSceneUpIsRefusedBeforeItRuns) {
  // -1e38 m/s² is finite, but a bunny under it would overflow single precision within three
  // seconds; the scene is refused at its JSON path, and nothing is written.
  const test::TempDir dir;
  const fs::path out = dir.path() / "out";
  const fs::path scene =
      dir.write("blowup.json",
                scene_text(R"("gravity": [0, -1e38, 0], "bodies": [{"position": [0, 1, 0]}])"));
  expect_bad_input({"simulate", scene.string(), "--no-cache", "--out", out.string()},
                   scene.string() + ": /gravity/1: must be between -1000 and 1000, got -1e+38");
  EXPECT_FALSE(fs::exists(out));
}

// One bunny with the default tree dropped from 1 m onto the exact plane, run for 5 s in `mode`;
// the summary as JSON.
nlohmann::json dropped_bunny(const test::TempDir& dir, const std::string& mode) {
  const fs::path scene =
      dir.write("drop.json", scene_text(R"("frames": 300, "ground": {"type": "plane"},
                                 "bodies": [{"position": [0, 1, 0]}])"));
  const test::CommandResult r = sphys_cli({"simulate", scene.string(), "--mode", mode, "--out",
                                           (dir.path() / mode).string(), "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(SimulateCommand, TheLowestCentreIsGivenAtTheEndAndOverTheRun) {
  // A bunny thrown up at 5 m/s from y = 0 with nothing below, for half a second, by semi-implicit
  // Euler in the soft step's 6 substeps of h = dt / 6 a frame: after k substeps
  // y = 5 k h - g h^2 (1 + ... + k). It is lowest after the first frame, y1 = 5 dt - 21 g h^2 =
  // 0.0817 m, and at the end y = 2.5 - 16290 g h^2 = 1.2669 m, still rising.
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path scene =
      dir.write("throw.json", scene_text(R"("frames": 30, "ground": {"type": "none"},
                                 "bodies": [{"position": [0, 0, 0], "linear_velocity": [0, 5, 0]}])"));
  const test::CommandResult r =
      sphys_cli({"simulate", scene.string(), "--out", (dir.path() / "out").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  constexpr double g = 9.81, dt = 1.0 / 60.0, h = dt / 6.0;
  EXPECT_NEAR(json["lowest_center_y_run_m"].get<double>(), 5.0 * dt - g * h * h * 21, 1e-5);
  EXPECT_NEAR(json["lowest_center_y_end_m"].get<double>(), 30 * dt * 5.0 - g * h * h * 16290, 1e-4);
  EXPECT_EQ(json["movable_bodies"], 1);
  EXPECT_EQ(json["bodies_still_moving"], 1);
  EXPECT_EQ(json["bodies_at_rest"], 0);
  EXPECT_EQ(json["bodies_below_ground"], 0);
  // The text says the same.
  const test::CommandResult text =
      sphys_cli({"simulate", scene.string(), "--out", (dir.path() / "text").string()});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("0 of 1 movable bodies at the end (0 asleep, 1 still moving)"));
  EXPECT_THAT(text.out, HasSubstr("m at the end, 0.08174 m over the run)"));
}

TEST(SimulateCommand, PlausibleModeBringsADroppedBunnyToRestOnThePlane) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const nlohmann::json plausible = dropped_bunny(dir, "plausible");
  EXPECT_EQ(plausible["response"], "plausible");
  // It lands within half a second and settles soon after (seen: at rest and asleep from frame
  // 84 of 300), then stays at rest to the end.
  EXPECT_EQ(plausible["movable_bodies"], 1);
  EXPECT_EQ(plausible["bodies_at_rest"], 1);
  EXPECT_EQ(plausible["bodies_asleep"], 1);
  ASSERT_FALSE(plausible["all_at_rest_from_frame"].is_null());
  EXPECT_LT(plausible["all_at_rest_from_frame"].get<int>(), 180);
  EXPECT_DOUBLE_EQ(plausible["all_at_rest_from_s"].get<double>(),
                   plausible["all_at_rest_from_frame"].get<int>() / 60.0);
  EXPECT_LT(plausible["final_kinetic_energy_J"].get<double>(), 1e-3);
  EXPECT_LT(plausible["jitter_m_per_s"].get<double>(), 0.01);
  // It never sinks by 1% of its 1 m (seen: 0.26% at most, 0.06% on average).
  EXPECT_GT(plausible["deepest_penetration_m"].get<double>(), 0.0);
  EXPECT_LT(plausible["deepest_penetration_percent_of_size"].get<double>(), 1.0);
  EXPECT_LT(plausible["mean_penetration_percent_of_size"].get<double>(),
            plausible["deepest_penetration_percent_of_size"].get<double>());
  EXPECT_EQ(plausible["bodies_still_moving"], 0);
  EXPECT_GT(plausible["lowest_center_y_end_m"].get<double>(), 0.0);
  EXPECT_GT(plausible["lowest_center_y_run_m"].get<double>(), 0.0);
  EXPECT_LE(plausible["lowest_center_y_run_m"].get<double>(),
            plausible["lowest_center_y_end_m"].get<double>());
  // Asleep on the plane, it rests on it within the slop: the overlap counted afresh at the end
  // sees what the world no longer tests.
  EXPECT_GE(plausible["end_overlap_m"].get<double>(), 0.0);
  EXPECT_LT(plausible["end_overlap_m"].get<double>(), 0.01);
  EXPECT_DOUBLE_EQ(plausible["end_overlap_percent_of_size"].get<double>(),
                   100.0 * plausible["end_overlap_m"].get<double>());

  // The paper's response lets the same bunny sink deeper (seen: 2.2% of its size) and never
  // quite stops it.
  const nlohmann::json paper = dropped_bunny(dir, "paper");
  EXPECT_EQ(paper["response"], "paper");
  EXPECT_GT(paper["deepest_penetration_m"].get<double>(),
            plausible["deepest_penetration_m"].get<double>());
}

TEST(SimulateCommand, OptionsOverrideTheScenesWorldSettings) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path scene = dir.write(
      "fall.json", scene_text(R"("frames": 2, "response": "plausible", "ground": {"type": "none"},
                                 "bodies": [)" +
                              std::string(kQuickBody) + "]"));
  const fs::path out = dir.path() / "out";
  const test::CommandResult r =
      sphys_cli({"simulate", scene.string(), "--mode", "paper", "--contacts", "all",
                 "--collision-passes", "3", "--ground", "plane", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("response            paper, 3 collision passes per frame\n"));
  EXPECT_THAT(r.out, HasSubstr("\nmean penetration    0 m (0%; over the 0 frames with overlaps)"));
  EXPECT_THAT(r.out, HasSubstr("\nat rest             0 of 1 movable bodies at the end (0 asleep, "
                               "1 still moving); never all at rest\n"));
  // The recording keeps the scene as run.
  const auto recorded =
      nlohmann::json::parse(tools::read_recording(out / "recording.sphysrec").metadata);
  EXPECT_EQ(recorded["response"], "paper");
  EXPECT_EQ(recorded["contacts"], "all");
  EXPECT_EQ(recorded["collision_passes"], 3);
  EXPECT_EQ(recorded["ground"]["type"], "plane");

  const test::CommandResult set =
      sphys_cli({"simulate", scene.string(), "--set", "solver.contact_hertz=20", "--set",
                 "solver.soft_substeps=2", "--set", "sleep.enabled=false", "--out", out.string()});
  ASSERT_EQ(set.exit_code, 0) << set.err;
  const auto set_scene =
      nlohmann::json::parse(tools::read_recording(out / "recording.sphysrec").metadata);
  EXPECT_EQ(set_scene["solver"]["contact_hertz"], 20);
  EXPECT_EQ(set_scene["solver"]["soft_substeps"], 2);
  EXPECT_EQ(set_scene["sleep"]["enabled"], false);

  const test::CommandResult plausible =
      sphys_cli({"simulate", scene.string(), "--contacts", "all", "--out", out.string()});
  ASSERT_EQ(plausible.exit_code, 0) << plausible.err;
  const std::string lanes(solver_lanes_name(resolve_solver_lanes(SolverLanes::kAuto)));
  EXPECT_THAT(
      plausible.out,
      HasSubstr("response            plausible, all contacts, " + lanes +
                " lanes, 1 to 8 collision passes per frame (1.00 on average, 1 at most)\n"));
}

}  // namespace
}  // namespace sphys
