#pragma once

// `sphys view --screenshot` under Xvfb with Mesa's software OpenGL, and reading the PNG back:
// shared by the scene viewer's tests and the robot viewer's. The including program defines
// SPHYS_CLI_PATH and links stb.

#include <cstdlib>
#include <filesystem>
#include <stb_image.h>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/run_command.h"

namespace sphys::test {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> rgb;

  [[nodiscard]] const unsigned char* at(int x, int y) const {
    return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  }
};

// The sky's colour, as the renderer clears to it.
inline bool is_sky(const unsigned char* p) {
  return std::abs(p[0] - 199) <= 3 && std::abs(p[1] - 209) <= 3 && std::abs(p[2] - 222) <= 3;
}

inline Image read_png(const std::filesystem::path& png) {
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

// Runs `sphys ARGS` under Xvfb.
inline CommandResult sphys_under_xvfb(std::vector<std::string> args) {
  // Mesa's software renderer keeps allocations past exit, which LeakSanitizer would report.
  setenv("ASAN_OPTIONS", "detect_leaks=0:abort_on_error=1", 1);
  args.insert(args.begin(), {"-a", "-s", "-screen 0 640x480x24", SPHYS_CLI_PATH});
  return run_command("xvfb-run", args);
}

// Runs `sphys view ARGS` under Xvfb.
inline CommandResult view(std::vector<std::string> args) {
  args.insert(args.begin(), "view");
  return sphys_under_xvfb(args);
}

// `sphys view ARGS --screenshot PNG` at width × height, read back.
inline Image screenshot(const std::filesystem::path& png, std::vector<std::string> args, int width,
                        int height) {
  args.insert(args.end(), {"--screenshot", png.string(), "--width", std::to_string(width),
                           "--height", std::to_string(height)});
  const CommandResult r = view(args);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  return read_png(png);
}

// Pixels of `image` for which `pick(r, g, b)` holds.
template <typename Pick>
int count_pixels(const Image& image, Pick pick) {
  int count = 0;
  for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
    count += pick(image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]) ? 1 : 0;
  }
  return count;
}

}  // namespace sphys::test
