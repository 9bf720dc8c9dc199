// The descent's child test in AVX2 lanes. This file alone of the collision detection is compiled
// with -mavx2 (without FMA): it includes no Eigen and instantiates the kernel in its anonymous
// namespace only, so that nothing compiled here is linked in place of the rest of the library's
// code on a processor without AVX2. It is called only where the processor has AVX2
// (child_test_lanes.cpp).

#include "collision/child_test.h"
#include "core/simd.h"

namespace sphys {

#if defined(__AVX2__)
namespace {

#include "collision/child_test_kernel.h"

}  // namespace

ChildTestKernel avx2_child_test_kernel() { return &child_lanes::test_children<Avx2Lanes>; }
#else
ChildTestKernel avx2_child_test_kernel() { return nullptr; }
#endif

}  // namespace sphys
