// Paper mode's response: eq. 4 per contact, in order, for up to WorldSettings::paper_passes
// passes (src/dynamics/paper_response.cpp).

#include "core/stopwatch.h"
#include "dynamics/paper_response.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {

void apply_paper_impulses(PassContext& pass) {
  const PhaseClock clock(&pass.world.parallel);
  WorldState& world = pass.world;
  const std::span<const Contact> contacts = world.detector.contacts();
  const PaperResponseStats response = apply_paper_response(
      world.store, contacts, world.settings.ground_restitution, world.settings.paper_passes);
  pass.stats.impulses += response.impulses;
  pass.stats.response_passes += response.passes;
  pass.stats.contacts += static_cast<std::uint32_t>(contacts.size());
  clock.add_to(pass.stats.response_ms, pass.stats.response_serial_ms);
}

}  // namespace sphys
