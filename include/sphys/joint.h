#pragma once

// Joints: two bodies, or a body and the world, held together by rows solved in the soft step
// with the contacts (plausible mode; docs/joints.md). Every joint is made from a JointDesc,
// whose defaults make a valid ball joint once its bodies are named, as Box2D makes every object
// from a definition.

#include <cstdint>

#include "sphys/body_id.h"
#include "sphys/math.h"
#include "sphys/slot_id.h"

namespace sphys {

// JointId's kind (SlotId's tag): declared only, never defined.
struct JointTag;

// A joint of a world: its slot in the world's joints and the slot's generation (SlotId).
// JointId{} names no joint.
using JointId = SlotId<JointTag>;

// What a joint leaves free between its bodies.
enum class JointType : std::uint8_t {
  kHinge,     // revolute: turning about the axis; angle limits, motor and spring
  kSlider,    // prismatic: sliding along the axis, no turning; position limits, motor, spring
  kBall,      // spherical: any turning; an optional swing cone and twist limit
  kWeld,      // fixed: nothing, stiff or soft (JointDesc::spring)
  kDistance,  // the anchors' distance: a rod, a spring, or a rope between min and max length
};

// A joint's limits on its angle (hinge, ball twist; unit: rad), position (slider; unit: m) or
// length (distance; unit: m). lower <= upper.
struct JointLimit {
  bool enabled = false;  // false leaves the joint free
  float lower = 0.0f;    // unit: rad or m, as the joint's position
  float upper = 0.0f;    // unit: rad or m, as the joint's position
};

// A motor driving a hinge's or slider's speed with a bounded torque or force.
struct JointMotor {
  bool enabled = false;  // false: no motor
  // The relative speed it drives to (body b against body a). unit: rad/s (hinge), m/s (slider)
  float speed = 0.0f;
  // The most it applies, >= 0. unit: N·m (hinge), N (slider)
  float max_effort = 0.0f;
};

// A spring-damper on a joint's position, as a frequency and a damping ratio of the joint's
// effective mass (Box2D's): stiffness m (2π hertz)², damping 2 m ζ (2π hertz).
struct JointSpring {
  bool enabled = false;  // false: no spring
  // Its frequency, >= 0; 0 is no stiffness (a distance joint's rope). unit: Hz
  float hertz = 0.0f;
  // Its damping ratio, >= 0; 1 is critical damping. unit: dimensionless
  float damping_ratio = 0.0f;
  // The position it pulls to (hinge, slider; a distance joint's is JointDesc::length). unit:
  // rad or m
  float target = 0.0f;
};

// A ball joint's swing cone: the angle between the two bodies' axes at most.
struct JointCone {
  bool enabled = false;  // false: any swing
  float angle = 0.0f;    // half-angle of the cone, 0..π. unit: rad
};

// What World::add_joint needs. Anchors and axes are in each body's frame (the world's for the
// null body). Angles are measured from the bodies' relative orientation when the joint is added,
// about body a's axis; a slider's position is the anchors' offset along body a's axis.
struct JointDesc {
  JointType type = JointType::kBall;  // what the joint leaves free
  BodyId body_a;                      // a body of the world, or the null id for the world
  BodyId body_b;                      // a body of the world, or the null id for the world
  Vec3 anchor_a = Vec3::Zero();       // the joint's point on body a. unit: m
  Vec3 anchor_b = Vec3::Zero();       // the joint's point on body b. unit: m
  // The hinge's, slider's or ball's twist axis on each body, not zero (normalised when added).
  Vec3 axis_a = Vec3::UnitX();
  Vec3 axis_b = Vec3::UnitX();  // as axis_a, on body b
  // Hinge: angle; slider: position; ball: twist angle; distance: min and max length.
  JointLimit limit;
  JointMotor motor;    // hinge and slider
  JointSpring spring;  // hinge, slider, distance; a weld's softness (its target unused)
  JointCone cone;      // ball
  // Friction in the joint, >= 0; 0 is none: the most torque (hinge: about its axis; ball: about
  // every axis) or force (slider: along its axis) with which it resists its bodies' relative
  // motion, as a motor holding speed 0 would (Box2D v3's ragdoll), so that a limb comes to rest.
  // Welds and distance joints have none. unit: N·m (hinge, ball) or N (slider)
  float friction = 0.0f;
  // A distance joint's length: its rod's, or its spring's rest length, > 0. unit: m
  float length = 1.0f;
  // Whether the two bodies' contacts with each other count (off: they pass through each other).
  bool collide_connected = false;
};

// What a joint did in the last step, as World::joint_state reads it.
struct JointState {
  // Hinge: angle (rad); slider: position (m); ball: twist angle (rad); distance: length (m);
  // weld: 0.
  float position = 0.0f;
  // The rate of `position`. unit: rad/s or m/s
  float speed = 0.0f;
  // How far the joint is from what it holds: the anchors apart (hinge, ball, weld), body b's
  // anchor off the axis (slider), the length off its rod's (rigid distance) or outside its
  // limits (rope, spring). unit: m
  float gap = 0.0f;
  // The force the joint applied to body b at its anchor in the last step (body a took the
  // opposite), world frame. unit: N
  Vec3 force = Vec3::Zero();
  // The torque it applied to body b besides the force's moment, world frame. unit: N·m
  Vec3 torque = Vec3::Zero();
};

}  // namespace sphys
