// Stage 6 of a substep (plausible mode): how long each moving body has been still, and the
// bodies still long enough that touch no restless body fall asleep.

#include "collision/collision_detector.h"
#include "core/stopwatch.h"
#include "sphys/world.h"
#include "world/sleep_tracker.h"

namespace sphys {

void World::update_sleep(float dt, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  // The bodies that fall asleep stop there, in the store.
  sleep_changes_.clear();
  stats.islands =
      sleep_->update(detector_->contacts(), dt, settings_.sleep, *parallel_, sleep_changes_);
  stats.sleep_ms += elapsed_ms(start);
}

}  // namespace sphys
