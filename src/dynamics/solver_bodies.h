#pragma once

// The bodies as the soft step sees them: one slot per body of the store and one more, the last,
// for the ground plane. The solver works on these velocities and writes the awake bodies' back to
// the store when done.

#include <cstdint>
#include <span>
#include <vector>

#include "core/buffers.h"
#include "sphys/body_store.h"
#include "sphys/math.h"

namespace sphys {

// Fills the slots: every body's position; velocities, inverse mass and world inverse inertia of
// the awake bodies, zero for the others and the ground, so that an impulse leaves them as they
// are.
inline void load_solver_bodies(const BodyStore& bodies, std::vector<Vec3>& linear,
                               std::vector<Vec3>& angular, std::vector<Vec3>& position,
                               std::vector<float>& inverse_mass,
                               std::vector<Mat3>& inverse_inertia) {
  const std::size_t slots = bodies.slots() + 1;
  fill_buffer(linear, slots, Vec3(Vec3::Zero()));
  fill_buffer(angular, slots, Vec3(Vec3::Zero()));
  fill_buffer(position, slots, Vec3(Vec3::Zero()));
  fill_buffer(inverse_mass, slots, 0.0f);
  fill_buffer(inverse_inertia, slots, Mat3(Mat3::Zero()));
  const std::span<const Transform> poses = bodies.poses();
  for (std::size_t i = 0; i < poses.size(); ++i) position[i] = poses[i].translation;
  for (const std::uint32_t i : bodies.awake()) {
    linear[i] = bodies.linear_velocities()[i];
    angular[i] = bodies.angular_velocities()[i];
    inverse_mass[i] = bodies.inverse_masses()[i];
    inverse_inertia[i] = bodies.inverse_inertias_world()[i];
  }
}

// The solved velocities of the awake bodies into the store.
inline void store_solver_velocities(std::span<const Vec3> linear, std::span<const Vec3> angular,
                                    BodyStore& bodies) {
  for (const std::uint32_t i : bodies.awake()) {
    bodies.linear_velocities()[i] = linear[i];
    bodies.angular_velocities()[i] = angular[i];
  }
}

}  // namespace sphys
