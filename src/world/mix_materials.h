#pragma once

namespace sphys {

struct WorldState;

// WorldState::materials: each of the detector's contacts' friction and restitution, the one set
// for its pair (World::set_pair_material), else the mix of its bodies' or the ground's.
void mix_materials(WorldState& world);

}  // namespace sphys
