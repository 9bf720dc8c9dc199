// The soft step's lanes as solver_settings.h offers them: core's lane choice (core/simd_lanes.h),
// with AVX2 where this build compiled the contact passes' AVX2 file.

#include <cstddef>

#include "core/simd_lanes.h"
#include "dynamics/contact_lanes.h"
#include "sphys/solver_settings.h"

namespace sphys {

std::string_view solver_lanes_name(SolverLanes lanes) {
  return kLaneSetNames[static_cast<std::size_t>(lanes)];
}

SolverLanes resolve_solver_lanes(SolverLanes requested) {
  return choose_lanes(requested, avx2_lane_kernels() != nullptr);
}

}  // namespace sphys
