// Stage 6 of a substep (plausible mode): how long each moving body has been still, and the
// bodies still long enough that touch no restless body fall asleep.

#include "core/buffers.h"
#include "core/stopwatch.h"
#include "sphys/world.h"
#include "world/sleep_tracker.h"

namespace sphys {

void World::update_sleep(float dt, StepStats& stats) {
  const StepClock::time_point start = StepClock::now();
  fill_buffer(speeds_, store_->slots(), 0.0f);
  for (const std::uint32_t i : store_->awake()) speeds_[i] = store_->fastest_point_speed(i);
  // The bodies that fall asleep stop there, in the store.
  sleep_changes_.clear();
  stats.islands =
      sleep_->update(speeds_, detector_.contacts(), dt, settings_.sleep, sleep_changes_);
  stats.sleep_ms += elapsed_ms(start);
}

}  // namespace sphys
