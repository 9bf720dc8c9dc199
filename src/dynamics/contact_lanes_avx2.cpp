// The soft step's passes in AVX2 lanes. This file alone is compiled with -mavx2 (and no FMA, as
// the whole library): it includes no Eigen, whose layout depends on the instruction set, and
// instantiates the passes for Avx2Lanes only, so that no function compiled here is one the rest
// of the library could link to on a processor without AVX2. It is called only where the processor
// has AVX2 (solver_lanes.cpp).

#include "core/simd.h"
#include "dynamics/contact_lanes.h"
#include "dynamics/lane_kernels_of.h"

namespace sphys {

#if defined(__AVX2__)
namespace {
constexpr LaneKernels<kLaneWidth> kAvx2 = lane_kernels_of<Avx2Lanes>();
}  // namespace

const LaneKernels<kLaneWidth>* avx2_lane_kernels() { return &kAvx2; }
#else
const LaneKernels<kLaneWidth>* avx2_lane_kernels() { return nullptr; }
#endif

}  // namespace sphys
