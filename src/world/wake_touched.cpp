// The detector passed over the pairs of sleeping bodies: without their contacts a blow on a
// sleeping pile would pass through its top body unopposed. So the sleeping bodies that a moving
// body touches wake, and their pairs get their narrow phase now, once; a woken body that moves
// wakes those it touches in turn, until nothing more wakes. Then the islands that this pass's
// contacts join merge (they split once a step, plausible_pipeline.cpp).

#include <algorithm>

#include "core/stopwatch.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {

void wake_touched(PassContext& pass) {
  WorldState& world = pass.world;
  const PhaseClock clock(&world.parallel);
  // Counted in the narrow phase's and contacts' times. unit: ms
  PhaseTime woken_detection;
  for (;;) {
    world.sleep_changes.clear();
    world.sleep.wake_disturbed(world.detector.contacts(), world.settings.sleep,
                               world.sleep_changes);
    if (world.sleep_changes.empty()) break;
    // This pass's gravity, as the bodies awake at its start had: without it the warm start,
    // the impulses that held them against gravity when they fell asleep, threw them up at
    // g dt, and a woken heap was restless again for a whole sleep time.
    // A sleeping body is at rest, so its motion is finite.
    for (const std::uint32_t body : world.sleep_changes) {
      static_cast<void>(bound_body_motion(world, body, pass.pass_dt));
    }
    const CollisionStats& woken = world.detector.detect_woken();
    woken_detection.ms += woken.narrow_phase_ms + woken.contacts_ms;
    woken_detection.serial_ms += woken.narrow_phase_serial_ms + woken.contacts_serial_ms;
    add_detection(world, woken, pass.stats);
    if (woken.parted_pairs > 0) world.sleep.parted();
  }
  world.sleep.link_islands(world.detector.contacts());
  const PhaseTime spent = clock.elapsed();
  pass.stats.sleep_ms += spent.ms - woken_detection.ms;
  pass.stats.sleep_serial_ms += std::max(0.0, spent.serial_ms - woken_detection.serial_ms);
}

}  // namespace sphys
