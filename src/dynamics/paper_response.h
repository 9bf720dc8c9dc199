#pragma once

// The paper's collision response (§4, eq. 4): one impulse along the normal per contact.

#include <cstdint>
#include <span>

#include "sphys/body_store.h"
#include "sphys/contact.h"
#include "sphys/material.h"

namespace sphys {

// For each contact in order, when the contact points approach along the normal (relative normal
// velocity v_c < 0), applies J = j n with
//   j = −(1 + ε) v_c / (1/m₁ + 1/m₂ + n·((I₁⁻¹(r₁ × n)) × r₁) + n·((I₂⁻¹(r₂ × n)) × r₂))
// at the contact point: +J to body b, −J to body a, linear and angular. Each impulse changes the
// velocities the next contacts see (Gauss–Seidel); static bodies take none. The pass over all
// contacts is repeated until
// a pass applies no impulse or `max_passes` passes are done (see docs/experiment.md). A contact
// whose body_a is kGroundPlaneBody is against the static ground plane with restitution
// `ground_restitution`.
struct PaperResponseStats {
  std::uint32_t impulses = 0;  // impulses applied, over all passes
  std::uint32_t passes = 0;    // passes made
};
PaperResponseStats apply_paper_response(BodyStore& bodies, std::span<const Contact> contacts,
                                        float ground_restitution, std::uint32_t max_passes);

}  // namespace sphys
