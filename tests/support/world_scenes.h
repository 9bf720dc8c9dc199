#pragma once

// Bodies and floors for the plausible mode's physics tests: a bumpy 1 m box of 1000 kg, a ball,
// the exact plane as floor, a slope as tilted gravity, and a loop of steps.

#include <cmath>

#include <gtest/gtest.h>

#include "sphys/world.h"
#include "support/cube_tree.h"

namespace sphys::test {

inline constexpr float kGravity = 9.81f;
inline constexpr float kDt = 1.0f / 60.0f;
inline constexpr float kBoxSide = 1.0f;  // the side of octree_cube_tree()'s cube. unit: m

// How far the cube's spheres reach below its centre: where it rests on a plane. unit: m
inline float cube_half_height() {
  static const float half = [] {
    const SphereTree& tree = *octree_cube_tree();
    float lowest = 0.0f;
    for (std::uint32_t node = 0; node < tree.size(); ++node) {
      if (tree.is_leaf(node)) {
        lowest = std::min(lowest, tree.sphere(node).center.y() - tree.sphere(node).radius);
      }
    }
    return -lowest;
  }();
  return half;
}

// A homogeneous cube of `mass` (1000 kg: 1000 kg/m³): I = m s²/6 about every axis.
inline BodyDesc cube(const Vec3& position, float friction, float mass = 1000.0f) {
  BodyDesc desc;
  desc.tree = octree_cube_tree();
  desc.pose.translation = position;
  desc.mass = mass;
  desc.inertia = Mat3::Identity() * (desc.mass * kBoxSide * kBoxSide / 6.0f);
  desc.friction = friction;
  desc.restitution = 0.0f;
  return desc;
}

// A solid ball of `mass` (unit: kg) and `radius` (unit: m) at `position`: I = 2/5 m r².
inline BodyDesc ball_body(float radius, float mass, const Vec3& position) {
  BodyDesc desc;
  desc.tree = one_sphere_tree(radius);
  desc.pose.translation = position;
  desc.mass = mass;
  desc.inertia = Mat3::Identity() * (0.4f * mass * radius * radius);
  return desc;
}

// A solid ball of 1 kg.
inline BodyDesc ball(float radius, const Vec3& position, float restitution) {
  BodyDesc desc = ball_body(radius, 1.0f, position);
  desc.restitution = restitution;
  return desc;
}

// The exact plane y <= 0 as the floor, with the given material.
inline WorldSettings on_plane(float friction, float restitution) {
  WorldSettings settings;
  settings.collision.ground_plane_height = 0.0f;
  settings.ground_friction = friction;
  settings.ground_restitution = restitution;
  settings.plausibility_figures = true;
  return settings;
}

// A slope of angle θ is the floor under gravity tilted by θ: the same forces in the slope's
// frame, with the exact plane as the slope. Down the slope is +x.
inline WorldSettings slope(float angle, float friction) {
  WorldSettings settings = on_plane(friction, 0.0f);
  settings.gravity = kGravity * Vec3(std::sin(angle), -std::cos(angle), 0.0f);
  return settings;
}

inline void run(World& world, float seconds) {
  const int steps = static_cast<int>(std::lround(seconds / kDt));
  for (int i = 0; i < steps; ++i) ASSERT_FALSE(world.step(kDt).non_finite_body);
}

// One step with `box` driven along z at 0.1 m/s (above the sleep speed), turning every 30 frames:
// face to face with its neighbour along x, it pushes nothing.
inline void jiggle(World& world, BodyId box, int frame) {
  const float side = (frame / 30) % 2 == 0 ? 1.0f : -1.0f;
  world.set_velocity(box, Vec3(0.0f, 0.0f, 0.1f * side), Vec3::Zero());
  world.step(kDt);
}

}  // namespace sphys::test
