// Stage 6 of a substep (plausible mode): how long each moving body has been still, and the
// bodies still long enough that touch no restless body fall asleep.

#include "sphys/world.h"
#include "world/sleep_tracker.h"

namespace sphys {

void World::update_sleep(float dt, StepStats& stats) {
  speeds_.assign(bodies_.size(), 0.0f);
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    if (moving_[i] != 0) speeds_[i] = fastest_point_speed(i);
  }
  sleep_changes_.clear();
  stats.islands =
      sleep_->update(speeds_, dynamic_, detector_.contacts(), dt, settings_.sleep, sleep_changes_);
  for (const std::uint32_t body : sleep_changes_) {
    bodies_[body].linear_velocity.setZero();
    bodies_[body].angular_velocity.setZero();
    detector_.set_asleep({body}, true);
  }
}

}  // namespace sphys
