#pragma once

// A pass table of one lane type, for contact_lanes.cpp and contact_lanes_avx2.cpp.

#include "dynamics/contact_lane_kernels.h"
#include "dynamics/contact_lanes.h"

namespace sphys {

template <class F>
constexpr LaneKernels<F::kWidth> lane_kernels_of() {
  return {&lanes::warm_start<F>, &lanes::solve<F>, &lanes::restitute<F>};
}

}  // namespace sphys
