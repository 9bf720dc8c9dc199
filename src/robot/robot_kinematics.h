#pragma once

// A robot's kinematics compiled for many configurations at once: per link, its joint's motion as
// constant matrices, so that a link's pose for joint value q is a few multiply-adds of sin q and
// 1 - cos q (robot_kinematics_kernel.h), eight configurations in the lanes of one vector. Plain
// arrays and no Eigen: the AVX2 kernel's file must not share an inline function with the rest of
// the library (robot_kinematics_avx2.cpp).

#include <cstddef>
#include <cstdint>

namespace sphys {

// Configurations posed together: the lanes of one kernel call. unit: configurations
inline constexpr int kPoseLanes = 8;

// One lane vector's floats, aligned for the kernels' loads and stores.
struct alignas(32) PoseLane {
  float v[kPoseLanes];
};

enum class LinkMotion : std::uint8_t { kFixed, kTurn, kSlide };

// A link's pose in its parent's for joint value q: rotation A + sin q B + (1 - cos q) C (A the
// origin's rotation R, B = R K, C = R K² with K the cross-product matrix of the joint's axis:
// Rodrigues' formula), translation t + q d (d = R axis, sliding joints). Matrices row-major.
struct KinematicsTables {
  int links = 0;
  int spheres = 0;
  const std::int32_t* parent =
      nullptr;                          // -1: the link's pose is its own (the root's, in the world)
  const std::int32_t* joint = nullptr;  // the joint value's row in the values block
  const LinkMotion* motion = nullptr;
  const float* a = nullptr;  // 9 per link
  const float* b = nullptr;
  const float* c = nullptr;
  const float* t = nullptr;  // 3 per link
  const float* d = nullptr;
  const std::int32_t* sphere_link = nullptr;
  const float* sphere = nullptr;  // x, y, z, radius per sphere, in its link's frame
  // The first `boxed_links` links' boxes of their spheres in their own frames: centre, its
  // components' magnitudes and half extents, 3 floats each a link.
  int boxed_links = 0;
  const float* box_centre = nullptr;
  const float* box_centre_size = nullptr;
  const float* box_half = nullptr;
};

// Poses kPoseLanes configurations: `values` holds, per joint, kPoseLanes joint values (turning
// joints' already in [-pi, pi]); `links` gets each link's pose (rotation row-major, then
// translation: 12 × kPoseLanes floats a link); `boxes`, unless null, each boxed link's box in the
// world (low x, y, z, then high x, y, z: 6 × kPoseLanes floats a link), the box of its spheres
// in its frame turned and moved, with a margin against rounding; `out` gets, per configuration,
// spheres × (x, y, z, radius) in the world, or is null for the links alone.
using PoseBlock = void (*)(const KinematicsTables& tables, const float* values, float* links,
                           float* boxes, float* out);
// Places the `count` spheres listed in `spheres` for the kPoseLanes configurations whose links'
// poses `links` holds (as PoseBlock wrote them): lane i's (x, y, z, radius) of sphere s at
// out[i] + 4 s, the others left as they are.
using PlaceBlock = void (*)(const KinematicsTables& tables, const float* links,
                            const std::uint32_t* spheres, std::size_t count, float* const* out);
// A kernel's two calls, in one width of lanes. Every kernel gives the same bits, and a sphere
// placed by either call the same bits.
struct KinematicsKernel {
  PoseBlock pose = nullptr;
  PlaceBlock place = nullptr;
};
[[nodiscard]] KinematicsKernel portable_kernel();
[[nodiscard]] KinematicsKernel sse2_kernel();  // empty where SSE2 is not compiled in
[[nodiscard]] KinematicsKernel avx2_kernel();  // empty where the AVX2 file is not compiled for it

}  // namespace sphys
