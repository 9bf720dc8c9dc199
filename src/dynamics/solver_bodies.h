#pragma once

// The bodies as both plausible solvers see them: one slot per body and one more, the last, for
// the ground plane.

#include <cstdint>
#include <span>
#include <vector>

#include "core/buffers.h"
#include "sphys/math.h"
#include "sphys/rigid_body.h"

namespace sphys {

// Fills the slots: every body's position; velocities, inverse mass and world inverse inertia of
// the bodies with `moving[i] != 0` that are not static, zero for the others and the ground, so
// that an impulse leaves them as they are.
inline void load_solver_bodies(std::span<const RigidBody> bodies,
                               std::span<const std::uint8_t> moving, std::vector<Vec3>& linear,
                               std::vector<Vec3>& angular, std::vector<Vec3>& position,
                               std::vector<float>& inverse_mass,
                               std::vector<Mat3>& inverse_inertia) {
  const std::size_t slots = bodies.size() + 1;
  fill_buffer(linear, slots, Vec3(Vec3::Zero()));
  fill_buffer(angular, slots, Vec3(Vec3::Zero()));
  fill_buffer(position, slots, Vec3(Vec3::Zero()));
  fill_buffer(inverse_mass, slots, 0.0f);
  fill_buffer(inverse_inertia, slots, Mat3(Mat3::Zero()));
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const RigidBody& body = bodies[i];
    position[i] = body.pose.translation;
    if (body.is_static || moving[i] == 0) continue;
    linear[i] = body.linear_velocity;
    angular[i] = body.angular_velocity;
    inverse_mass[i] = body.inverse_mass;
    inverse_inertia[i] = body.inverse_inertia_world();
  }
}

}  // namespace sphys
