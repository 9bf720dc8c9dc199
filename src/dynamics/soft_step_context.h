#pragma once

// What the soft step works with in one collision pass, made once a pass (as Box2D v3's
// b2StepContext): its substeps, gravity, the contacts' springs, the lanes' settings and the
// threads.

#include <cstdint>

#include "dynamics/contact_lanes.h"
#include "sphys/math.h"
#include "sphys/parallel.h"
#include "sphys/solver_settings.h"

namespace sphys {

struct SoftStepContext {
  // A collision pass of `pass_dt` (unit: s) in `pass_substeps` equal substeps, under `settings`
  // and `step_gravity` (unit: m/s²), solved on `threads`.
  SoftStepContext(const SolverSettings& settings, const Vec3& step_gravity, float pass_dt,
                  std::uint32_t pass_substeps, const Parallel& threads);

  std::uint32_t substeps = 1;
  float substep_dt = 0.0f;      // unit: s
  Vec3 gravity = Vec3::Zero();  // unit: m/s²
  bool warm_starting = true;
  // The springs' a2 = h ω (2ζ + h ω) (dimensionless) and bias speed per metre of penetration
  // (unit: 1/s), between two moving bodies and against an immovable one.
  float spring_moving = 0.0f;
  float spring_immovable = 0.0f;
  float bias_rate_moving = 0.0f;
  float bias_rate_immovable = 0.0f;
  LaneSettings lanes;  // the passes' settings
  const Parallel& parallel;
};

}  // namespace sphys
