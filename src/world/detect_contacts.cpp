// The detection stage of a collision pass: bounds and the broad phase, the narrow phase and the
// manifolds, all in the detector.

#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {

void add_detection(const WorldState& world, const CollisionStats& detection, StepStats& stats) {
  stats.broad_phase_ms += detection.broad_phase_ms;
  stats.narrow_phase_ms += detection.narrow_phase_ms;
  stats.contacts_ms += detection.contacts_ms;
  stats.broad_phase_serial_ms += detection.broad_phase_serial_ms;
  stats.narrow_phase_serial_ms += detection.narrow_phase_serial_ms;
  stats.contacts_serial_ms += detection.contacts_serial_ms;
  stats += static_cast<const DetectionCounters&>(detection);
  stats.crowded_bodies = std::max(stats.crowded_bodies, detection.crowded_bodies);
  if (!world.settings.plausibility_figures) return;
  const double depth_sum = stats.mean_penetration * stats.penetrating_contacts;
  stats.deepest_penetration = std::max(stats.deepest_penetration, detection.deepest_penetration);
  stats.penetrating_contacts += detection.penetrating_contacts;
  stats.mean_penetration =
      stats.penetrating_contacts > 0
          ? (depth_sum + detection.penetration_sum) / stats.penetrating_contacts
          : 0.0;
}

void detect_contacts(PassContext& pass) {
  WorldState& world = pass.world;
  const CollisionStats& detection = world.detector.detect();
  pass.stats.bodies = detection.bodies;
  add_detection(world, detection, pass.stats);
  if (detection.parted_pairs > 0) world.sleep.parted();
}

}  // namespace sphys
