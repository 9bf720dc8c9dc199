#include "sphys/tools/run_summary.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "experiment/plausibility_json.h"
#include "io/json_number.h"
#include "sphys/tools/median.h"
#include "sphys/tools/overlap.h"

namespace sphys::tools {
namespace {

// The longest bounding-box side of the largest body, the yardstick of penetrations. unit: m
double largest_body_size(const SimulationSetup& setup) {
  double size = 0.0;
  for (const BodyShape& shape : setup.shapes) {
    size = std::max(size, shape.body_mesh->bounds().sizes().maxCoeff());
  }
  return size;
}

// The state of the bodies at the end of the run, and the lowest any went (`run_lowest`, m).
void add_end_state(nlohmann::ordered_json& summary, const Scene& scene,
                   const SimulationSetup& setup, const Plausibility& plausible, float run_lowest) {
  const double size = largest_body_size(setup);
  const auto percent = [size](double depth) {
    return number_or_null(size > 0.0 ? 100.0 * depth / size : std::nan(""));
  };
  summary["largest_body_size_m"] = size;
  add_plausibility_json(summary, plausible);
  summary["deepest_penetration_percent_of_size"] = percent(plausible.deepest_penetration);
  summary["mean_penetration_percent_of_size"] = percent(plausible.mean_penetration);
  const std::optional<int> settled = plausible.all_at_rest_frame;
  summary["all_at_rest_from_s"] =
      number_or_null(settled ? *settled * scene.time_step : std::nan(""));
  std::uint32_t below = 0;
  float lowest = std::numeric_limits<float>::infinity();
  for (const BodyId body : setup.bodies) {
    const float y = setup.world->body(body).pose.translation.y();
    lowest = std::min(lowest, y);
    if (scene.ground.kind != GroundSpec::Kind::kNone &&
        !(y >= static_cast<float>(scene.ground.height))) {
      ++below;
    }
  }
  // The world does not test bodies asleep together against each other, so StepStats says
  // nothing of a sleeping pile: counted afresh over every pair.
  const std::optional<float> plane =
      scene.ground.kind == GroundSpec::Kind::kPlane
          ? std::optional<float>(static_cast<float>(scene.ground.height))
          : std::nullopt;
  const Overlap end_overlap = deepest_overlap(setup, plane);
  summary["end_overlap_m"] = end_overlap.depth;
  summary["end_overlap_percent_of_size"] = percent(end_overlap.depth);
  summary["bodies_below_ground"] = below;
  summary["lowest_center_y_end_m"] = number_or_null(lowest);
  summary["lowest_center_y_run_m"] = number_or_null(std::min(lowest, run_lowest));
}

}  // namespace

void RunTotals::add(const StepStats& s, const SimulationSetup& setup) {
  if (phases.empty()) {
    for (const StepFigure& figure : step_figures()) {
      if (figure.in_frames_csv && figure.unit == "ms" && figure.name != "step_ms") {
        phases.emplace_back(&figure, 0.0);
      }
    }
  }
  step_ms.push_back(s.step_ms);
  for (auto& [figure, sum] : phases) sum += figure->read(s);
  step += s.step_ms;
  contacts += s.contacts;
  max_contacts = std::max(max_contacts, s.contacts);
  collision_passes += s.collision_passes;
  max_collision_passes = std::max(max_collision_passes, s.collision_passes);
  plausibility.add(s);
  for (const BodyId body : setup.bodies) {
    lowest_center_y = std::min(lowest_center_y, setup.world->body(body).pose.translation.y());
  }
}

std::string run_summary_json(const Scene& scene, const SimulationSetup& setup,
                             const RunTotals& totals) {
  const double frames = static_cast<double>(totals.step_ms.size());
  const double mean_ms = totals.step / frames;
  nlohmann::ordered_json summary;
  summary["scene"] = scene.name;
  summary["bodies"] = setup.bodies.size();
  summary["sphere_trees"] = setup.shapes.empty() ? "" : setup.shapes.front().tree_source;
  summary["response"] = response_mode_name(scene.response);
  summary["contact_set"] = contact_set_name(scene.solver.contacts);
  summary["solver_lanes"] = solver_lanes_name(setup.world->solver_lanes());
  summary["collision_passes"] = scene.collision_passes;
  summary["max_collision_passes"] = scene.max_collision_passes;
  summary["collision_passes_per_frame"] = {{"mean", totals.collision_passes / frames},
                                           {"max", totals.max_collision_passes}};
  summary["frames"] = totals.step_ms.size();
  summary["time_step_s"] = scene.time_step;
  summary["wall_s"] = totals.wall_s;
  summary["steps_per_s"] = 1000.0 / mean_ms;
  summary["step_ms"] = {{"mean", mean_ms}, {"median", median(totals.step_ms)}};
  summary["contacts_per_frame"] = {{"mean", totals.contacts / frames},
                                   {"max", totals.max_contacts}};
  // Per phase, named as its figure less "_ms"; the serial times apart, named as their phase, the
  // whole step's as "step": the share of the step that more threads would not shorten.
  nlohmann::ordered_json shares = nlohmann::ordered_json::object();
  nlohmann::ordered_json serial_shares = {{"step", nullptr}};
  for (const auto& [figure, sum] : totals.phases) {
    std::string name(figure->name);
    if (name == "serial_ms") {
      serial_shares["step"] = totals.share(sum);
    } else if (name.ends_with("_serial_ms")) {
      name.resize(name.size() - std::string_view("_serial_ms").size());
      serial_shares[name] = totals.share(sum);
    } else {
      name.resize(name.size() - std::string_view("_ms").size());
      shares[name] = totals.share(sum);
    }
  }
  summary["time_share_percent"] = shares;
  summary["serial_share_percent"] = serial_shares;
  add_end_state(summary, scene, setup, totals.plausibility.result(), totals.lowest_center_y);
  return summary.dump(2);
}

std::string non_finite_message(const SimulationSetup& setup, std::uint32_t world_index, int frame) {
  const BodyId id = setup.world->id_of(world_index);
  const auto found = std::find(setup.bodies.begin(), setup.bodies.end(), id);
  const auto body = static_cast<std::size_t>(found - setup.bodies.begin());
  const RigidBody& state = setup.world->body(id);
  char detail[256];
  std::snprintf(detail, sizeof detail,
                "position (%g, %g, %g), velocity (%g, %g, %g), angular velocity (%g, %g, %g)",
                state.pose.translation.x(), state.pose.translation.y(), state.pose.translation.z(),
                state.linear_velocity.x(), state.linear_velocity.y(), state.linear_velocity.z(),
                state.angular_velocity.x(), state.angular_velocity.y(), state.angular_velocity.z());
  return "the simulation went non-finite: body " + std::to_string(body) + " (/bodies/" +
         std::to_string(body) + ") at frame " + std::to_string(frame) + ": " + detail;
}

}  // namespace sphys::tools
