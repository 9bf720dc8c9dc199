#pragma once

#include <cstdint>

namespace sphys {

// What a soft step's solve did.
struct SoftStepStats {
  std::uint32_t contacts_solved = 0;  // those with a moving body
  std::uint32_t warm_started = 0;  // of them, matched to a contact of the previous collision pass
  std::uint32_t bounces = 0;       // contacts given restitution
};

}  // namespace sphys
