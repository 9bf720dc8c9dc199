#pragma once

// The stages of a collision pass, each in the file named for it, and what more than one stage
// shares. The pipelines (world/paper_pipeline.cpp, world/plausible_pipeline.cpp) put them in
// order.

#include <cstdint>

#include "world/pipeline.h"

namespace sphys {

struct CollisionStats;

// Paper mode: the velocities under gravity and the forces applied for the step, the first half
// of semi-implicit Euler (world/integrate_velocities.cpp).
void integrate_velocities(PassContext& pass);
// Plausible mode: each awake body's reach in the pass for speculative contacts, with gravity's
// and the applied forces' speed at its end (world/bound_motion.cpp).
void bound_motion(PassContext& pass);
// One body's reach, as bound_motion; false when its motion is no longer finite.
[[nodiscard]] bool bound_body_motion(WorldState& world, std::uint32_t body, float pass_dt);
// Bounds, broad and narrow phase, manifolds: the detector's (world/detect_contacts.cpp).
void detect_contacts(PassContext& pass);
// A detection's figures added to the step's (world/detect_contacts.cpp).
void add_detection(const WorldState& world, const CollisionStats& detection, StepStats& stats);
// Plausible mode: the sleeping bodies that moving ones touch wake, with their pairs' narrow
// phase; the islands the pass's contacts join merge (world/wake_touched.cpp).
void wake_touched(PassContext& pass);
// Plausible mode: each contact's material, then the soft step, which moves the bodies too
// (world/solve_contacts.cpp).
void solve_contacts(PassContext& pass);
// Paper mode: eq. 4 per contact, in order (world/apply_paper_impulses.cpp).
void apply_paper_impulses(PassContext& pass);
// Paper mode: the positions, the second half of semi-implicit Euler, each body then finished as
// finalize_bodies does (world/integrate_positions.cpp).
void integrate_positions(PassContext& pass);
// Plausible mode: each awake body finished once: its world inertia, whether it is finite, its
// fastest point's speed and its still time (world/finalize_bodies.cpp).
void finalize_bodies(PassContext& pass);
// Plausible mode: the bodies still long enough that touch no restless body fall asleep
// (world/update_sleep.cpp).
void update_sleep(PassContext& pass);

// Once a step, at its end, where asked for (WorldSettings::plausibility_figures): kinetic energy,
// bodies at rest and jitter (world/measure_rest.cpp).
void measure_rest(WorldState& world, StepStats& stats);

}  // namespace sphys
