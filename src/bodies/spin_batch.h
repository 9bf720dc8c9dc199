#pragma once

// Four bodies' turns in double lanes: what integrate_positions_keeping_spin (rigid_body.cpp)
// hands its kernel and gets back. Plain arrays and no Eigen: the AVX2 kernel's file must share no
// inline function with the rest of the library (spin_lanes_avx2.cpp).

#include <cstdint>

#include "core/simd_double.h"
#include "sphys/solver_settings.h"

namespace sphys {

// Each array holds one number of the four bodies, body i in lane i; a body's 3 × 3 matrices are
// column-major (element r + 3 c is row r, column c), its quaternion x, y, z, w.
struct alignas(32) SpinBatch {
  // In.
  double rotation[4][kDoubleLanes];          // orientation at the substep's start
  double angular_velocity[3][kDoubleLanes];  // world frame. unit: rad/s
  double inertia[9][kDoubleLanes];           // body frame. unit: kg·m²
  double inverse_inertia[9][kDoubleLanes];   // body frame. unit: 1/(kg·m²)
  // Out, for the bodies whose turn_too_far bit is clear.
  double turned_rotation[4][kDoubleLanes];
  double turned_angular_velocity[3][kDoubleLanes];  // world frame. unit: rad/s
  // Bit i: body i turns more than the implicit midpoint rule follows in one substep and must go
  // by integrate_position instead.
  std::uint32_t turns_too_far = 0;
};

// One batch's turns over a substep of `step` (unit: s) by the implicit midpoint rule for the
// body-frame angular momentum (rigid_body.h).
using SpinKernel = void (*)(SpinBatch& batch, double step);

// The kernel in `lanes` (a lane set the processor has; kAuto: the widest). Every lane set gives
// the same bits.
[[nodiscard]] SpinKernel spin_kernel(SolverLanes lanes);
// The AVX2 kernel, or null where this build has none (spin_lanes_avx2.cpp).
[[nodiscard]] SpinKernel avx2_spin_kernel();

}  // namespace sphys
