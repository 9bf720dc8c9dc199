#pragma once

// A joint as the soft step sees it: its bodies' slots, its frames on each body, its parameters
// and the impulses it keeps from step to step for warm starting. The world keeps one per joint
// (src/world/joint_store.h); the joint solver (joint_solver.h) reads and updates them.

#include <cstdint>

#include "sphys/joint.h"
#include "sphys/math.h"

namespace sphys {

// The slot a joint to the world names for its world side.
inline constexpr std::uint32_t kWorldSlot = 0xFFFFFFFFu;

// What a joint's rows applied in one substep, kept for the next step's warm start. unit: N·s
// (linear rows) or N·m·s (angular rows)
struct JointImpulses {
  // The point rows (ball, hinge, weld); a slider's two rows across its axis in x and y.
  Vec3 linear = Vec3::Zero();
  // The rotation locks (weld, slider); a hinge's two rows across its axis in x and y.
  Vec3 angular = Vec3::Zero();
  float spring = 0.0f;  // the spring's row; a rigid distance joint's rod
  float motor = 0.0f;
  float lower = 0.0f;  // the lower limit's, >= 0
  float upper = 0.0f;  // the upper limit's, >= 0
  float cone = 0.0f;   // a ball joint's swing cone, >= 0
  // The friction's rows (JointDesc::friction): a hinge's about its axis and a slider's along its
  // axis in x; a ball's about the world's axes.
  Vec3 friction = Vec3::Zero();
};

struct JointModel {
  JointDesc desc;                     // as added (axes normalised), with the setters' changes
  std::uint32_t body_a = kWorldSlot;  // store slots, kWorldSlot for the world
  std::uint32_t body_b = kWorldSlot;
  // Each body's joint frame: its x axis is the joint's axis, and the frames coincide when the
  // joint's angles are 0 (their relative orientation when the joint was added).
  Quat frame_a = Quat::Identity();
  Quat frame_b = Quat::Identity();
  JointImpulses impulses;
  JointState state;  // what the last step did
  bool alive = false;
};

}  // namespace sphys
