// Stages 2 and 3 of a substep: bounds and the broad phase, the narrow phase and the manifolds
// (all in the detector), then waking the sleeping islands that moving bodies disturb, with the
// narrow phase of their pairs alone.

#include "core/stopwatch.h"
#include "sphys/world.h"
#include "world/sleep_tracker.h"

namespace sphys {

void World::add_detection(const CollisionStats& detection, StepStats& stats) const {
  stats.broad_phase_ms += detection.broad_phase_ms;
  stats.narrow_phase_ms += detection.narrow_phase_ms;
  stats.contacts_ms += detection.contacts_ms;
  stats += static_cast<const DetectionCounters&>(detection);
  stats.crowded_bodies = std::max(stats.crowded_bodies, detection.crowded_bodies);
  if (!settings_.plausibility_figures) return;
  const double depth_sum = stats.mean_penetration * stats.penetrating_contacts;
  stats.deepest_penetration = std::max(stats.deepest_penetration, detection.deepest_penetration);
  stats.penetrating_contacts += detection.penetrating_contacts;
  stats.mean_penetration =
      stats.penetrating_contacts > 0
          ? (depth_sum + detection.penetration_sum) / stats.penetrating_contacts
          : 0.0;
}

void World::detect_contacts(StepStats& stats) {
  const CollisionStats& detection = detector_->detect();
  stats.bodies = detection.bodies;
  add_detection(detection, stats);
  if (detection.parted_pairs > 0) sleep_->parted();
}

// The detector passed over the pairs of sleeping bodies: without their contacts a blow on a
// sleeping pile would pass through its top body unopposed. So the sleeping bodies that a moving
// body touches wake, and their pairs get their narrow phase now, once; a woken body that moves
// wakes those it touches in turn, until nothing more wakes. Then the islands that this substep's
// contacts join merge (they split once a step, World::step).
void World::wake_touched(float dt, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  double woken_detection_ms = 0.0;  // counted in the narrow phase's and contacts' times
  for (;;) {
    sleep_changes_.clear();
    sleep_->wake_disturbed(detector_->contacts(), settings_.sleep, sleep_changes_);
    if (sleep_changes_.empty()) break;
    // This substep's gravity, as the bodies awake in stage 1 had: without it the warm start,
    // the impulses that held them against gravity when they fell asleep, threw them up at
    // g dt, and a woken heap was restless again for a whole sleep time.
    // A sleeping body is at rest, so its motion is finite.
    for (const std::uint32_t body : sleep_changes_) {
      static_cast<void>(integrate_velocity(body, dt, true));
    }
    const CollisionStats& woken = detector_->detect_woken();
    woken_detection_ms += woken.narrow_phase_ms + woken.contacts_ms;
    add_detection(woken, stats);
    if (woken.parted_pairs > 0) sleep_->parted();
  }
  sleep_->link_islands(detector_->contacts());
  stats.sleep_ms += elapsed_ms(start) - woken_detection_ms;
}

}  // namespace sphys
