#pragma once

#include <cstdint>

namespace sphys {

// What a plausible-mode solve did.
struct ContactSolverStats {
  std::uint32_t constraints = 0;   // contacts solved (those with a moving body)
  std::uint32_t warm_started = 0;  // of them, matched to a contact of the previous step
  std::uint32_t bounces = 0;       // contacts given restitution
};

}  // namespace sphys
