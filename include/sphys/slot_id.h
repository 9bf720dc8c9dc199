#pragma once

#include <cstdint>

namespace sphys {

// An object of a world (a body, a joint, a robot): its slot in the world's store of its kind and
// the slot's generation, so that the id of a removed object never names the object added in its
// slot later. Generations count from 1, so that the default id, generation 0, names nothing (as
// Box2D's zero id and Jolt's default BodyID): every call given it throws sphys::Error. A handle,
// never a pointer: storage may move. `Tag` only names the kind, so that each kind's id is a type
// of its own (BodyId, JointId, RobotId) and one kind's id is never taken for another's.
template <class Tag>
struct SlotId {
  std::uint32_t index = 0;       // the object's slot in the world's store of its kind
  std::uint32_t generation = 0;  // the slot's generation when the object was added; 0: none
  // The default id: no object ever had it.
  [[nodiscard]] bool is_null() const { return generation == 0; }
  // The same slot and generation: the same object.
  friend bool operator==(const SlotId&, const SlotId&) = default;
};

}  // namespace sphys
