#include "sphys/tools/experiment_json.h"

#include <nlohmann/json.hpp>

#include "io/json_number.h"

namespace sphys::tools {

std::string row_result_json(const RowResult& result) {
  const RowSummary summary = summarize(result);
  const Plausibility& plausible = result.plausibility;
  nlohmann::ordered_json row;
  row["id"] = result.row.id();
  row["depth"] = result.row.depth;
  row["stacks"] = result.row.stacks;
  row["per_stack"] = result.row.per_stack;
  row["frames"] = result.frames.size();
  row["contacts_per_frame"] = summary.contacts_per_frame;
  row["mean_frame_ms"] = summary.mean_frame_ms;
  row["fps"] = summary.fps;
  row["frame_time_sd_ms"] = summary.frame_time_sd_ms;
  row["detection_share_percent"] = summary.detection_share;
  row["response_share_percent"] = summary.response_share;
  row["bodies"] = result.bodies;
  row["bodies_below_plane"] = result.bodies_below_plane;
  row["lowest_center_y_end_m"] = result.lowest_center_y;
  row["deepest_penetration_m"] = plausible.deepest_penetration;
  row["deepest_penetration_frame"] = plausible.deepest_frame;
  row["mean_penetration_m"] = plausible.mean_penetration;
  row["penetrating_frames"] = plausible.penetrating_frames;
  row["movable_bodies"] = plausible.movable_bodies;
  row["bodies_at_rest"] = plausible.bodies_at_rest;
  row["bodies_asleep"] = plausible.bodies_asleep;
  row["bodies_still_moving"] = plausible.movable_bodies - plausible.bodies_at_rest;
  row["all_at_rest_from_frame"] = plausible.all_at_rest_frame
                                      ? nlohmann::ordered_json(*plausible.all_at_rest_frame)
                                      : nlohmann::ordered_json();
  row["jitter_m_per_s"] = plausible.jitter;
  row["final_kinetic_energy_J"] = plausible.final_kinetic_energy;
  row["stopped_non_finite"] = result.stopped_non_finite;
  row["ground"] = result.ground;
  row["tree_builder"] = result.tree_builder;
  return row.dump(2);
}

std::string statistics_json(const ExperimentStatistics& statistics) {
  const ExperimentStatistics& s = statistics;
  const nlohmann::ordered_json json = {
      {"contacts_fps_correlation", number_or_null(s.contacts_fps_correlation)},
      {"contacts_frame_sd_correlation", number_or_null(s.contacts_frame_sd_correlation)},
      {"detection_share_mean_percent", number_or_null(s.detection_share_mean)},
      {"detection_share_sd_points", number_or_null(s.detection_share_sd)},
      {"response_share_mean_percent", number_or_null(s.response_share_mean)},
      {"response_share_sd_points", number_or_null(s.response_share_sd)},
      {"detection_share_contacts_correlation",
       number_or_null(s.detection_share_contacts_correlation)},
      {"response_share_contacts_correlation",
       number_or_null(s.response_share_contacts_correlation)}};
  return json.dump(2);
}

}  // namespace sphys::tools
