#include "sphys/tools/experiment_json.h"

#include <nlohmann/json.hpp>

#include "experiment/plausibility_json.h"
#include "io/json_number.h"

namespace sphys::tools {

std::string row_result_json(const RowResult& result) {
  const RowSummary summary = summarize(result);
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
  // With frames drawn (--render, --render-all); null otherwise.
  row["frames_drawn"] = summary.frames_drawn;
  row["fps_with_drawing"] = number_or_null(summary.fps_with_drawing);
  row["drawing_share_percent"] = number_or_null(summary.drawing_share);
  row["detection_share_of_drawn_frame_percent"] = number_or_null(summary.detection_share_drawn);
  row["response_share_of_drawn_frame_percent"] = number_or_null(summary.response_share_drawn);
  row["bodies"] = result.bodies;
  row["bodies_below_plane"] = result.bodies_below_plane;
  row["lowest_center_y_end_m"] = result.lowest_center_y;
  add_plausibility_json(row, result.plausibility);
  row["stopped_non_finite"] = result.stopped_non_finite;
  row["ground"] = result.ground;
  row["tree_builder"] = result.tree_builder;
  // Figure 2: the first and last frame's PNGs beside the report, or why there are none.
  row["first_picture"] = result.first_picture;
  row["last_picture"] = result.last_picture;
  row["pictures_missing"] = result.pictures_missing;
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
