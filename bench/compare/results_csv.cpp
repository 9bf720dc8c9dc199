#include "results_csv.h"

#include <limits>

#include "sphys/tools/csv_file.h"
#include "sphys/tools/machine.h"

namespace sphys::compare {
namespace {

using tools::CsvCell;

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();  // a figure that is not there

double number(const std::optional<double>& value) { return value.value_or(kNone); }

}  // namespace

void write_results_csv(const std::filesystem::path& path, const RunDescription& run,
                       const std::vector<SceneRows>& scenes) {
  const std::vector<std::string> columns = {"date",
                                            "cpu",
                                            "hardware_threads",
                                            "build",
                                            "command",
                                            "runs",
                                            "time_limit_s",
                                            "layout",
                                            "depth",
                                            "frames",
                                            "engine",
                                            "fewest_frames_run",
                                            "stopped_at_time_limit",
                                            "median_ms",
                                            "mean_ms",
                                            "reference_engine",
                                            "median_over_reference",
                                            "mean_over_reference",
                                            "ratio_frames",
                                            "mean_us_per_body",
                                            "contacts_per_step",
                                            "deepest_m",
                                            "deepest_last_second_m",
                                            "overlap_at_end_m",
                                            "kinetic_energy_at_end_j",
                                            "moving_at_end",
                                            "bodies",
                                            "joints",
                                            "asleep_at_end",
                                            "below_plane",
                                            "peak_memory_mib",
                                            "largest_joint_gap_m",
                                            "joint_gap_at_end_m",
                                            "largest_tracking_error_rad",
                                            "mean_tracking_error_rad",
                                            "largest_finger_error_m",
                                            "warnings"};
  const tools::Machine machine = tools::this_machine();
  std::vector<std::vector<CsvCell>> rows;
  for (const SceneRows& scene : scenes) {
    for (const EngineRow& row : scene.rows) {
      const RunResult& worst = row.worst;
      std::vector<CsvCell> cells = {run.date,
                                    machine.cpu,
                                    static_cast<double>(machine.hardware_threads),
                                    run.build,
                                    run.command,
                                    static_cast<double>(run.runs),
                                    run.time_limit,
                                    scene.layout,
                                    static_cast<double>(scene.depth),
                                    static_cast<double>(scene.frames),
                                    row.engine};
      // A failed engine has no figures, only its reason, in the last column.
      const auto figure = [&](double value) { return row.ran ? value : kNone; };
      const std::vector<CsvCell> figures = {
          figure(static_cast<double>(row.fewest_frames)),
          figure(row.stopped ? 1.0 : 0.0),
          figure(row.median_ms),
          figure(row.mean_ms),
          scene.reference,
          number(row.median_ratio),
          number(row.mean_ratio),
          figure(static_cast<double>(row.ratio_frames)),
          figure(row.us_per_body),
          figure(row.contacts_per_step),
          figure(static_cast<double>(worst.deepest)),
          figure(static_cast<double>(worst.deepest_last_second)),
          figure(static_cast<double>(worst.end_overlap)),
          figure(worst.kinetic_energy),
          figure(static_cast<double>(worst.moving)),
          figure(static_cast<double>(worst.bodies)),
          figure(static_cast<double>(worst.joints)),
          worst.asleep ? static_cast<double>(*worst.asleep) : kNone,
          figure(static_cast<double>(worst.below)),
          number(worst.peak_memory_mib),
          scene.jointed ? figure(static_cast<double>(worst.largest_gap)) : kNone,
          scene.jointed ? figure(static_cast<double>(worst.largest_gap_at_end)) : kNone,
          scene.robot ? figure(worst.largest_turn_error) : kNone,
          scene.robot ? figure(worst.mean_turn_error) : kNone,
          scene.robot ? figure(worst.largest_slide_error) : kNone};
      cells.insert(cells.end(), figures.begin(), figures.end());
      cells.emplace_back(worst.warnings);
      rows.push_back(std::move(cells));
    }
  }
  tools::write_csv(path, columns, rows);
}

}  // namespace sphys::compare
