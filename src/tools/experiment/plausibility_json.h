#pragma once

// A run's plausibility figures under the names every report gives them (`sphys simulate --json`,
// `sphys experiment --json`, Python's summaries), added in that order to a JSON object.

#include <nlohmann/json.hpp>

#include "sphys/tools/experiment.h"

namespace sphys::tools {

inline void add_plausibility_json(nlohmann::ordered_json& out, const Plausibility& p) {
  out["deepest_penetration_m"] = p.deepest_penetration;
  out["deepest_penetration_frame"] = p.deepest_frame;
  out["mean_penetration_m"] = p.mean_penetration;
  out["penetrating_frames"] = p.penetrating_frames;
  out["movable_bodies"] = p.movable_bodies;
  out["bodies_at_rest"] = p.bodies_at_rest;
  out["bodies_asleep"] = p.bodies_asleep;
  out["bodies_still_moving"] = p.movable_bodies - p.bodies_at_rest;
  out["all_at_rest_from_frame"] =
      p.all_at_rest_frame ? nlohmann::ordered_json(*p.all_at_rest_frame) : nlohmann::ordered_json();
  out["jitter_m_per_s"] = p.jitter;
  out["final_kinetic_energy_J"] = p.final_kinetic_energy;
}

}  // namespace sphys::tools
