#include "dynamics/substep_change.h"

namespace sphys {

void shift_to_substep(const JointSolverBodies& bodies, const Vec3& gravity, float last_h, float h) {
  if (!(last_h > 0.0f) || last_h == h) return;
  const Vec3 shift = 0.5f * (last_h - h) * gravity;
  for (std::size_t slot = 0; slot < bodies.velocity.size(); ++slot) {
    if (bodies.inverse_mass[slot] > 0.0f) bodies.velocity[slot].linear += shift;
  }
}

}  // namespace sphys
