#pragma once

// How the materials of two touching bodies combine. See docs/dynamics.md.

#include <cmath>

namespace sphys {

// Friction of a pair: the geometric mean (as Box2D and Bullet mix it), so that a frictionless
// body slides on anything and two equal materials keep their own coefficient.
[[nodiscard]] inline float mix_friction(float a, float b) { return std::sqrt(a * b); }

// Restitution of a pair: the larger (as Box2D mixes it), so that a bouncy body stays bouncy on
// any floor. The paper uses one ε for every pair.
[[nodiscard]] inline float mix_restitution(float a, float b) { return a > b ? a : b; }

// A material for one pair of bodies, replacing the mix of their own (World::set_pair_material).
struct PairMaterial {
  float friction = 0.5f;     // Coulomb coefficient, >= 0. unit: dimensionless
  float restitution = 0.3f;  // 0..1. unit: dimensionless
};

}  // namespace sphys
