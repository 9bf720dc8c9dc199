// `sphys experiment` draws the paper's Figure 2 (each row's first and last frame) offscreen under
// Xvfb, and with --render every tenth frame (--render-all every one), timed as the paper's frames
// were.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "apps/cli.h"
#include "sphys/tools/experiment.h"
#include "support/screenshot.h"
#include "support/temp_file.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

// The bunnies' sand colour: more red than blue (the sky is bluish, the ground grey).
bool sand(int r, int /*g*/, int b) { return r > b + 20; }

// Sand pixels in the lower half of the picture over all sand pixels.
double sand_low_fraction(const test::Image& image) {
  int low = 0;
  int all = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const unsigned char* p = image.at(x, y);
      if (!sand(p[0], p[1], p[2])) continue;
      ++all;
      low += y >= image.height / 2 ? 1 : 0;
    }
  }
  return all == 0 ? 0.0 : static_cast<double>(low) / all;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ExperimentPictures, FigureTwoShowsTheStacksFallingOntoTheGround) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "experiment";
  const test::CommandResult r = test::sphys_under_xvfb(
      {"experiment", "--only", "d2-8x10", "--frames", "150", "--no-plots", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const test::Image first = test::read_png(out / "d2-8x10-first.png");
  const test::Image last = test::read_png(out / "d2-8x10-last.png");
  ASSERT_EQ(first.width, 640);
  ASSERT_EQ(first.height, 480);
  ASSERT_EQ(last.rgb.size(), first.rgb.size());
  EXPECT_NE(first.rgb, last.rgb);
  // Bunnies in both; the ground (grey, darker than the sky) fills the bottom middle.
  EXPECT_GT(test::count_pixels(first, sand), 640 * 480 / 200);
  EXPECT_GT(test::count_pixels(last, sand), 640 * 480 / 200);
  const unsigned char* ground = last.at(320, 470);
  EXPECT_FALSE(test::is_sky(ground));
  EXPECT_LT(std::abs(ground[0] - ground[1]), 20);
  // The stacks stand tall at first; after 150 frames the bunnies lie low, on the ground.
  EXPECT_GT(sand_low_fraction(last), sand_low_fraction(first) + 0.2)
      << sand_low_fraction(first) << " then " << sand_low_fraction(last);
  // The report shows them under the paper's caption.
  const std::string report = read_text(out / "report.md");
  EXPECT_THAT(report, HasSubstr("## Figure 2"));
  EXPECT_THAT(report, HasSubstr("](d2-8x10-first.png)"));
  EXPECT_THAT(report, HasSubstr("](d2-8x10-last.png)"));
}

TEST(ExperimentPictures, WithoutADisplayTheReportSaysWhyThereAreNoPictures) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "experiment";
  // No X display at all (an empty DISPLAY), so no window can be made.
  const std::string display = getenv("DISPLAY") != nullptr ? getenv("DISPLAY") : "";
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  const test::CommandResult r = test::sphys_cli(
      {"experiment", "--only", "d2-8x10", "--frames", "2", "--no-plots", "--out", out.string()});
  const test::CommandResult render = test::sphys_cli(
      {"experiment", "--only", "d2-8x10", "--frames", "2", "--render", "--out", out.string()});
  if (!display.empty()) setenv("DISPLAY", display.c_str(), 1);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(read_text(out / "report.md"), HasSubstr("| d2-8x10 | no pictures: "));
  EXPECT_FALSE(fs::exists(out / "d2-8x10-first.png"));
  // --render cannot do without: refused before any row runs.
  EXPECT_EQ(render.exit_code, 2) << render.out;
  EXPECT_THAT(render.err, HasSubstr("--render: cannot draw frames"));
}

// Runs d2-8x10 for 20 frames with `flag` and checks the drawing's figures; returns the CSV's
// drawing times, frame by frame.
std::vector<double> drawn_run(const std::string& flag, std::uint32_t frames_drawn) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "experiment";
  const test::CommandResult r =
      test::sphys_under_xvfb({"experiment", "--only", "d2-8x10", "--frames", "20", flag,
                              "--no-plots", "--out", out.string(), "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  if (r.exit_code != 0) return {};
  const auto json = nlohmann::json::parse(r.out);
  const auto& row = json["rows"][0];
  EXPECT_TRUE(row["fps_with_drawing"].is_number()) << row;
  EXPECT_EQ(row["frames_drawn"], frames_drawn);
  const double fps = row["fps"];
  const double drawn = row["fps_with_drawing"];
  const double share = row["drawing_share_percent"];
  // Drawing is more work per frame: fewer frames per second, by the drawing's share exactly
  // (frame time with drawing = physics time / (1 - share)).
  EXPECT_LT(drawn, fps);
  EXPECT_GT(share, 0.0);
  EXPECT_LT(share, 100.0);
  EXPECT_NEAR(drawn, fps * (1.0 - share / 100.0), 1e-6 * fps);
  EXPECT_TRUE(fs::is_regular_file(out / "d2-8x10-last.png"));
  const std::string report = read_text(out / "report.md");
  EXPECT_THAT(report, HasSubstr("## Frames drawn"));
  EXPECT_THAT(report, HasSubstr("| d2-8x10 | " + std::to_string(frames_drawn) + " of 20 |"));
  std::ifstream csv(out / "d2-8x10.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "frame,step_ms,detection_ms,response_ms,contacts,render_ms");
  std::vector<double> render_ms;
  while (std::getline(csv, line)) render_ms.push_back(std::stod(line.substr(line.rfind(',') + 1)));
  EXPECT_EQ(render_ms.size(), 20u);
  return render_ms;
}

TEST(ExperimentPictures, RenderingEveryFrameCountsTheDrawingInTheFrameRate) {
  // Every frame's drawing time is in the CSV.
  for (const double ms : drawn_run("--render-all", 20)) EXPECT_GT(ms, 0.0);
}

TEST(ExperimentPictures, RenderingASampleDrawsEveryTenthFrameAndTheLast) {
  const std::vector<double> render_ms = drawn_run("--render", 20 / tools::kRenderSampleStride);
  ASSERT_EQ(render_ms.size(), 20u);
  for (std::size_t i = 0; i < render_ms.size(); ++i) {
    // Frames 10 and 20 (1-based) are the sample; frame 20 is the last picture's too.
    const bool sampled = (i + 1) % tools::kRenderSampleStride == 0;
    EXPECT_EQ(render_ms[i] > 0.0, sampled) << "frame " << i + 1 << ": " << render_ms[i];
  }
}

}  // namespace
}  // namespace sphys
