// `sphys view --screenshot` under Xvfb with Mesa's software OpenGL: the picture shows the scene
// where the camera looks.

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "apps/cli.h"
#include "support/screenshot.h"
#include "support/temp_file.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 320;
constexpr int kHeight = 180;

using test::count_pixels;
using test::Image;
using test::is_sky;
using test::read_png;
using test::view;

// `sphys view ARGS --screenshot` at kWidth × kHeight.
Image screenshot(const fs::path& png, const std::vector<std::string>& args) {
  return test::screenshot(png, args, kWidth, kHeight);
}

// Renders stacks:4x25 (depth 2) after `frames` frames, with the sphere overlay at `spheres`.
Image screenshot(const test::TempDir& dir, int frames, int spheres) {
  const fs::path png =
      dir.path() / ("shot-" + std::to_string(frames) + "-" + std::to_string(spheres) + ".png");
  return screenshot(png, {"stacks:4x25", "--depth", "2", "--frames", std::to_string(frames),
                          "--spheres", std::to_string(spheres)});
}

TEST(ViewCommand, AScreenshotShowsTheGroundAndTheBunniesWhereTheCameraLooks) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  for (const int frames : {0, 60}) {
    const Image image = screenshot(dir, frames, 0);
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    // Not blank: the corners are sky, and a good part of the picture is not.
    EXPECT_TRUE(is_sky(image.at(0, 0))) << "frame " << frames;
    EXPECT_TRUE(is_sky(image.at(kWidth - 1, 0))) << "frame " << frames;
    int not_sky = 0;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) not_sky += is_sky(image.at(x, y)) ? 0 : 1;
    }
    EXPECT_GT(not_sky, kWidth * kHeight / 10) << "frame " << frames;
    // The camera looks down at the stacks' middle: the ground fills the bottom middle, grey and
    // lit (the three channels close, darker than the sky).
    const unsigned char* ground = image.at(kWidth / 2, kHeight * 9 / 10);
    EXPECT_FALSE(is_sky(ground)) << "frame " << frames;
    EXPECT_LT(std::abs(ground[0] - ground[1]), 20) << "frame " << frames;
    EXPECT_LT(ground[2], 199) << "frame " << frames;
    // The stacks rise from the middle of the ground: the centre column is bunnies, in their
    // sand colour (more red than blue), not sky.
    int bunny = 0;
    for (int y = kHeight / 4; y < kHeight * 3 / 4; ++y) {
      const unsigned char* p = image.at(kWidth / 2, y);
      bunny += !is_sky(p) && p[0] > p[2] + 20 ? 1 : 0;
    }
    EXPECT_GT(bunny, kHeight / 10) << "frame " << frames;
  }
}

TEST(ViewCommand, TheSphereOverlayChangesThePicture) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const Image plain = screenshot(dir, 30, 0);
  const Image spheres = screenshot(dir, 30, 2);
  ASSERT_EQ(plain.rgb.size(), spheres.rgb.size());
  // The overlay's blue spheres over the bunnies: many pixels change, towards blue.
  int changed = 0;
  int bluer = 0;
  for (std::size_t i = 0; i + 2 < plain.rgb.size(); i += 3) {
    if (plain.rgb[i] != spheres.rgb[i] || plain.rgb[i + 1] != spheres.rgb[i + 1] ||
        plain.rgb[i + 2] != spheres.rgb[i + 2]) {
      ++changed;
      bluer += spheres.rgb[i + 2] - spheres.rgb[i] > plain.rgb[i + 2] - plain.rgb[i] ? 1 : 0;
    }
  }
  EXPECT_GT(changed, kWidth * kHeight / 50);
  EXPECT_GT(bluer, changed / 2);
}

TEST(ViewCommand, TheBodiesCastShadowsThatDarkenThePicture) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const std::vector<std::string> scene = {"stacks:4x25", "--depth", "2", "--frames", "60"};
  const Image shadowed = screenshot(dir.path() / "shadowed.png", scene);
  std::vector<std::string> without = scene;
  without.push_back("--no-shadows");
  const Image plain = screenshot(dir.path() / "plain.png", without);
  ASSERT_EQ(plain.rgb.size(), shadowed.rgb.size());
  // Shadows only take sunlight away: the pixels that change get darker, and there are many
  // (the stacks' long shadow on the ground, the bodies shading one another).
  int changed = 0;
  int darker = 0;
  for (std::size_t i = 0; i + 2 < plain.rgb.size(); i += 3) {
    const int before = plain.rgb[i] + plain.rgb[i + 1] + plain.rgb[i + 2];
    const int after = shadowed.rgb[i] + shadowed.rgb[i + 1] + shadowed.rgb[i + 2];
    if (before == after) continue;
    ++changed;
    darker += after < before ? 1 : 0;
  }
  EXPECT_GT(changed, kWidth * kHeight / 50);
  EXPECT_GT(darker, changed * 95 / 100);
}

TEST(ViewCommand, TheContactAndBoxOverlaysDrawInTheirColours) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const std::vector<std::string> scene = {"stacks:4x25", "--depth", "2", "--frames", "60"};
  const Image plain = screenshot(dir.path() / "plain.png", scene);
  std::vector<std::string> with_contacts = scene;
  with_contacts.push_back("--show-contacts");
  const Image contacts = screenshot(dir.path() / "contacts.png", with_contacts);
  std::vector<std::string> with_boxes = scene;
  with_boxes.push_back("--show-boxes");
  const Image boxes = screenshot(dir.path() / "boxes.png", with_boxes);
  // Contact crosses are red, normals yellow; the broad phase's boxes green. None of these
  // colours is in the plain picture (sky, grey ground, sand bunnies).
  const auto red = [](int r, int g, int b) { return r > 180 && g < 90 && b < 90; };
  const auto yellow = [](int r, int g, int b) { return r > 180 && g > 150 && b < 80; };
  const auto green = [](int r, int g, int b) { return g > r + 60 && g > b + 60; };
  EXPECT_EQ(count_pixels(plain, red), 0);
  EXPECT_EQ(count_pixels(plain, yellow), 0);
  EXPECT_EQ(count_pixels(plain, green), 0);
  // 60 frames in, the bottom of the stacks is on the ground: some hundred contacts.
  EXPECT_GT(count_pixels(contacts, red), 20);
  EXPECT_GT(count_pixels(contacts, yellow), 20);
  EXPECT_GT(count_pixels(boxes, green), 200);
}

TEST(ViewCommand, AReplayedFrameLooksLikeTheLiveRunAtThatFrame) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const test::CommandResult run = test::run_command(
      SPHYS_CLI_PATH, {"simulate", "stacks:4x25", "--depth", "2", "--mode", "paper", "--frames",
                       "40", "--out", (dir.path() / "run").string()});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const std::string recording = (dir.path() / "run" / "recording.sphysrec").string();
  // Frame 0 of a recording is the start, frame N the state after N steps, as --frames N live.
  for (const int frame : {0, 40}) {
    const std::string n = std::to_string(frame);
    const Image live =
        screenshot(dir.path() / ("live" + n + ".png"),
                   {"stacks:4x25", "--depth", "2", "--mode", "paper", "--frames", n});
    const Image replay =
        screenshot(dir.path() / ("replay" + n + ".png"), {"--replay", recording, "--frames", n});
    ASSERT_EQ(live.rgb.size(), replay.rgb.size());
    EXPECT_EQ(live.rgb, replay.rgb) << "frame " << frame;
  }
  // And frame 40 is not frame 0: the bunnies have fallen.
  EXPECT_NE(read_png(dir.path() / "replay0.png").rgb, read_png(dir.path() / "replay40.png").rgb);
}

TEST(ViewCommand, TheWindowRunsLiveAndReplaysForSomeFramesThenReportsTheFrameRate) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const test::CommandResult live =
      view({"stacks:2x3", "--depth", "2", "--exit-after", "5", "--spheres", "2", "--show-contacts",
            "--show-boxes", "--width", "320", "--height", "180"});
  ASSERT_EQ(live.exit_code, 0) << live.out << live.err;
  EXPECT_NE(live.out.find("sphys view: 5 frames displayed in"), std::string::npos) << live.out;

  const test::CommandResult run = test::run_command(
      SPHYS_CLI_PATH,
      {"simulate", "stacks:2x3", "--depth", "2", "--frames", "10", "--out", dir.path().string()});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const test::CommandResult replay =
      view({"--replay", (dir.path() / "recording.sphysrec").string(), "--exit-after", "3",
            "--spheres", "1", "--width", "320", "--height", "180"});
  ASSERT_EQ(replay.exit_code, 0) << replay.out << replay.err;
  EXPECT_NE(replay.out.find("sphys view: 3 frames displayed in"), std::string::npos) << replay.out;
}

// Three bunnies hung in a row from the world by a hinge and two ball joints, recorded for 20
// frames, then drawn from the recording with and without the joints' overlay; and the recording
// with its first joint's type corrupted, refused by the viewer and the export.
TEST(ViewCommand, AReplayDrawsItsJointsAndRefusesACorruptOne) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path scene = dir.write("chain.json", R"({"format": "sphys-scene", "version": 1,
      "frames": 20, "ground": {"type": "plane"},
      "bodies": [{"size": 0.8, "position": [0, 3, 0], "sphere_tree": {"method": "octree", "depth": 1}},
                 {"size": 0.8, "position": [1.5, 3, 0], "sphere_tree": {"method": "octree", "depth": 1}},
                 {"size": 0.8, "position": [3, 3, 0], "sphere_tree": {"method": "octree", "depth": 1}}],
      "joints": [{"type": "hinge", "body_a": null, "body_b": 0, "anchor_a": [-0.75, 3, 0],
                  "anchor_b": [-0.75, 0, 0], "axis_a": [0, 0, 1], "axis_b": [0, 0, 1]},
                 {"type": "ball", "body_a": 0, "body_b": 1, "anchor_a": [0.75, 0, 0],
                  "anchor_b": [-0.75, 0, 0]},
                 {"type": "ball", "body_a": 1, "body_b": 2, "anchor_a": [0.75, 0, 0],
                  "anchor_b": [-0.75, 0, 0]}]})");
  const fs::path out = dir.path() / "run";
  const test::CommandResult run =
      test::run_command(SPHYS_CLI_PATH, {"simulate", scene.string(), "--out", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const fs::path recording = out / "recording.sphysrec";
  const std::vector<std::string> replay = {"--replay", recording.string(), "--frames", "20"};
  std::vector<std::string> hidden = replay;
  hidden.push_back("--no-joints");
  const Image joints = screenshot(dir.path() / "joints.png", replay);
  const Image plain = screenshot(dir.path() / "plain.png", hidden);
  // The joints are magenta, a colour found nowhere else (sky, grey ground, sand bunnies).
  const auto magenta = [](int r, int g, int b) { return r > 180 && g < 90 && b > 180; };
  EXPECT_EQ(count_pixels(plain, magenta), 0);
  EXPECT_GT(count_pixels(joints, magenta), 30);

  // The joint records follow the 32-byte header, the metadata and the joint count.
  std::string bytes = test::read_whole(recording);
  std::uint32_t metadata_length = 0;
  for (int i = 0; i < 4; ++i) {
    metadata_length |= std::uint32_t{static_cast<unsigned char>(bytes[28 + i])} << (8 * i);
  }
  bytes[32 + metadata_length + 4] = 7;  // the first joint's type, a u32, little-endian
  const fs::path corrupt = dir.write("corrupt.sphysrec", bytes);
  const std::string message = corrupt.string() + ": joint 0: type 7 is not a joint type";
  test::expect_bad_input(
      {"view", "--replay", corrupt.string(), "--screenshot", (dir.path() / "x.png").string()},
      message);
  test::expect_bad_input({"export", corrupt.string(), "--gltf", (dir.path() / "x.glb").string()},
                         message);
  EXPECT_FALSE(fs::exists(dir.path() / "x.png"));
}

TEST(ViewCommand, BadOptionsExitWithCode2) {
  test::expect_bad_input({"view", "stacks:1x1", "--screenshot", "/tmp/x.png", "--width", "4"},
                         "--width and --height must be between 16 and 8192");
  test::expect_bad_input({"view", "stacks:1x1", "--screenshot", "/tmp/x.png", "--ground", "box"},
                         "--ground must be octree or plane, got 'box'");
  test::expect_bad_input({"view", "stacks:0x1", "--screenshot", "/tmp/x.png"},
                         "unknown preset 'stacks:0x1'");
  test::expect_bad_input({"view", "stacks:1x1", "--screenshot", "/tmp/x.png", "--mode", "bogus"},
                         "--mode: unknown response mode 'bogus'");
  test::expect_bad_input({"view", "stacks:1x1", "--msaa", "32"}, "--msaa must be between 0 and 16");
  test::expect_bad_input({"view", "stacks:1x1", "--exit-after", "0"},
                         "--exit-after must be at least 1");
  test::expect_bad_input({"view", "stacks:1x1", "--replay", "/tmp/x.sphysrec"},
                         "give a scene or --replay, not both");
  test::expect_bad_input({"view", "--replay", "/tmp/x.sphysrec", "--mode", "paper"},
                         "--mode and --ground change a live run");
  test::expect_bad_input({"view", "--replay", "/nonexistent/run.sphysrec"},
                         "/nonexistent/run.sphysrec");
}

TEST(ViewCommand, AReplayScreenshotPastTheLastFrameIsRefused) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const test::CommandResult run = test::run_command(
      SPHYS_CLI_PATH,
      {"simulate", "stacks:1x2", "--depth", "2", "--frames", "5", "--out", dir.path().string()});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const std::string recording = (dir.path() / "recording.sphysrec").string();
  test::expect_bad_input({"view", "--replay", recording, "--frames", "6", "--screenshot",
                          (dir.path() / "x.png").string()},
                         "--frames 6 is past the recording's last frame, 5");
  EXPECT_FALSE(fs::exists(dir.path() / "x.png"));
}

}  // namespace
}  // namespace sphys
