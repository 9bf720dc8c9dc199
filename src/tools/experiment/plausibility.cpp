#include <numeric>

#include "sphys/tools/experiment.h"

namespace sphys::tools {

void PlausibilityMeter::add(const StepStats& stats) {
  ++frames_;
  if (stats.deepest_penetration > figures_.deepest_penetration) {
    figures_.deepest_penetration = stats.deepest_penetration;
    figures_.deepest_frame = frames_;
  }
  // A frame without overlaps has a mean of 0 that would only dilute the depth of those with.
  if (stats.penetrating_contacts > 0) {
    penetration_sum_ += stats.mean_penetration;
    ++figures_.penetrating_frames;
  }
  figures_.movable_bodies = stats.movable_bodies;
  figures_.bodies_at_rest = stats.bodies_at_rest;
  figures_.bodies_asleep = stats.bodies_asleep;
  figures_.final_kinetic_energy = stats.kinetic_energy;
  if (stats.bodies_at_rest < stats.movable_bodies) {
    figures_.all_at_rest_frame.reset();
  } else if (!figures_.all_at_rest_frame) {
    figures_.all_at_rest_frame = frames_;
  }
  // The last kJitterFrames frames, oldest overwritten, so that a long run needs no more memory.
  if (jitter_.size() < kJitterFrames) {
    jitter_.push_back(stats.jitter);
  } else {
    jitter_[next_jitter_] = stats.jitter;
  }
  next_jitter_ = (next_jitter_ + 1) % kJitterFrames;
}

Plausibility PlausibilityMeter::result() const {
  Plausibility figures = figures_;
  if (figures.penetrating_frames > 0) {
    figures.mean_penetration = penetration_sum_ / figures.penetrating_frames;
  }
  if (!jitter_.empty()) {
    figures.jitter =
        std::accumulate(jitter_.begin(), jitter_.end(), 0.0) / static_cast<double>(jitter_.size());
  }
  return figures;
}

}  // namespace sphys::tools
