// `sphys view --screenshot` under Xvfb with Mesa's software OpenGL: the picture shows the scene
// where the camera looks.

#include <cstdlib>
#include <filesystem>
#include <stb_image.h>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "apps/cli.h"
#include "support/temp_file.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 320;
constexpr int kHeight = 180;

struct Image {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> rgb;

  [[nodiscard]] const unsigned char* at(int x, int y) const {
    return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  }
};

// The sky's colour, as the renderer clears to it.
bool is_sky(const unsigned char* p) {
  return std::abs(p[0] - 199) <= 3 && std::abs(p[1] - 209) <= 3 && std::abs(p[2] - 222) <= 3;
}

// Renders stacks:4x25 (depth 2) after `frames` frames, with the sphere overlay at `spheres`.
Image screenshot(const test::TempDir& dir, int frames, int spheres) {
  const fs::path png =
      dir.path() / ("shot-" + std::to_string(frames) + "-" + std::to_string(spheres) + ".png");
  // Mesa's software renderer keeps allocations past exit, which LeakSanitizer would report.
  setenv("ASAN_OPTIONS", "detect_leaks=0:abort_on_error=1", 1);
  const test::CommandResult r = test::run_command(
      "xvfb-run",
      {"-a", "-s", "-screen 0 640x480x24", SPHYS_CLI_PATH, "view", "stacks:4x25", "--depth", "2",
       "--frames", std::to_string(frames), "--spheres", std::to_string(spheres), "--screenshot",
       png.string(), "--width", std::to_string(kWidth), "--height", std::to_string(kHeight)});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  Image image;
  int channels = 0;
  unsigned char* data = stbi_load(png.string().c_str(), &image.width, &image.height, &channels, 3);
  if (data == nullptr) {
    ADD_FAILURE() << "no PNG at " << png;
    return image;
  }
  image.rgb.assign(data, data + static_cast<std::size_t>(image.width) * image.height * 3);
  stbi_image_free(data);
  return image;
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

TEST(ViewCommand, BadOptionsExitWithCode2) {
  test::expect_bad_input({"view", "stacks:1x1", "--screenshot", "/tmp/x.png", "--width", "4"},
                         "--width and --height must be between 16 and 8192");
  test::expect_bad_input({"view", "stacks:1x1", "--screenshot", "/tmp/x.png", "--ground", "box"},
                         "--ground must be octree or plane, got 'box'");
  test::expect_bad_input({"view", "stacks:0x1", "--screenshot", "/tmp/x.png"},
                         "unknown preset 'stacks:0x1'");
  test::expect_bad_input({"view", "stacks:1x1", "--screenshot", "/tmp/x.png", "--mode", "bogus"},
                         "unknown response mode 'bogus'");
}

}  // namespace
}  // namespace sphys
