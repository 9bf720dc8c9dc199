// The kinematics kernel in plain floats and in two SSE2 registers (robot_kinematics_kernel.h);
// AVX2's is in robot_kinematics_avx2.cpp.

#include "robot/robot_kinematics.h"

#include "core/simd.h"

namespace sphys {
namespace {

#include "robot/robot_kinematics_kernel.h"

}  // namespace

KinematicsKernel portable_kernel() {
  return {&pose_block_of<PortableLanes<kPoseLanes>>, &place_block_of<PortableLanes<kPoseLanes>>};
}

KinematicsKernel sse2_kernel() {
#if defined(__SSE2__)
  return {&pose_block_of<Sse2PairLanes>, &place_block_of<Sse2PairLanes>};
#else
  return {};
#endif
}

}  // namespace sphys
