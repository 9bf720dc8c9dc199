#pragma once

// The soft step's velocities when its substep changes length from one collision pass to the next
// (the world's adaptive collision passes, WorldSettings::max_collision_passes).

#include "dynamics/joint_solver.h"
#include "sphys/math.h"

namespace sphys {

// Symplectic Euler (velocities, then positions by the new velocities) keeps velocities half a
// substep behind the positions, and the energy it keeps differs from the true one by a term of
// h/2: a substep that shortens as a pendulum speeds up and lengthens as it slows takes a little
// of its energy at every change (a 1 rad, 1 m pendulum of 5 cm lost 3.7% in 10 s, against 0.4%
// at any fixed number of passes). Moving every moving body's velocity by gravity's half of the
// change, g (last_h − h) / 2, keeps them half the new substep behind instead. Nothing when
// `last_h` (unit: s) is 0 (the first pass) or equals `h` (unit: s).
void shift_to_substep(const JointSolverBodies& bodies, const Vec3& gravity, float last_h, float h);

}  // namespace sphys
