// The soft step's passes instantiated for SSE2's lanes, for plain floats of the same width and for
// one lane; AVX2's are contact_lanes_avx2.cpp's.

#include "dynamics/contact_lanes.h"

#include "core/simd.h"
#include "dynamics/contact_lane_kernels.h"
#include "dynamics/lane_kernels_of.h"

namespace sphys {
namespace {

constexpr LaneKernels<kLaneWidth> kPortable = lane_kernels_of<PortableLanes<kLaneWidth>>();
#if defined(__SSE2__)
constexpr LaneKernels<kLaneWidth> kSse2 = lane_kernels_of<Sse2PairLanes>();
#endif
constexpr LaneKernels<1> kSingle = lane_kernels_of<PortableLanes<1>>();

}  // namespace

const LaneKernels<kLaneWidth>& lane_kernels(SolverLanes lanes) {
  switch (lanes) {
#if defined(__SSE2__)
    case SolverLanes::kSse2:
      return kSse2;
#endif
    case SolverLanes::kAvx2:
      if (const LaneKernels<kLaneWidth>* avx2 = avx2_lane_kernels()) return *avx2;
      break;
    default:
      break;
  }
  return kPortable;
}

const LaneKernels<1>& single_lane_kernels() { return kSingle; }

}  // namespace sphys
