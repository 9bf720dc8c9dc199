// The soft step's passes instantiated for the build's lanes, for plain floats of the same width
// and for one lane. With SPHYS_AVX2 this file alone is compiled with -mavx2 (it includes no
// Eigen, whose layout depends on the instruction set).

#include "dynamics/contact_lanes.h"

#include "core/simd.h"
#include "dynamics/contact_lane_kernels.h"

namespace sphys {
namespace {

#if defined(__AVX2__)
using NativeLanes = Avx2Lanes;
#elif defined(__SSE2__)
using NativeLanes = Sse2Lanes;
#else
using NativeLanes = PortableLanes<4>;
#endif
static_assert(NativeLanes::kWidth == kLaneWidth,
              "SPHYS_LANE_WIDTH must match the instruction set contact_lanes.cpp is built for");

template <class F>
constexpr LaneKernels<F::kWidth> kernels_of() {
  return {&lanes::warm_start<F>, &lanes::solve<F>, &lanes::restitute<F>};
}

constexpr LaneKernels<kLaneWidth> kNative = kernels_of<NativeLanes>();
constexpr LaneKernels<kLaneWidth> kPortable = kernels_of<PortableLanes<kLaneWidth>>();
constexpr LaneKernels<1> kSingle = kernels_of<PortableLanes<1>>();

}  // namespace

const LaneKernels<kLaneWidth>& native_lane_kernels() { return kNative; }
const LaneKernels<kLaneWidth>& portable_lane_kernels() { return kPortable; }
const LaneKernels<1>& single_lane_kernels() { return kSingle; }

}  // namespace sphys
