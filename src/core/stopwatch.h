#pragma once

// The clock the step's phases are timed with, and a phase's serial part: the time it spends
// outside the loops that threads share, which more threads do not shorten.

#include <algorithm>
#include <chrono>

#include "sphys/parallel.h"

namespace sphys {

using StepClock = std::chrono::steady_clock;

// Milliseconds since `since`. unit: ms
[[nodiscard]] inline double elapsed_ms(StepClock::time_point since) {
  return std::chrono::duration<double, std::milli>(StepClock::now() - since).count();
}

// A phase's time. unit: ms
struct PhaseTime {
  double ms = 0.0;         // all of it
  double serial_ms = 0.0;  // outside the threads' loops (Parallel::loop_ms)
};

// Times a phase from its making: its wall-clock time, and that less the time `parallel`'s loops
// took meanwhile (none: all of it is serial).
class PhaseClock {
 public:
  explicit PhaseClock(const Parallel* parallel)
      : parallel_(parallel), start_(StepClock::now()), loops_at_start_(loop_ms()) {}

  [[nodiscard]] PhaseTime elapsed() const {
    const double ms = elapsed_ms(start_);
    return {ms, std::max(0.0, ms - (loop_ms() - loops_at_start_))};
  }
  // Adds the phase's time so far to a figure and its serial twin.
  void add_to(double& ms, double& serial_ms) const {
    const PhaseTime spent = elapsed();
    ms += spent.ms;
    serial_ms += spent.serial_ms;
  }

 private:
  [[nodiscard]] double loop_ms() const { return parallel_ != nullptr ? parallel_->loop_ms() : 0.0; }

  const Parallel* parallel_;
  StepClock::time_point start_;
  double loops_at_start_;  // unit: ms
};

}  // namespace sphys
