// Each contact's material in plausible mode: the one set for its pair, else the mix of its
// bodies' (sphys/material.h).

#include "world/mix_materials.h"

#include "core/buffers.h"
#include "world/world_state.h"

namespace sphys {

void mix_materials(WorldState& world) {
  const std::span<const Contact> contacts = world.detector.contacts();
  const std::span<const float> friction = world.store.frictions();
  const std::span<const float> restitution = world.store.restitutions();
  resize_buffer(world.materials, contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& contact = contacts[k];
    const std::uint32_t a = contact.body_a;
    const std::uint32_t b = contact.body_b;
    if (a == kGroundPlaneBody) {
      world.materials[k] = {mix_friction(world.settings.ground_friction, friction[b]),
                            mix_restitution(world.settings.ground_restitution, restitution[b])};
      continue;
    }
    const auto pair = world.pair_materials.empty() ? world.pair_materials.end()
                                                   : world.pair_materials.find(pair_key(a, b));
    world.materials[k] = pair != world.pair_materials.end()
                             ? pair->second
                             : PairMaterial{mix_friction(friction[a], friction[b]),
                                            mix_restitution(restitution[a], restitution[b])};
  }
}

}  // namespace sphys
