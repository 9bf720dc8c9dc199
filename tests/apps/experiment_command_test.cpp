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
#include "support/temp_file.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;
using test::expect_bad_input;
using test::sphys_cli;
using testing::HasSubstr;

using test::read_lines;

TEST(ExperimentCommand, OneRowPrintsThePapersFiguresAndWritesTheReport) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "experiment";
  const test::CommandResult r = sphys_cli({"experiment", "--only", "d2-8x10", "--frames", "3",
                                           "--no-plots", "--no-pictures", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Table 1's row for 8 stacks of 10 at depth 2, on one line: contacts per frame, FPS and
  // frame-time sd as the paper printed them.
  const std::size_t at = r.out.find("16381.50");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::size_t line_start = r.out.rfind('\n', at) + 1;
  const std::string line = r.out.substr(line_start, r.out.find('\n', at) - line_start);
  EXPECT_THAT(line, HasSubstr("8 × 10"));
  EXPECT_THAT(line, HasSubstr("43.80"));
  EXPECT_THAT(line, HasSubstr("9.25"));
  EXPECT_THAT(line, HasSubstr("0 of 80"));
  EXPECT_THAT(r.out, HasSubstr((out / "report.md").string()));

  std::ifstream report_file(out / "report.md");
  std::stringstream report;
  report << report_file.rdbuf();
  EXPECT_THAT(report.str(), HasSubstr("d2-8x10"));
  EXPECT_THAT(report.str(), HasSubstr("16381.50"));
  // --no-plots drew none, and the report links none.
  EXPECT_THAT(report.str(), Not(HasSubstr("## Plots")));
  EXPECT_THAT(report.str(), Not(HasSubstr("-frame-time.png")));
  // The paper's response unless asked otherwise, and the report says so at the top.
  EXPECT_THAT(r.out, testing::StartsWith("Response: paper ("));
  EXPECT_THAT(report.str(), HasSubstr("\n\nResponse: paper ("));

  const std::vector<std::string> csv = read_lines(out / "d2-8x10.csv");
  ASSERT_EQ(csv.size(), 4u);
  EXPECT_EQ(csv[0], "frame,step_ms,detection_ms,response_ms,contacts,render_ms");
  for (int frame = 1; frame <= 3; ++frame) {
    EXPECT_EQ(csv[static_cast<std::size_t>(frame)].substr(0, 2), std::to_string(frame) + ",");
  }
  // Only the one row ran, and --no-plots and --no-pictures drew nothing.
  int files = 0;
  for (const auto& entry : fs::directory_iterator(out)) {
    EXPECT_NE(entry.path().extension(), ".png") << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 2);
}

TEST(ExperimentCommand, JsonHasTheRowAndItsFrames) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "experiment";
  const test::CommandResult r =
      sphys_cli({"experiment", "--only", "d2-8x10", "--frames", "3", "--no-plots", "--ground",
                 "plane", "--out", out.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  ASSERT_EQ(json["rows"].size(), 1u);
  const auto& row = json["rows"][0];
  EXPECT_EQ(row["id"], "d2-8x10");
  EXPECT_EQ(row["frames"], 3);
  EXPECT_EQ(row["bodies"], 80);
  EXPECT_EQ(json["response"], "paper");
  EXPECT_EQ(json["contacts"], "reduced");
  EXPECT_EQ(row["stopped_non_finite"], false);
  EXPECT_EQ(row["bodies_below_plane"], 0);
  // Three frames of falling: no body rests, none is asleep in paper mode.
  EXPECT_GE(row["deepest_penetration_m"].get<double>(), 0.0);
  EXPECT_GE(row["mean_penetration_m"].get<double>(), 0.0);
  EXPECT_EQ(row["bodies_at_rest"], 0);
  EXPECT_TRUE(row["all_at_rest_from_frame"].is_null());
  EXPECT_GE(row["jitter_m_per_s"].get<double>(), 0.0);
  EXPECT_GT(row["final_kinetic_energy_J"].get<double>(), 0.0);
  EXPECT_GE(row["contacts_per_frame"].get<double>(), 0.0);
  EXPECT_GT(row["fps"].get<double>(), 0.0);
  EXPECT_THAT(row["tree_builder"].get<std::string>(), HasSubstr("combined, branching 8"));
  // Three frames of falling from 1 m: the lowest bunny is still well above the plane.
  EXPECT_GT(row["lowest_center_y_end_m"].get<double>(), 0.9);
  EXPECT_EQ(json["report"], (out / "report.md").string());
  EXPECT_TRUE(fs::exists(out / "d2-8x10.csv"));
}

TEST(ExperimentCommand, PlausibleModeIsRunAndReported) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "experiment";
  const auto run = [&](const std::string& contacts) {
    const test::CommandResult r =
        sphys_cli({"experiment", "--only", "d3-8x10", "--frames", "30", "--no-plots", "--mode",
                   "plausible", "--contacts", contacts, "--out", out.string(), "--json"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto all = run("all");
  EXPECT_EQ(all["response"], "plausible");
  EXPECT_EQ(all["contacts"], "all");
  std::ifstream report_file(out / "report.md");
  std::stringstream report;
  report << report_file.rdbuf();
  EXPECT_THAT(report.str(), HasSubstr("\nResponse: plausible ("));
  EXPECT_THAT(report.str(), HasSubstr("\nContacts: all ("));
  // By frame 30 the lowest bunnies have landed: reduced, a pair keeps a manifold of at most 4
  // contacts, or closing fast one per pair of its trees' 8-leaf parts that meet, so the response
  // sees fewer contacts than one per leaf pair.
  const auto reduced = run("reduced");
  EXPECT_EQ(reduced["contacts"], "reduced");
  EXPECT_LT(reduced["rows"][0]["contacts_per_frame"].get<double>(),
            all["rows"][0]["contacts_per_frame"].get<double>());
}

TEST(ExperimentCommand, BadOptionsExitWithCode2) {
  const test::TempDir dir;
  const std::string out = (dir.path() / "experiment").string();
  expect_bad_input({"experiment", "--only", "d2-8x10,d4-1x1", "--out", out, "--no-cache"},
                   "unknown experiment row 'd4-1x1'; rows: d2-4x25, d2-4x50, d3-4x25, d3-4x50, "
                   "d2-8x10, d2-8x20, d3-8x10, d3-8x20");
  expect_bad_input({"experiment", "--only", "", "--out", out, "--no-cache"},
                   "unknown experiment row ''");
  expect_bad_input({"experiment", "--frames", "0", "--out", out, "--no-cache"},
                   "--frames must be at least 1");
  expect_bad_input(
      {"experiment", "--only", "d2-8x10", "--ground", "bogus", "--out", out, "--no-cache"},
      "--ground must be octree or plane, got 'bogus'");
  expect_bad_input(
      {"experiment", "--only", "d2-8x10", "--mode", "bogus", "--out", out, "--no-cache"},
      "--mode: unknown response mode 'bogus'; response modes: paper, plausible");
  expect_bad_input(
      {"experiment", "--only", "d2-8x10", "--contacts", "some", "--out", out, "--no-cache"},
      "--contacts: unknown contact set 'some'; contact sets: all, reduced");
  // Refused before anything ran: no report.
  EXPECT_FALSE(fs::exists(fs::path(out) / "report.md"));
}

}  // namespace
}  // namespace sphys
