// The descent's child test in plain floats and in SSE2's lanes, and the choice among them and
// AVX2's (child_test_lanes_avx2.cpp).

#include "collision/child_test.h"
#include "core/simd.h"
#include "core/simd_lanes.h"

namespace sphys {
namespace {

#include "collision/child_test_kernel.h"

}  // namespace

ChildTestKernel child_test_kernel(SolverLanes lanes) {
  switch (choose_lanes(lanes, avx2_child_test_kernel() != nullptr)) {
#if defined(__SSE2__)
    case SolverLanes::kSse2:
      return &child_lanes::test_children<Sse2PairLanes>;
#endif
    case SolverLanes::kAvx2:
      return avx2_child_test_kernel();
    default:
      return &child_lanes::test_children<PortableLanes<kChildLanes>>;
  }
}

}  // namespace sphys
