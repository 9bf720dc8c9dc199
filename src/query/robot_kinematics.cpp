// The kinematics kernel in plain floats and in two SSE2 registers (robot_kinematics_kernel.h);
// AVX2's is in robot_kinematics_avx2.cpp.

#include "query/robot_kinematics.h"

#include "core/simd.h"

namespace sphys {
namespace {

#include "query/robot_kinematics_kernel.h"

}  // namespace

PoseBlock portable_pose_block() { return &pose_block_of<PortableLanes<kPoseLanes>>; }

PoseBlock sse2_pose_block() {
#if defined(__SSE2__)
  return &pose_block_of<Sse2PairLanes>;
#else
  return nullptr;
#endif
}

}  // namespace sphys
