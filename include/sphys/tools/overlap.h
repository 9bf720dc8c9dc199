#pragma once

// How deep bodies overlap where they are now, counted independently of the world's detector,
// which does not look at bodies asleep together: the check that a pile left to sleep did not
// sink into itself or into the ground.

#include <cstdint>
#include <limits>
#include <optional>

#include "sphys/tools/build_world.h"

namespace sphys::tools {

// The deepest overlap of two leaf spheres found by deepest_overlap, and its bodies.
struct Overlap {
  float depth = 0.0f;  // r_a + r_b − |c_a − c_b| of the deepest leaf pair; 0 when none. unit: m
  // The scene bodies (indices into SimulationSetup::bodies) of that pair; kGround for the ground.
  std::uint32_t body_a = 0;
  std::uint32_t body_b = 0;  // the pair's other body, or kGround
  // The ground's stand-in for a scene body index (no body has it).
  static constexpr std::uint32_t kGround = std::numeric_limits<std::uint32_t>::max();
};

// The deepest overlap of two leaf spheres of different scene bodies, or of a leaf sphere with the
// ground: the exact plane y = plane_height when given, and the octree ground's tree when the
// setup has one. Pairs are culled by spheres around all their leaves, then every leaf pair is
// tested.
[[nodiscard]] Overlap deepest_overlap(const SimulationSetup& setup,
                                      std::optional<float> plane_height);

}  // namespace sphys::tools
