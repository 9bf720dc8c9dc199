// Plausible mode's last stage: the bodies still long enough (their still time counted by
// finalize_bodies) that touch no restless body fall asleep.

#include "core/stopwatch.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {

void update_sleep(PassContext& pass) {
  const PhaseClock clock(&pass.world.parallel);
  WorldState& world = pass.world;
  // The bodies that fall asleep stop there, in the store.
  world.sleep_changes.clear();
  pass.stats.islands =
      world.sleep.update(world.detector.contacts(), world.settings.sleep, world.sleep_changes);
  clock.add_to(pass.stats.sleep_ms, pass.stats.sleep_serial_ms);
}

}  // namespace sphys
