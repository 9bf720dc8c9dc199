#pragma once

#include "sphys/slot_id.h"

namespace sphys {

// BodyId's kind (SlotId's tag): declared only, never defined.
struct BodyTag;

// A body of a world: its slot in the world's body store and the slot's generation (SlotId).
// BodyId{} names no body.
using BodyId = SlotId<BodyTag>;

}  // namespace sphys
