// Bad input and interruption as the command line meets them: one line naming the file or option
// and the problem with exit code 2, never a crash or a hang; Ctrl-C and SIGTERM end a long run at
// its next frame with no temporary file left behind.

#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "apps/cli.h"
#include "sphys/tools/recording.h"
#include "support/temp_file.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;
using test::expect_refused;
using test::sphys_cli;

// One bunny; with a one-level tree over the exact plane, the quickest scene to prepare.
constexpr const char* kQuickScene = "stacks:1x1";

TEST(ReliabilityCommand, CommandLineParseErrorsSayWhoSpeaks) {
  expect_refused({"simulate"}, "sphys: error: scene is required\n");
  expect_refused({"mesh-info", "bunny", "--density"},
                 "sphys: error: --density: 1 required FLOAT:POSITIVE missing\n");
  expect_refused({"simulate", "stacks:1x1", "--threads", "-3"},
                 "sphys: error: --threads: Value -3 not in range 0 to 1024\n");
  expect_refused({"frobnicate"},
                 "sphys: error: The following argument was not expected: "
                 "frobnicate\n");
  // --help and --version still succeed.
  EXPECT_EQ(sphys_cli({"--version"}).exit_code, 0);
  EXPECT_EQ(sphys_cli({"simulate", "--help"}).exit_code, 0);
}

TEST(ReliabilityCommand, EmptyFileNamesAreRefusedByTheOption) {
  expect_refused({"build-tree", "bunny", "-o", ""},
                 "sphys: error: --output: expected a file name, got \"\"\n");
  expect_refused({"simulate", "stacks:1x1", "--out", ""},
                 "sphys: error: --out: expected a file name, got \"\"\n");
  expect_refused({"mesh-info", ""}, "sphys: error: mesh: expected a file name, got \"\"\n");
  expect_refused({"export", "run.sphysrec", "--gltf", ""},
                 "sphys: error: --gltf: expected a file name, got \"\"\n");
}

TEST(ReliabilityCommand, NamedPipesAreRefusedAtOnce) {
  const test::TempDir dir;
  for (const std::string name : {"pipe.obj", "pipe.ply", "pipe.json", "pipe.sph"}) {
    ASSERT_EQ(mkfifo((dir.path() / name).c_str(), 0600), 0);
  }
  const std::string fifo = ": is a named pipe (FIFO), not a regular file\n";
  const fs::path obj = dir.path() / "pipe.obj";
  expect_refused({"mesh-info", obj.string()}, "sphys: error: " + obj.string() + fifo);
  const fs::path ply = dir.path() / "pipe.ply";
  expect_refused({"build-tree", ply.string(), "-o", (dir.path() / "t.sph").string()},
                 "sphys: error: " + ply.string() + fifo);
  const fs::path json = dir.path() / "pipe.json";
  expect_refused({"simulate", json.string()}, "sphys: error: " + json.string() + fifo);
  const fs::path sph = dir.path() / "pipe.sph";
  expect_refused({"tree-info", sph.string()}, "sphys: error: " + sph.string() + fifo);
  expect_refused({"tree-info", "/dev/zero"},
                 "sphys: error: /dev/zero: is a device, not a regular file\n");
}

// 10^5 unclosed '[' (100 kB) took 30 s and 9.8 GB before the nesting bound.
TEST(ReliabilityCommand, DeeplyNestedSceneIsRefusedAtOnce) {
  const test::TempDir dir;
  const std::string scene = dir.write("deep.json", std::string(100'000, '[')).string();
  expect_refused({"simulate", scene},
                 "sphys: error: " + scene +
                     ": /0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0: arrays and objects nested more than 16 "
                     "deep\n");
}

// 10^7 bodies of 3 bytes each (30 MB) took 4.2 GB and minutes, and 56 s and 5.9 GB before that,
// on their way to bad_alloc; the millionth-and-first is refused as it is read.
TEST(ReliabilityCommand, MillionsOfBodiesAreRefusedAtOnce) {
  const test::TempDir dir;
  std::string text = R"({"format": "sphys-scene", "version": 1, "bodies": [{})";
  for (int i = 1; i < 10'000'000; ++i) text += ",{}";
  const std::string scene = dir.write("crowd.json", text + "]}").string();
  expect_refused({"simulate", scene}, "sphys: error: " + scene +
                                          ": /bodies: more than 1000000 bodies; a scene holds at "
                                          "most that many\n");
}

TEST(ReliabilityCommand, ReplayFramesPastTheRecordingAreRefused) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const test::CommandResult r = sphys_cli({"simulate", kQuickScene, "--depth", "1", "--ground",
                                           "plane", "--frames", "5", "--out", dir.path().string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string recording = (dir.path() / "recording.sphysrec").string();
  // Refused before a window opens, as sphys export refuses it.
  expect_refused(
      {"view", "--replay", recording, "--frames", "999999"},
      "sphys: error: " + recording + ": --frames 999999 is past the recording's last frame, 5\n");
}

// Runs a long simulation into a folder that holds an earlier run's outputs, sends `signal` once
// the recording's temporary file exists (the frame loop is about to run or running), and checks
// the exit: the code, one line, no temporary file, the earlier outputs untouched.
void expect_clean_interruption(int signal, int exit_code) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const std::vector<std::string> run = {"simulate", kQuickScene, "--depth", "1",
                                        "--ground", "plane",     "--out",   dir.path().string()};
  std::vector<std::string> short_run = run;
  short_run.insert(short_run.end(), {"--frames", "5"});
  ASSERT_EQ(sphys_cli(short_run).exit_code, 0);
  const std::string csv = test::read_whole(dir.path() / "frames.csv");
  const std::string recording = test::read_whole(dir.path() / "recording.sphysrec");

  std::vector<std::string> long_run = run;
  // Far more frames than the signal lets it run: seconds even for one body.
  long_run.insert(long_run.end(), {"--frames", "1000000"});
  test::RunningCommand command(SPHYS_CLI_PATH, long_run);
  constexpr auto kPatience = std::chrono::seconds(30);
  const auto start = std::chrono::steady_clock::now();
  while (test::temporary_files_in(dir.path()).empty() &&
         std::chrono::steady_clock::now() - start < kPatience) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_FALSE(test::temporary_files_in(dir.path()).empty()) << "the run never started recording";
  kill(command.pid(), signal);
  const test::CommandResult r = command.wait();

  EXPECT_EQ(r.exit_code, exit_code);
  EXPECT_EQ(r.err, "sphys: interrupted\n");
  EXPECT_TRUE(test::temporary_files_in(dir.path()).empty());
  EXPECT_EQ(test::read_whole(dir.path() / "frames.csv"), csv);
  EXPECT_EQ(test::read_whole(dir.path() / "recording.sphysrec"), recording);
  EXPECT_EQ(tools::read_recording(dir.path() / "recording.sphysrec").frame_count, 6u);
}

TEST(ReliabilityCommand, CtrlCStopsASimulationCleanly) { expect_clean_interruption(SIGINT, 130); }

TEST(ReliabilityCommand, SigtermStopsASimulationCleanly) {
  expect_clean_interruption(SIGTERM, 143);
}

}  // namespace
}  // namespace sphys
