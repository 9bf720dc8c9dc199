// Stage 6 of a substep (plausible mode): how long each moving body has been still, and the
// bodies still long enough that touch no restless body and are pressed in no deeper than the
// solver leaves resting contacts fall asleep.

#include <limits>

#include "core/buffers.h"
#include "sphys/world.h"
#include "world/sleep_tracker.h"

namespace sphys {

void World::update_sleep(float dt, StepStats& stats) {
  fill_buffer(speeds_, store_->slots(), 0.0f);
  for (const std::uint32_t i : store_->awake()) speeds_[i] = store_->fastest_point_speed(i);
  // The bodies that fall asleep stop there, in the store.
  sleep_changes_.clear();
  stats.islands = sleep_->update(speeds_, detector_.contacts(), dt, settings_.sleep,
                                 resting_depth(), sleep_changes_);
}

// The soft step's contact springs give under load by design (a heavy pile's bottom contacts
// rest deeper than its top's), so depth does not hold its bodies awake.
float World::resting_depth() const { return std::numeric_limits<float>::infinity(); }

}  // namespace sphys
