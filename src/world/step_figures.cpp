#include <array>
#include <string>

#include "sphys/step_stats.h"

namespace sphys {
namespace {

// A figure read from a member of StepStats (or of its DetectionCounters).
template <auto Member>
constexpr StepFigure figure(std::string_view name, std::string_view unit, bool in_frames_csv) {
  using Value = std::remove_cvref_t<decltype(StepStats{}.*Member)>;
  return {.name = name,
          .unit = unit,
          .count = std::is_integral_v<Value>,
          .in_frames_csv = in_frames_csv,
          .read = [](const StepStats& stats) { return static_cast<double>(stats.*Member); }};
}

constexpr bool kCsv = true;
constexpr bool kNotCsv = false;
using Step = StepStats;
using Detection = DetectionCounters;

constexpr auto kFigures = std::to_array<StepFigure>({
    // frames.csv's columns after the frame and its time, in order.
    figure<&Step::step_ms>("step_ms", "ms", kCsv),
    figure<&Step::broad_phase_ms>("broad_phase_ms", "ms", kCsv),
    figure<&Step::narrow_phase_ms>("narrow_phase_ms", "ms", kCsv),
    figure<&Step::contacts_ms>("contacts_ms", "ms", kCsv),
    figure<&Step::response_ms>("response_ms", "ms", kCsv),
    figure<&Step::integration_ms>("integration_ms", "ms", kCsv),
    figure<&Step::sleep_ms>("sleep_ms", "ms", kCsv),
    figure<&Detection::candidate_pairs>("candidate_pairs", "", kCsv),
    figure<&Detection::sphere_tests>("sphere_tests", "", kCsv),
    figure<&Detection::leaf_pairs>("leaf_pairs", "", kCsv),
    figure<&Step::contacts>("contacts", "", kCsv),
    figure<&Step::impulses>("impulses", "", kCsv),
    figure<&Step::contacts_solved>("contacts_solved", "", kCsv),
    figure<&Step::kinetic_energy>("kinetic_energy", "J", kCsv),
    figure<&Step::deepest_penetration>("deepest_penetration", "m", kCsv),
    figure<&Step::mean_penetration>("mean_penetration", "m", kCsv),
    figure<&Step::bodies_at_rest>("bodies_at_rest", "", kCsv),
    figure<&Step::bodies_asleep>("bodies_asleep", "", kCsv),
    figure<&Step::jitter>("jitter", "m/s", kCsv),
    figure<&Step::warm_started>("warm_started", "", kCsv),
    figure<&Step::islands>("islands", "", kCsv),
    figure<&Step::collision_passes>("collision_passes", "", kCsv),
    figure<&Step::serial_ms>("serial_ms", "ms", kCsv),
    figure<&Step::broad_phase_serial_ms>("broad_phase_serial_ms", "ms", kCsv),
    figure<&Step::narrow_phase_serial_ms>("narrow_phase_serial_ms", "ms", kCsv),
    figure<&Step::contacts_serial_ms>("contacts_serial_ms", "ms", kCsv),
    figure<&Step::response_serial_ms>("response_serial_ms", "ms", kCsv),
    figure<&Step::integration_serial_ms>("integration_serial_ms", "ms", kCsv),
    figure<&Step::sleep_serial_ms>("sleep_serial_ms", "ms", kCsv),
    // The rest.
    {.name = "detection_ms",
     .unit = "ms",
     .read = [](const StepStats& stats) { return stats.detection_ms(); }},
    figure<&Step::bodies>("bodies", "", kNotCsv),
    figure<&Step::response_passes>("response_passes", "", kNotCsv),
    figure<&Step::bounces>("bounces", "", kNotCsv),
    figure<&Detection::pairs_cut_short>("pairs_cut_short", "", kNotCsv),
    figure<&Detection::coincident_centres>("coincident_centres", "", kNotCsv),
    figure<&Detection::descended_pairs>("descended_pairs", "", kNotCsv),
    figure<&Detection::reused_pairs>("reused_pairs", "", kNotCsv),
    figure<&Detection::pairs_deferred>("pairs_deferred", "", kNotCsv),
    figure<&Step::crowded_bodies>("crowded_bodies", "", kNotCsv),
    figure<&Step::movable_bodies>("movable_bodies", "", kNotCsv),
    figure<&Step::penetrating_contacts>("penetrating_contacts", "", kNotCsv),
});

}  // namespace

std::span<const StepFigure> step_figures() { return kFigures; }

std::string frames_csv_column(const StepFigure& figure) {
  std::string unit(figure.unit);
  for (std::size_t slash = unit.find('/'); slash != std::string::npos; slash = unit.find('/')) {
    unit.replace(slash, 1, "_per_");
  }
  std::string column(figure.name);
  if (unit.empty() || column.ends_with("_" + unit)) return column;
  return column + "_" + unit;
}

}  // namespace sphys
