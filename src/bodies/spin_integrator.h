#pragma once

// The plausible mode's integrator for the orientations: integrate_position's motion with the
// angular momentum following Euler's equations, in double lanes four bodies at a time.

#include <span>

#include "bodies/spin_batch.h"
#include "sphys/math.h"

namespace sphys {

// A body as integrate_positions_keeping_spin moves it: its pose and angular velocity (updated),
// its linear velocity and its inertia in its own frame.
struct SpinningBody {
  Transform* pose;                   // moved. unit: m
  const Vec3* linear_velocity;       // world frame. unit: m/s
  Vec3* angular_velocity;            // world frame, updated. unit: rad/s
  const Mat3* inertia_body;          // about the centre of mass, body axes. unit: kg·m²
  const Mat3* inverse_inertia_body;  // unit: 1/(kg·m²)
};

// The motion of integrate_position (rigid_body.h) over `dt` (unit: s) with the angular momentum
// following Euler's equations in the body frame by the implicit midpoint rule, in double
// (spin_kernel.h): a torque-free body keeps |L| and its kinetic energy to float rounding (2e-5
// over 2,400 steps of an asymmetric body tumbling). A body turning more than half a radian in the
// step goes by integrate_position. Each body gets the result it has alone, in whichever lanes
// `kernel` runs (spin_kernel(lanes)).
void integrate_positions_keeping_spin(std::span<const SpinningBody> bodies, float dt,
                                      SpinKernel kernel);

}  // namespace sphys
