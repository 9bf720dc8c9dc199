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
using S = StepStats;
using D = DetectionCounters;

constexpr auto kFigures = std::to_array<StepFigure>({
    // frames.csv's columns after the frame and its time, in order.
    figure<&S::step_ms>("step_ms", "ms", kCsv),
    figure<&S::broad_phase_ms>("broad_phase_ms", "ms", kCsv),
    figure<&S::narrow_phase_ms>("narrow_phase_ms", "ms", kCsv),
    figure<&S::contacts_ms>("contacts_ms", "ms", kCsv),
    figure<&S::response_ms>("response_ms", "ms", kCsv),
    figure<&S::integration_ms>("integration_ms", "ms", kCsv),
    figure<&S::sleep_ms>("sleep_ms", "ms", kCsv),
    figure<&D::candidate_pairs>("candidate_pairs", "", kCsv),
    figure<&D::sphere_tests>("sphere_tests", "", kCsv),
    figure<&D::leaf_pairs>("leaf_pairs", "", kCsv),
    figure<&S::contacts>("contacts", "", kCsv),
    figure<&S::impulses>("impulses", "", kCsv),
    figure<&S::contacts_solved>("contacts_solved", "", kCsv),
    figure<&S::kinetic_energy>("kinetic_energy", "J", kCsv),
    figure<&S::deepest_penetration>("deepest_penetration", "m", kCsv),
    figure<&S::mean_penetration>("mean_penetration", "m", kCsv),
    figure<&S::bodies_at_rest>("bodies_at_rest", "", kCsv),
    figure<&S::bodies_asleep>("bodies_asleep", "", kCsv),
    figure<&S::jitter>("jitter", "m/s", kCsv),
    figure<&S::warm_started>("warm_started", "", kCsv),
    figure<&S::islands>("islands", "", kCsv),
    figure<&S::collision_passes>("collision_passes", "", kCsv),
    // The rest.
    {.name = "detection_ms",
     .unit = "ms",
     .read = [](const StepStats& stats) { return stats.detection_ms(); }},
    figure<&S::bodies>("bodies", "", kNotCsv),
    figure<&S::response_passes>("response_passes", "", kNotCsv),
    figure<&S::bounces>("bounces", "", kNotCsv),
    figure<&D::pairs_cut_short>("pairs_cut_short", "", kNotCsv),
    figure<&D::coincident_centres>("coincident_centres", "", kNotCsv),
    figure<&D::descended_pairs>("descended_pairs", "", kNotCsv),
    figure<&D::reused_pairs>("reused_pairs", "", kNotCsv),
    figure<&D::pairs_deferred>("pairs_deferred", "", kNotCsv),
    figure<&S::crowded_bodies>("crowded_bodies", "", kNotCsv),
    figure<&S::movable_bodies>("movable_bodies", "", kNotCsv),
    figure<&S::penetrating_contacts>("penetrating_contacts", "", kNotCsv),
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
