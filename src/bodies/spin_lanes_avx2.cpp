// The spin integrator's kernel in AVX2 lanes. This file alone of the bodies is compiled with
// -mavx2 (without FMA): it includes no Eigen and instantiates the kernel in its anonymous
// namespace only, so that nothing compiled here is linked in place of the rest of the library's
// code on a processor without AVX2. It is called only where the processor has AVX2
// (spin_lanes.cpp).

#include "bodies/spin_batch.h"
#include "core/simd_double.h"

namespace sphys {

#if defined(__AVX2__)
namespace {

#include "bodies/spin_kernel.h"

}  // namespace

SpinKernel avx2_spin_kernel() { return &spin::turn_batch<Avx2DoubleLanes>; }
#else
SpinKernel avx2_spin_kernel() { return nullptr; }
#endif

}  // namespace sphys
