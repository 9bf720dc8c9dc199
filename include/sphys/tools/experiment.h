#pragma once

// The paper's evaluation (§5): its eight experiments, its published figures, and the summaries and
// statistics we compute to set ours beside them. Running the rows: sphys/tools/run_experiment.h.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace sphys::tools {

// One experiment: S stacks of N bunnies with sphere-trees of the given depth.
struct ExperimentRow {
  int depth = 2;       // levels including the root
  int stacks = 4;      // S
  int per_stack = 25;  // N
  // "d2-4x25": what --only accepts.
  [[nodiscard]] std::string id() const;
  friend bool operator==(const ExperimentRow&, const ExperimentRow&) = default;
};

// A row of the paper's Table 1.
struct PaperRow {
  ExperimentRow row;
  double contacts_per_frame = 0.0;
  double fps = 0.0;
  double frame_time_sd_ms = 0.0;  // standard deviation of the time to generate a frame. unit: ms
};

// The eight rows in the paper's printed order: d2-4x25, d2-4x50, d3-4x25, d3-4x50, then the same
// for 8x10 and 8x20.
[[nodiscard]] std::span<const PaperRow> paper_table();

// The §5 statistics, as published or as we measure them. Shares are percentages of frame time;
// their standard deviations are across the rows. Correlations are Pearson's r across the rows
// (NaN when fewer than two rows or no spread).
struct ExperimentStatistics {
  double contacts_fps_correlation = 0.0;
  double contacts_frame_sd_correlation = 0.0;
  double detection_share_mean = 0.0;  // unit: %
  double detection_share_sd = 0.0;    // unit: percentage points
  double response_share_mean = 0.0;   // unit: %
  double response_share_sd = 0.0;     // unit: percentage points
  double detection_share_contacts_correlation = 0.0;
  double response_share_contacts_correlation = 0.0;
};
[[nodiscard]] const ExperimentStatistics& paper_statistics();

// What one run of one row measured, frame by frame.
struct FrameSample {
  double step_ms = 0.0;       // the whole physics step (the frame: no rendering here)
  double detection_ms = 0.0;  // broad phase, narrow phase and contacts
  double response_ms = 0.0;
  std::uint32_t contacts = 0;
};

struct RowResult {
  ExperimentRow row;
  std::vector<FrameSample> frames;
  std::string tree_builder;  // e.g. "combined, branching 8"
  std::string ground;        // e.g. "octree of a 16 m box, 5 levels"
  std::uint32_t bodies = 0;
  std::uint32_t bodies_below_plane = 0;  // centre of mass below y = 0 at the end
  float lowest_center_y = 0.0f;          // lowest centre of mass at the end. unit: m
  float deepest_penetration = 0.0f;      // largest contact depth over the run. unit: m
  bool stopped_non_finite = false;
};

struct RowSummary {
  ExperimentRow row;
  double contacts_per_frame = 0.0;  // mean over frames
  double mean_frame_ms = 0.0;       // unit: ms
  double fps = 0.0;                 // 1000 / mean_frame_ms: physics only
  double frame_time_sd_ms = 0.0;    // sample standard deviation over frames. unit: ms
  double detection_share = 0.0;     // total detection time / total frame time. unit: %
  double response_share = 0.0;      // unit: %
};

// Figures a run cannot give are NaN: all of them without frames, the sd with fewer than two, FPS
// and shares when no time was measured.
[[nodiscard]] RowSummary summarize(const RowResult& result);
[[nodiscard]] ExperimentStatistics compute_statistics(std::span<const RowSummary> rows);
// Pearson's correlation coefficient; NaN when sizes differ, fewer than two values, or either
// sequence has no spread.
[[nodiscard]] double pearson(std::span<const double> x, std::span<const double> y);

// Table 1 with the paper's figures beside ours, then the §5 statistics, as plain text for a
// terminal.
[[nodiscard]] std::string comparison_text(std::span<const RowResult> results);
// The same as a Markdown report (with the machine description and notes), for report.md. It links
// the plots by file name (plot_files), so it belongs in the directory given to write_plots.
[[nodiscard]] std::string markdown_report(std::span<const RowResult> results,
                                          const std::string& machine);
// Per-frame CSV of one row: frame (from 1), step_ms, detection_ms, response_ms, contacts.
void write_row_csv(const std::filesystem::path& path, const RowResult& result);
// The PNGs write_plots draws for a row, by file name: "<id>-frame-time.png", "<id>-contacts.png".
struct PlotFiles {
  std::string frame_time;  // step time per frame
  std::string contacts;    // contacts per frame
};
[[nodiscard]] PlotFiles plot_files(const ExperimentRow& row);
// Whether write_plots can draw: gnuplot is on PATH.
[[nodiscard]] bool plots_available();
// PNG plots via gnuplot (frame time and contacts per frame for each row with frames) into
// `directory`, created if missing; returns the files written. Each PNG is written whole or not at
// all. Throws sphys::Error when gnuplot is missing or fails.
std::vector<std::filesystem::path> write_plots(const std::filesystem::path& directory,
                                               std::span<const RowResult> results);

}  // namespace sphys::tools
