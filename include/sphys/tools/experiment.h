#pragma once

// The paper's evaluation (§5): its eight experiments, its published figures, and the summaries and
// statistics we compute to set ours beside them. Running the rows: sphys/tools/run_experiment.h.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sphys/step_stats.h"
#include "sphys/world.h"

namespace sphys::tools {

// The size of the frames `sphys experiment` draws (Figure 2 and --render). The paper does not
// say its window's size; we presume 640 × 480. unit: pixels
inline constexpr int kDrawnFrameWidth = 640;
inline constexpr int kDrawnFrameHeight = 480;  // unit: pixels
// `sphys experiment --render` draws and times every this many-th frame after its step (88 of the
// paper's 880): drawing all 7,040 frames in software takes about ten minutes on two cores, the
// physics seconds; the sample's mean drawing time stands for the frames not drawn. `--render-all`
// draws every frame. unit: frames
inline constexpr std::uint32_t kRenderSampleStride = 10;

// One experiment: S stacks of N bunnies with sphere-trees of the given depth.
struct ExperimentRow {
  int depth = 2;       // levels including the root
  int stacks = 4;      // S
  int per_stack = 25;  // N
  // "d2-4x25": what --only accepts.
  [[nodiscard]] std::string id() const;
  // The same depth, stacks and bodies per stack.
  friend bool operator==(const ExperimentRow&, const ExperimentRow&) = default;
};

// A row of the paper's Table 1.
struct PaperRow {
  ExperimentRow row;                // the experiment
  double contacts_per_frame = 0.0;  // mean over the frames
  double fps = 0.0;                 // frames per second as published. unit: 1/s
  double frame_time_sd_ms = 0.0;    // standard deviation of the time to generate a frame. unit: ms
};

// The eight rows in the paper's printed order: d2-4x25, d2-4x50, d3-4x25, d3-4x50, then the same
// for 8x10 and 8x20.
[[nodiscard]] std::span<const PaperRow> paper_table();

// The §5 statistics, as published or as we measure them. Shares are percentages of frame time;
// their standard deviations are across the rows. Correlations are Pearson's r across the rows
// (NaN when fewer than two rows or no spread).
struct ExperimentStatistics {
  double contacts_fps_correlation = 0.0;              // contacts per frame against FPS
  double contacts_frame_sd_correlation = 0.0;         // contacts per frame against frame time sd
  double detection_share_mean = 0.0;                  // unit: %
  double detection_share_sd = 0.0;                    // unit: percentage points
  double response_share_mean = 0.0;                   // unit: %
  double response_share_sd = 0.0;                     // unit: percentage points
  double detection_share_contacts_correlation = 0.0;  // detection share against contacts
  double response_share_contacts_correlation = 0.0;   // response share against contacts
};
// The statistics as the paper prints them (how we read its misprints: src/tools/experiment/
// paper_table.cpp).
[[nodiscard]] const ExperimentStatistics& paper_statistics();

// What one run of one row measured, frame by frame.
struct FrameSample {
  double step_ms = 0.0;        // the whole physics step
  double detection_ms = 0.0;   // broad phase, narrow phase and contacts
  double response_ms = 0.0;    // the response's impulses (StepStats::response_ms). unit: ms
  std::uint32_t contacts = 0;  // the response's contacts in the step (StepStats::contacts)
  // Drawing the frame after the step (`sphys experiment --render`); 0 when it was not drawn.
  // unit: ms
  double render_ms = 0.0;
};

// How far bodies sank into one another over a run and whether they came to rest: what makes an
// animation look plausible, from the world's StepStats frame by frame.
struct Plausibility {
  float deepest_penetration = 0.0f;  // largest overlap of two leaf spheres. unit: m
  int deepest_frame = 0;             // the frame (from 1) of that overlap; 0: none overlapped
  // Mean of StepStats::mean_penetration over the frames with overlapping leaf pairs; 0 when none
  // had any. unit: m
  double mean_penetration = 0.0;
  int penetrating_frames = 0;  // frames with overlapping leaf pairs
  // At the end of the run: bodies that are not static, and those at rest or asleep among them.
  std::uint32_t movable_bodies = 0;
  std::uint32_t bodies_at_rest = 0;  // as StepStats::bodies_at_rest counts them
  std::uint32_t bodies_asleep = 0;   // as StepStats::bodies_asleep counts them
  // The first frame (from 1) from which every moving body stayed at rest to the end; unset when
  // some body still moved in the last frame.
  std::optional<int> all_at_rest_frame;
  // Mean of StepStats::jitter over the last kJitterFrames frames (all, when fewer). unit: m/s
  double jitter = 0.0;
  double final_kinetic_energy = 0.0;  // unit: J
};

// The frames at the end of a run whose jitter is averaged: one second at 60 frames per second,
// long enough to smooth single frames, short enough to leave out the settling.
inline constexpr std::size_t kJitterFrames = 60;

// Gathers a run's Plausibility from the StepStats of each frame, in order.
class PlausibilityMeter {
 public:
  // Takes the next frame's figures.
  void add(const StepStats& stats);
  // The figures of the frames added so far.
  [[nodiscard]] Plausibility result() const;

 private:
  Plausibility figures_;
  int frames_ = 0;
  double penetration_sum_ = 0.0;  // of StepStats::mean_penetration. unit: m
  std::vector<double> jitter_;    // per frame, the last kJitterFrames. unit: m/s
  std::size_t next_jitter_ = 0;   // where the next frame's jitter goes in jitter_
};

// How the rows are run: the paper's response unless asked otherwise.
struct ExperimentMode {
  ResponseMode response = ResponseMode::kPaper;  // the worlds' response mode
  // The contacts plausible mode responds to; paper mode responds to every leaf-pair contact.
  ContactSet contacts = SolverSettings{}.contacts;
};

// What running one row gave: its frames, its world's description and its end state.
struct RowResult {
  ExperimentRow row;                     // the row run
  std::vector<FrameSample> frames;       // one per frame stepped, in order
  std::string tree_builder;              // e.g. "combined, branching 8"
  std::string ground;                    // e.g. "octree of a 16 m box, 5 levels"
  std::uint32_t bodies = 0;              // the scene's bodies
  std::uint32_t bodies_below_plane = 0;  // centre of mass below y = 0 at the end
  float lowest_center_y = 0.0f;          // lowest centre of mass at the end. unit: m
  Plausibility plausibility;             // over the frames stepped
  bool stopped_non_finite = false;       // a body's state stopped being finite: the run ended there
  // Figure 2: the first and the last frame drawn (file names beside the report), or why they
  // could not be ("" when they were, or were not asked for).
  std::string first_picture;
  std::string last_picture;      // the last frame's file name
  std::string pictures_missing;  // why they could not be drawn; "" when drawn or not asked for
  // Frames timed with their drawing: every this many-th one (the frames at 1-based indices
  // n, 2n, ...; 1 is every frame), 0 when none were. unit: frames
  std::uint32_t drawn_every = 0;
};

// One row's figures as Table 1 gives them, from its frames (summarize).
struct RowSummary {
  ExperimentRow row;                // the row run
  double contacts_per_frame = 0.0;  // mean over frames
  double mean_frame_ms = 0.0;       // unit: ms
  double fps = 0.0;                 // 1000 / mean_frame_ms: physics only
  double frame_time_sd_ms = 0.0;    // sample standard deviation over frames. unit: ms
  double detection_share = 0.0;     // total detection time / total frame time. unit: %
  double response_share = 0.0;      // unit: %
  // With frames drawn (--render, --render-all): frames per second counting the drawing as the
  // paper's frames did, and the drawing's share of that frame time (unit: %), the frames not drawn
  // counted at the drawn ones' mean. NaN when none was drawn.
  std::uint32_t frames_drawn = 0;  // the frames timed with their drawing
  double fps_with_drawing = 0.0;   // unit: 1/s
  double drawing_share = 0.0;      // unit: %
  // Detection's and response's shares of the drawn frame's time, the paper's basis. unit: %
  double detection_share_drawn = 0.0;
  double response_share_drawn = 0.0;  // unit: %
};

// Figures a run cannot give are NaN: all of them without frames, the sd with fewer than two, FPS
// and shares when no time was measured.
[[nodiscard]] RowSummary summarize(const RowResult& result);
// The §5 statistics across the rows' summaries (means, sample sds and correlations; NaN where
// they cannot be computed).
[[nodiscard]] ExperimentStatistics compute_statistics(std::span<const RowSummary> rows);
// Pearson's correlation coefficient; NaN when sizes differ, fewer than two values, or either
// sequence has no spread.
[[nodiscard]] double pearson(std::span<const double> x, std::span<const double> y);

// Table 1 with the paper's figures beside ours, then the §5 statistics, as plain text for a
// terminal; the first lines say how the rows were run.
[[nodiscard]] std::string comparison_text(std::span<const RowResult> results,
                                          const ExperimentMode& mode);
// The same as a Markdown report (with the machine description and notes), for report.md. It links
// by file name the plots write_plots drew (`plots`, as it returned them; none: no plots section),
// so it belongs in the directory given to write_plots.
[[nodiscard]] std::string markdown_report(std::span<const RowResult> results,
                                          const std::string& machine, const ExperimentMode& mode,
                                          std::span<const std::filesystem::path> plots);
// Per-frame CSV of one row: frame (from 1), step_ms, detection_ms, response_ms, contacts,
// render_ms.
void write_row_csv(const std::filesystem::path& path, const RowResult& result);
// The PNGs write_plots draws for a row, by file name: "<id>-frame-time.png", "<id>-contacts.png".
struct PlotFiles {
  std::string frame_time;  // step time per frame
  std::string contacts;    // contacts per frame
};
// The file names write_plots gives the row's plots.
[[nodiscard]] PlotFiles plot_files(const ExperimentRow& row);
// Whether write_plots can draw: gnuplot is on PATH.
[[nodiscard]] bool plots_available();
// PNG plots via gnuplot (frame time and contacts per frame for each row with frames) into
// `directory`, created if missing; returns the files written. Each PNG is written whole or not at
// all. Throws sphys::Error when gnuplot is missing or fails.
std::vector<std::filesystem::path> write_plots(const std::filesystem::path& directory,
                                               std::span<const RowResult> results);

}  // namespace sphys::tools
