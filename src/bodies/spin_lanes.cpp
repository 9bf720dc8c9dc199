// The spin integrator's kernel in plain doubles and in SSE2's lanes, and the choice among them
// and AVX2's (spin_lanes_avx2.cpp).

#include "bodies/spin_batch.h"
#include "core/simd_double.h"
#include "core/simd_lanes.h"

namespace sphys {
namespace {

#include "bodies/spin_kernel.h"

}  // namespace

SpinKernel spin_kernel(SolverLanes lanes) {
  switch (choose_lanes(lanes, avx2_spin_kernel() != nullptr)) {
#if defined(__SSE2__)
    case SolverLanes::kSse2:
      return &spin::turn_batch<Sse2DoubleLanes>;
#endif
    case SolverLanes::kAvx2:
      return avx2_spin_kernel();
    default:
      return &spin::turn_batch<PortableDoubleLanes>;
  }
}

}  // namespace sphys
