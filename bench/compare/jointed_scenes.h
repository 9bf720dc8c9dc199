#pragma once

// The jointed benchmark scenes (issue 65's comparison), described once for every engine:
//
// - "ragdolls:R": R ragdolls of 11 limbs (pelvis, chest, head, upper arms, forearms, thighs,
//   shins), each limb a capsule of spheres, joined by 6 ball joints (swing cone and twist
//   limits) and 4 hinges (elbows, knees, with limits), lying in layers of 5 × 5 and falling
//   onto the plane and each other.
// - "chains:CxL": C chains of L links hinged to the world at one end (each hinge limited), held
//   level and let go, swinging down into a pile of bunnies (depth-3 trees) beneath them.
//
// Every limb's body frame has its axes along the limb and its centre of mass at the origin, so
// that its inertia is diagonal.

#include <string>

#include "bench_scene.h"

namespace sphys::compare {

// True for a jointed scene's name ("ragdolls:..." or "chains:..."), well formed or not.
[[nodiscard]] bool is_jointed_scene(const std::string& name);

// A ball joint's twist limit as one span either way, the larger side of its limits (π without
// them): what an engine with a symmetric twist limit takes (Bullet, ODE). unit: rad
[[nodiscard]] float twist_span(const JointDesc& ball);

// The scene a name describes. Throws sphys::Error naming the scene and its valid forms for a
// malformed name or a count out of range.
[[nodiscard]] BenchScene make_jointed_scene(const std::string& name);

}  // namespace sphys::compare
