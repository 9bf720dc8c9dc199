#pragma once

// The bodies as the soft step sees them: one slot per body of the store and one more, the last,
// for the ground plane. The solver works on these velocities and writes the awake bodies' back to
// the store when done. Both copies run on the threads, each slot written by one run.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/buffers.h"
#include "dynamics/contact_lanes.h"
#include "sphys/body_store.h"
#include "sphys/math.h"
#include "sphys/parallel.h"

namespace sphys {

// Slots or bodies per item of the threaded loops that copy them. unit: slots
inline constexpr std::size_t kSlotsPerRun = 256;

// A slot's velocities, a cache line to itself: the threads solving one colour write the
// velocities of different bodies, and bodies sharing a line would pass it to and fro.
struct alignas(64) SolverVelocity {
  Vec3 linear = Vec3::Zero();   // unit: m/s
  Vec3 angular = Vec3::Zero();  // unit: rad/s
};

// A slot's motion since the step's start, for its contacts' separations: translation and rotation
// (as a matrix). A row of its own too, which the lanes load as they load the velocities.
struct alignas(64) SolverMotion {
  Vec3 moved = Vec3::Zero();       // unit: m
  Mat3 turned = Mat3::Identity();  // column-major
};
static_assert(sizeof(SolverVelocity) == kBodyRow * sizeof(float) &&
                  sizeof(SolverMotion) == kBodyRow * sizeof(float),
              "the lanes read a body's velocities and motion as rows of kBodyRow floats");

// Fills the slots: every body's position; velocities, inverse mass and world inverse inertia of
// the awake bodies, zero for the others and the ground, so that an impulse leaves them as they
// are.
inline void load_solver_bodies(const BodyStore& bodies, const Parallel& parallel,
                               std::vector<SolverVelocity>& velocity, std::vector<Vec3>& position,
                               std::vector<float>& inverse_mass,
                               std::vector<Mat3>& inverse_inertia) {
  const std::size_t slots = bodies.slots() + 1;
  resize_buffer(velocity, slots);
  resize_buffer(position, slots);
  resize_buffer(inverse_mass, slots);
  resize_buffer(inverse_inertia, slots);
  const std::span<const Transform> poses = bodies.poses();
  parallel.for_each_run(slots, kSlotsPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      velocity[i] = SolverVelocity{};
      position[i] = i < poses.size() ? poses[i].translation : Vec3::Zero();
      inverse_mass[i] = 0.0f;
      inverse_inertia[i] = Mat3::Zero();
    }
  });
  const std::span<const std::uint32_t> awake = bodies.awake();
  parallel.for_each_run(awake.size(), kSlotsPerRun, [&](std::size_t begin, std::size_t end) {
    for (const std::uint32_t i : awake.subspan(begin, end - begin)) {
      velocity[i] = {bodies.linear_velocities()[i], bodies.angular_velocities()[i]};
      inverse_mass[i] = bodies.inverse_masses()[i];
      inverse_inertia[i] = bodies.inverse_inertias_world()[i];
    }
  });
}

// The solved velocities of the awake bodies into the store.
inline void store_solver_velocities(std::span<const SolverVelocity> velocity,
                                    const Parallel& parallel, BodyStore& bodies) {
  const std::span<const std::uint32_t> awake = bodies.awake();
  parallel.for_each_run(awake.size(), kSlotsPerRun, [&](std::size_t begin, std::size_t end) {
    for (const std::uint32_t i : awake.subspan(begin, end - begin)) {
      bodies.linear_velocities()[i] = velocity[i].linear;
      bodies.angular_velocities()[i] = velocity[i].angular;
    }
  });
}

}  // namespace sphys
