#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <sys/stat.h>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/experiment.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;
using sphys::test::read_whole;
using testing::AllOf;
using testing::HasSubstr;
using testing::IsEmpty;
using testing::Not;
using testing::StartsWith;

RowResult result_for(const ExperimentRow& row, std::vector<FrameSample> frames) {
  RowResult result;
  result.row = row;
  result.frames = std::move(frames);
  result.tree_builder = "combined, branching 8";
  result.ground = "octree of a 16 m box, 5 levels";
  result.bodies = static_cast<std::uint32_t>(row.stacks * row.per_stack);
  return result;
}

// Two rows of the paper and one it did not run, given out of the paper's order.
//   d2-4x25: contacts 150, mean 3 ms (333.33 FPS), sd sqrt(2), detection 25 %, response 41.67 %
//   d3-8x20: contacts 2000, mean 20 ms (50 FPS), sd sqrt(200), detection 20 %, response 40 %
std::vector<RowResult> sample_results() {
  RowResult extra = result_for({4, 2, 3}, {});
  extra.stopped_non_finite = true;
  RowResult deep = result_for({3, 8, 20}, {{10.0, 2.0, 4.0, 1000}, {30.0, 6.0, 12.0, 3000}});
  deep.bodies_below_plane = 2;
  deep.plausibility.deepest_penetration = 0.0125f;
  deep.plausibility.mean_penetration = 0.0031;
  deep.plausibility.bodies_at_rest = 150;
  deep.plausibility.jitter = 0.25;
  deep.plausibility.final_kinetic_energy = 1234.5;
  deep.lowest_center_y = -0.25f;
  RowResult shallow = result_for({2, 4, 25}, {{2.0, 0.5, 1.0, 100}, {4.0, 1.0, 1.5, 200}});
  shallow.plausibility.deepest_penetration = 0.001f;
  shallow.plausibility.mean_penetration = 0.0004;
  shallow.plausibility.bodies_at_rest = 100;
  shallow.plausibility.all_at_rest_frame = 2;
  shallow.plausibility.jitter = 0.0012;
  shallow.plausibility.final_kinetic_energy = 0.5;
  shallow.lowest_center_y = 0.5f;
  shallow.tree_builder = "octree | branching 8";
  shallow.ground = "exact plane";
  return {extra, deep, shallow};
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The first line holding `needle`, or "" (and a failure).
std::string line_with(const std::string& text, std::string_view needle) {
  for (const std::string& line : lines_of(text)) {
    if (line.find(needle) != std::string::npos) return line;
  }
  ADD_FAILURE() << "no line with '" << needle << "' in:\n" << text;
  return "";
}

// Columns on a terminal: UTF-8 continuation bytes take none.
std::size_t columns_of(const std::string& line) {
  return static_cast<std::size_t>(std::ranges::count_if(
      line, [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// The column just after the first `needle` in the line.
std::size_t column_after(const std::string& line, std::string_view needle) {
  const std::size_t at = line.find(needle);
  EXPECT_NE(at, std::string::npos) << needle << " in " << line;
  return columns_of(line.substr(0, at + needle.size()));
}

std::vector<std::string> names_in(const fs::path& directory) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory)) {
    names.push_back(entry.path().filename().string());
  }
  std::ranges::sort(names);
  return names;
}

// Sets PATH for one test and puts the old one back.
class PathOverride {
 public:
  explicit PathOverride(const std::string& path) {
    if (const char* old = std::getenv("PATH")) old_ = old;
    setenv("PATH", path.c_str(), 1);
  }
  ~PathOverride() {
    if (old_) {
      setenv("PATH", old_->c_str(), 1);
    } else {
      unsetenv("PATH");
    }
  }
  PathOverride(const PathOverride&) = delete;
  PathOverride& operator=(const PathOverride&) = delete;

 private:
  std::optional<std::string> old_;
};

// An executable shell script named gnuplot in `directory`.
void install_fake_gnuplot(const fs::path& directory, const std::string& body) {
  const fs::path program = directory / "gnuplot";
  std::ofstream(program) << "#!/bin/sh\n" << body << "\n";
  chmod(program.c_str(), 0755);
}

std::string plot_error(const fs::path& directory, const std::vector<RowResult>& results) {
  try {
    (void)write_plots(directory, results);
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "write_plots threw no sphys::Error";
  return "";
}

TEST(ExperimentComparison, SetsThePapersFiguresBesideOursRowByRow) {
  const std::string text = comparison_text(sample_results(), {});
  EXPECT_THAT(line_with(text, "4 × 25"),
              AllOf(StartsWith("    2"), HasSubstr(" 4216.81 "), HasSubstr(" 150.00 "),
                    HasSubstr(" 57.47 "), HasSubstr(" 333.33 "), HasSubstr(" 5.89 "),
                    HasSubstr(" 1.41 "), HasSubstr(" 0 of 100 "), HasSubstr(" 0.0010 ")));
  EXPECT_THAT(line_with(text, "8 × 20"),
              AllOf(StartsWith("    3"), HasSubstr(" 265562.60 "), HasSubstr(" 2000.00 "),
                    HasSubstr(" 6.91 "), HasSubstr(" 50.00 "), HasSubstr(" 69.29 "),
                    HasSubstr(" 14.14 "), HasSubstr(" 2 of 160 "), HasSubstr(" 0.0125 ")));
  // Ours only: mean penetration, bodies at rest at the end, the frame from which all were at
  // rest (the Markdown test checks the cell), the jitter of the last frames and the kinetic
  // energy at the end.
  EXPECT_THAT(line_with(text, "4 × 25"), AllOf(HasSubstr(" 0.0004 "), HasSubstr(" 100 of 100 "),
                                               HasSubstr(" 0.0012 "), HasSubstr(" 0.500")));
  EXPECT_THAT(line_with(text, "8 × 20"),
              AllOf(HasSubstr(" 0.0031 "), HasSubstr(" 150 of 160 "), HasSubstr(" never "),
                    HasSubstr(" 0.2500 "), HasSubstr(" 1234.500")));
  // A row the paper did not run: no paper figures, and ours n/a without frames.
  EXPECT_THAT(line_with(text, "2 × 3"), AllOf(HasSubstr(" - "), HasSubstr(" n/a ")));
  // Rows the results lack are left out.
  EXPECT_THAT(text, AllOf(Not(HasSubstr("5621.16")), Not(HasSubstr("4 × 50"))));
}

TEST(ExperimentComparison, ListsRowsInThePapersOrderThenTheOthers) {
  const std::string text = comparison_text(sample_results(), {});
  const std::size_t first = text.find("4 × 25");
  const std::size_t second = text.find("8 × 20");
  const std::size_t third = text.find("2 × 3");
  ASSERT_NE(third, std::string::npos);
  EXPECT_LT(first, second);
  EXPECT_LT(second, third);
}

TEST(ExperimentComparison, AlignsTheColumnsOfTable1) {
  const std::vector<std::string> lines = lines_of(comparison_text(sample_results(), {}));
  // The mode's two lines and a blank one, the title, a blank line, the group line, then names,
  // a rule and three rows, all numbers right-aligned to the same end; "×" counts as one column.
  ASSERT_GE(lines.size(), 11u);
  EXPECT_THAT(lines[3], StartsWith("Table 1: "));
  EXPECT_THAT(lines[6], StartsWith("depth  objects"));
  const std::size_t width = columns_of(lines[7]);
  EXPECT_EQ(lines[7], std::string(width, '-'));
  for (std::size_t i = 6; i < 11; ++i) EXPECT_EQ(columns_of(lines[i]), width) << lines[i];
  // Each paper figure ends where the header "paper" above it ends.
  const std::size_t paper_end = column_after(lines[6], "paper");
  EXPECT_EQ(column_after(lines[8], "4216.81"), paper_end);
  EXPECT_EQ(column_after(lines[9], "265562.60"), paper_end);
}

TEST(ExperimentComparison, SetsTheSection5StatisticsBesideOurs) {
  std::vector<RowResult> results = sample_results();
  results.erase(results.begin());  // the row without frames would make every statistic n/a
  const std::string text = comparison_text(results, {});
  // Contacts rise as FPS falls and the frame time spread grows: r = -1 and +1 with two rows.
  EXPECT_THAT(line_with(text, "contacts vs FPS"), AllOf(HasSubstr("+0.75"), HasSubstr("-1.00")));
  EXPECT_THAT(line_with(text, "contacts vs frame time sd"),
              AllOf(HasSubstr("+0.96"), HasSubstr("+1.00")));
  // Detection shares 25 and 20: mean 22.5, sd 2.5 * sqrt(2); response 41.67 and 40.
  EXPECT_THAT(line_with(text, "detection share of frame time"),
              AllOf(HasSubstr("23.00"), HasSubstr("22.50")));
  EXPECT_THAT(line_with(text, "detection share sd"), AllOf(HasSubstr("0.08"), HasSubstr("3.54")));
  EXPECT_THAT(line_with(text, "response share of frame time"),
              AllOf(HasSubstr("40.00"), HasSubstr("40.83")));
  EXPECT_THAT(line_with(text, "response share sd"), AllOf(HasSubstr("0.26"), HasSubstr("1.18")));
  EXPECT_THAT(line_with(text, "detection share vs contacts"),
              AllOf(HasSubstr("-0.59"), HasSubstr("-1.00")));
  EXPECT_THAT(line_with(text, "response share vs contacts"),
              AllOf(HasSubstr("+0.88"), HasSubstr("-1.00")));
}

TEST(ExperimentComparison, WritesNaForStatisticsItCannotCompute) {
  const std::vector<RowResult> one = {result_for({2, 4, 25}, {{2.0, 0.5, 1.0, 100}})};
  const std::string text = comparison_text(one, {});
  EXPECT_THAT(line_with(text, "contacts vs FPS"), AllOf(HasSubstr("+0.75"), HasSubstr("n/a")));
  EXPECT_THAT(line_with(text, "detection share sd"), HasSubstr("n/a"));
  EXPECT_THAT(line_with(text, "detection share of frame time"), HasSubstr("25.00"));
}

TEST(ExperimentMarkdown, HasTheMachineTheNotesAndBothTables) {
  const std::string md = markdown_report(sample_results(), "Test machine: 2 cores", {}, {});
  EXPECT_THAT(md, StartsWith("# "));
  EXPECT_THAT(md, HasSubstr("\nMachine: Test machine: 2 cores\n"));
  EXPECT_THAT(md, AllOf(HasSubstr("physics step alone"), HasSubstr("included rendering")));
  EXPECT_THAT(md, HasSubstr("\n## Table 1\n\n| depth | objects | contacts/frame (paper) |"));
  EXPECT_THAT(md,
              HasSubstr("| bodies below plane | deepest penetration (m) | mean penetration (m) | "
                        "bodies at rest at the end | all at rest from frame | jitter, last 60 "
                        "frames (m/s) | final kinetic energy (J) |\n"));
  // Not drawn: no FPS with drawing, and no "Frames drawn" or Figure 2 section.
  EXPECT_THAT(md, HasSubstr("\n| 2 | 4 × 25 | 4216.81 | 150.00 | 57.47 | 333.33 | n/a | 5.89 | "
                            "1.41 | 0 of 100 | 0.0010 | 0.0004 | 100 of 100 | 2 | 0.0012 | 0.500 "
                            "|\n"));
  EXPECT_THAT(md, HasSubstr("\n| 4 | 2 × 3 | - | n/a | - | n/a | n/a | - | n/a | 0 of 6 | 0.0000 "
                            "| 0.0000 | 0 of 6 | never | 0.0000 | 0.000 |\n"));
  EXPECT_THAT(md, Not(HasSubstr("## Frames drawn")));
  EXPECT_THAT(md, Not(HasSubstr("## Figure 2")));
  EXPECT_LT(md.find("| 4 × 25 |"), md.find("| 8 × 20 |"));
  EXPECT_THAT(md, HasSubstr("\n## Statistics (§5)\n\n| statistic | paper | ours |\n"));
  EXPECT_THAT(md, HasSubstr("\n| detection share of frame time (%) | 23.00 | n/a |\n"));
  // The paper's printed contacts-FPS correlation set against its own Table 1.
  EXPECT_THAT(md, HasSubstr("Table 1 gives r = -0.75"));
}

TEST(ExperimentMarkdown, StatesTheResponseModeAndTheContactsInItsHeader) {
  const auto header = [](const ExperimentMode& mode) {
    const std::string md = markdown_report(sample_results(), "m", mode, {});
    return md.substr(0, md.find("\n## Table 1"));
  };
  // The paper's response sees every leaf pair, whatever the contacts setting says.
  EXPECT_THAT(header({}), AllOf(HasSubstr("\nResponse: paper ("),
                                HasSubstr("\nContacts: every overlapping leaf pair (the contacts "
                                          "setting, reduced, applies to plausible mode only)\n")));
  EXPECT_THAT(header({ResponseMode::kPlausible, ContactSet::kReduced}),
              AllOf(HasSubstr("\nResponse: plausible ("), HasSubstr("\nContacts: reduced (")));
  EXPECT_THAT(header({ResponseMode::kPlausible, ContactSet::kAll}),
              HasSubstr("\nContacts: all (one per overlapping leaf pair"));
  // The terminal's table opens with the same lines.
  EXPECT_THAT(comparison_text(sample_results(), {ResponseMode::kPlausible, ContactSet::kAll}),
              StartsWith("Response: plausible ("));
}

TEST(ExperimentMarkdown, ReportsEachRunsBuilderAndEndState) {
  const std::string md = markdown_report(sample_results(), "m", {}, {});
  EXPECT_THAT(md, HasSubstr("\n## Runs\n"));
  // '|' in a builder's name is escaped so that it does not split the cell.
  EXPECT_THAT(md, HasSubstr("\n| d2-4x25 | octree \\| branching 8 | exact plane | 2 | yes | "
                            "0.5000 | no |\n"));
  EXPECT_THAT(md, HasSubstr("\n| d3-8x20 | combined, branching 8 | octree of a 16 m box, 5 levels "
                            "| 2 | no: 2 of 160 below | "
                            "-0.2500 | no |\n"));
  EXPECT_THAT(md,
              HasSubstr("\n| d4-2x3 | combined, branching 8 | octree of a 16 m box, 5 levels | 0 | "
                        "yes | 0.0000 | yes |\n"));
  // d3-8x20 lost bunnies over the octree ground's edge: the report says why.
  EXPECT_THAT(md, HasSubstr("\nThe bunnies below the plane slid off the octree ground's edge"));
}

TEST(ExperimentMarkdown, SaysNothingOfAnEdgeWhenNoBunnyFellOffOne) {
  std::vector<RowResult> results = sample_results();
  // The same loss on the exact plane (which has no edge), and none on the octree.
  results[1].ground = "exact plane";
  EXPECT_THAT(markdown_report(results, "m", {}, {}), Not(HasSubstr("octree ground's edge")));
  results[1].ground = "octree of a 16 m box, 5 levels";
  results[1].bodies_below_plane = 0;
  EXPECT_THAT(markdown_report(results, "m", {}, {}), Not(HasSubstr("octree ground's edge")));
}

TEST(ExperimentMarkdown, LinksThePlotsWritePlotsDraws) {
  const std::vector<std::filesystem::path> drawn = {
      "out/d2-4x25-frame-time.png", "out/d2-4x25-contacts.png", "out/d3-8x20-frame-time.png"};
  const std::string md = markdown_report(sample_results(), "m", {}, drawn);
  const PlotFiles files = plot_files({2, 4, 25});
  EXPECT_EQ(files.frame_time, "d2-4x25-frame-time.png");
  EXPECT_EQ(files.contacts, "d2-4x25-contacts.png");
  EXPECT_THAT(md, HasSubstr("](d2-4x25-frame-time.png)"));
  EXPECT_THAT(md, HasSubstr("](d2-4x25-contacts.png)"));
  EXPECT_THAT(md, HasSubstr("](d3-8x20-frame-time.png)"));
  // A row without frames has no plots.
  EXPECT_THAT(md, Not(HasSubstr("d4-2x3-frame-time.png")));
  EXPECT_LT(md.find("## Plots"), md.find("d2-4x25-frame-time.png"));
  // A plot not drawn is not linked; without plots (--no-plots, no gnuplot) there is no section.
  EXPECT_THAT(md, Not(HasSubstr("d3-8x20-contacts.png")));
  EXPECT_THAT(markdown_report(sample_results(), "m", {}, {}), Not(HasSubstr("## Plots")));
  EXPECT_THAT(markdown_report(sample_results(), "m", {}, {}), Not(HasSubstr("frame-time.png")));
}

TEST(ExperimentMarkdown, FramesDrawnEveryStepAndFigureTwo) {
  // Two frames, each drawn: physics 2 + 4 ms, drawing 2 + 4 ms.
  RowResult drawn = result_for({2, 8, 10}, {{2.0, 0.5, 1.0, 10, 2.0}, {4.0, 1.0, 2.0, 20, 4.0}});
  drawn.drawn_every = 1;
  drawn.first_picture = "d2-8x10-first.png";
  drawn.last_picture = "d2-8x10-last.png";
  RowResult missing = result_for({3, 8, 10}, {{1.0, 0.5, 0.25, 5}});
  missing.pictures_missing = "cannot start GLFW (is there a display?)";
  const RowSummary summary = summarize(drawn);
  EXPECT_DOUBLE_EQ(summary.fps, 1000.0 / 3.0);
  EXPECT_DOUBLE_EQ(summary.fps_with_drawing, 1000.0 * 2.0 / 12.0);
  EXPECT_DOUBLE_EQ(summary.drawing_share, 50.0);
  EXPECT_DOUBLE_EQ(summary.detection_share_drawn, 100.0 * 1.5 / 12.0);
  EXPECT_DOUBLE_EQ(summary.response_share_drawn, 100.0 * 3.0 / 12.0);
  EXPECT_TRUE(std::isnan(summarize(missing).fps_with_drawing));
  EXPECT_TRUE(std::isnan(summarize(missing).drawing_share));
  const std::string md = markdown_report(std::vector{drawn, missing}, "m", {}, {});
  EXPECT_THAT(md, HasSubstr("\n## Frames drawn\n"));
  EXPECT_THAT(md, HasSubstr("\n| d2-8x10 | 2 of 2 | 333.33 | 166.67 | 50.0 | 12.5 | 25.0 |\n"));
  EXPECT_THAT(md, Not(HasSubstr("\n| d3-8x10 | 1000.00 |")));
  EXPECT_THAT(md, HasSubstr("\n| d2-8x10 | ![d2-8x10, first frame](d2-8x10-first.png) | "
                            "![d2-8x10, last frame](d2-8x10-last.png) |\n"));
  EXPECT_THAT(md, HasSubstr("\n| d3-8x10 | no pictures: cannot start GLFW (is there a display?) "
                            "| |\n"));
}

TEST(ExperimentMarkdown, AFixedSampleOfFramesDrawnStandsForTheFramesNotDrawn) {
  // Four frames of 1 ms physics each (0.25 ms detection, 0.5 ms response); every 2nd one drawn, in
  // 3 and 5 ms, so the four frames count 4 ms of drawing each: 16 ms of drawing beside 4 of
  // physics. The first and third frames' drawing (the last picture's, say) is not in the sample.
  RowResult sampled = result_for({2, 8, 10}, {{1.0, 0.25, 0.5, 10, 9.0},
                                              {1.0, 0.25, 0.5, 10, 3.0},
                                              {1.0, 0.25, 0.5, 10, 0.0},
                                              {1.0, 0.25, 0.5, 10, 5.0}});
  sampled.drawn_every = 2;
  const RowSummary summary = summarize(sampled);
  EXPECT_EQ(summary.frames_drawn, 2u);
  EXPECT_DOUBLE_EQ(summary.fps_with_drawing, 1000.0 * 4.0 / 20.0);
  EXPECT_DOUBLE_EQ(summary.drawing_share, 80.0);
  EXPECT_DOUBLE_EQ(summary.detection_share_drawn, 5.0);
  EXPECT_DOUBLE_EQ(summary.response_share_drawn, 10.0);
  const std::string md = markdown_report(std::vector{sampled}, "m", {}, {});
  EXPECT_THAT(md, HasSubstr("\n| d2-8x10 | 2 of 4 | 1000.00 | 200.00 | 80.0 | 5.0 | 10.0 |\n"));
  // A frame of the sample left undrawn (a broken run): no figure rather than a wrong one.
  sampled.frames[3].render_ms = 0.0;
  EXPECT_TRUE(std::isnan(summarize(sampled).fps_with_drawing));
  EXPECT_EQ(summarize(sampled).frames_drawn, 0u);
  // Drawn but not asked to be timed (Figure 2's pictures alone): no figure.
  sampled.frames[3].render_ms = 5.0;
  sampled.drawn_every = 0;
  EXPECT_TRUE(std::isnan(summarize(sampled).fps_with_drawing));
}

TEST(ExperimentCsv, WritesOneLinePerFrameNumberedFromOne) {
  const test::TempDir dir;
  const fs::path path = dir.path() / "d2-4x25.csv";
  write_row_csv(path, result_for({2, 4, 25}, {{2.5, 0.25, 1.0, 10}, {3.5, 0.75, 1.5, 20}}));
  EXPECT_EQ(read_whole(path),
            "frame,step_ms,detection_ms,response_ms,contacts,render_ms\n"
            "1,2.5,0.25,1,10,0\n"
            "2,3.5,0.75,1.5,20,0\n");
}

TEST(ExperimentPlots, DrawsTwoPngsPerRowWithFrames) {
  if (!plots_available()) GTEST_SKIP() << "gnuplot is not on PATH (scripts/setup installs it)";
  const test::TempDir dir;
  // A quote and a space in the name test the quoting of the script; the folder does not exist
  // yet.
  const fs::path plots = dir.path() / "it's plots";
  std::vector<RowResult> results = sample_results();
  // One frame without contacts: gnuplot has to widen empty ranges rather than fail.
  results.push_back(result_for({2, 8, 10}, {{1.0, 0.0, 0.0, 0}}));
  const std::vector<fs::path> written = write_plots(plots, results);
  EXPECT_EQ(written, (std::vector<fs::path>{
                         plots / "d3-8x20-frame-time.png", plots / "d3-8x20-contacts.png",
                         plots / "d2-4x25-frame-time.png", plots / "d2-4x25-contacts.png",
                         plots / "d2-8x10-frame-time.png", plots / "d2-8x10-contacts.png"}));
  for (const fs::path& png : written) {
    const std::string bytes = read_whole(png);
    EXPECT_GT(bytes.size(), 1000u) << png;
    EXPECT_THAT(bytes, StartsWith(std::string("\x89PNG\r\n\x1a\n", 8))) << png;
  }
  // The data, the script and the temporary names are gone.
  EXPECT_EQ(names_in(plots),
            (std::vector<std::string>{"d2-4x25-contacts.png", "d2-4x25-frame-time.png",
                                      "d2-8x10-contacts.png", "d2-8x10-frame-time.png",
                                      "d3-8x20-contacts.png", "d3-8x20-frame-time.png"}));
}

TEST(ExperimentPlots, NothingToDrawNeedsNoGnuplot) {
  const test::TempDir dir;
  const PathOverride path(dir.path().string());
  EXPECT_THAT(write_plots(dir.path(), std::vector<RowResult>{}), IsEmpty());
  EXPECT_THAT(write_plots(dir.path(), std::vector<RowResult>{result_for({2, 4, 25}, {})}),
              IsEmpty());
}

TEST(ExperimentPlots, SaysHowToInstallAMissingGnuplot) {
  const test::TempDir dir;
  const PathOverride path(dir.path().string());
  EXPECT_FALSE(plots_available());
  EXPECT_EQ(plot_error(dir.path() / "plots", sample_results()),
            "gnuplot not found; install gnuplot-nox (scripts/setup does)");
  EXPECT_FALSE(fs::exists(dir.path() / "plots"));
}

TEST(ExperimentPlots, ReportsAFailingGnuplotAndLeavesNothingBehind) {
  const test::TempDir dir;
  const fs::path bin = dir.path() / "bin";
  fs::create_directory(bin);
  install_fake_gnuplot(bin, "echo 'line 3: something broke' >&2\nexit 3");
  const PathOverride path(bin.string());
  EXPECT_TRUE(plots_available());
  const fs::path plots = dir.path() / "plots";
  EXPECT_EQ(plot_error(plots, sample_results()),
            "gnuplot exited with status 3: line 3: something broke");
  EXPECT_THAT(names_in(plots), IsEmpty());
}

TEST(ExperimentPlots, RefusesAGnuplotThatDrewNothing) {
  const test::TempDir dir;
  const fs::path bin = dir.path() / "bin";
  fs::create_directory(bin);
  install_fake_gnuplot(bin, "exit 0");
  const PathOverride path(bin.string());
  const fs::path plots = dir.path() / "plots";
  EXPECT_THAT(plot_error(plots, sample_results()),
              HasSubstr("gnuplot finished without drawing the plot"));
  EXPECT_THAT(names_in(plots), IsEmpty());
}

// gnuplot exits 0 when its PNG could not be written whole (a full disk): a PNG without its end
// chunk is refused, and no earlier plot is replaced by it.
TEST(ExperimentPlots, RefusesAPlotCutShort) {
  const test::TempDir dir;
  const fs::path bin = dir.path() / "bin";
  fs::create_directory(bin);
  // The first 8 bytes of a PNG, its signature, into every file the script names.
  install_fake_gnuplot(bin,
                       "/bin/sed -n \"s/^set output '\\(.*\\)'$/\\1/p\" \"$1\" |\n"
                       "  while read -r png; do printf '\\211PNG\\r\\n\\032\\n' > \"$png\"; done");
  const PathOverride path(bin.string());
  const fs::path plots = dir.path() / "plots";
  EXPECT_THAT(plot_error(plots, sample_results()),
              HasSubstr("-frame-time.png: gnuplot did not draw the whole plot (gnuplot stopped "
                        "at 8 bytes, no PNG end)"));
  EXPECT_THAT(names_in(plots), IsEmpty());
}

}  // namespace
}  // namespace sphys::tools
