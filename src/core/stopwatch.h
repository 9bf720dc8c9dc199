#pragma once

// The clock the step's phases are timed with.

#include <chrono>

namespace sphys {

using StepClock = std::chrono::steady_clock;

// Milliseconds since `since`. unit: ms
[[nodiscard]] inline double elapsed_ms(StepClock::time_point since) {
  return std::chrono::duration<double, std::milli>(StepClock::now() - since).count();
}

}  // namespace sphys
