// The kinematics kernel in AVX2 lanes. This file alone of the queries is compiled with -mavx2
// (without FMA): it includes no Eigen and instantiates the kernel in its anonymous namespace only,
// so that nothing compiled here is linked in place of the rest of the library's code on a
// processor without AVX2. It is called only where the processor has AVX2 (robot_check.cpp).

#include "core/simd.h"
#include "robot/robot_kinematics.h"

namespace sphys {

#if defined(__AVX2__)
namespace {

#include "robot/robot_kinematics_kernel.h"

}  // namespace

KinematicsKernel avx2_kernel() { return {&pose_block_of<Avx2Lanes>, &place_block_of<Avx2Lanes>}; }
#else
KinematicsKernel avx2_kernel() { return {}; }
#endif

}  // namespace sphys
