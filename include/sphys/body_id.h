#pragma once

#include <cstdint>

namespace sphys {

// A body of a world: its slot in the world's body store and the slot's generation, so that the id
// of a removed body never names the body added in its slot later. Generations count from 1, so
// that the default id, generation 0, names no body (as Box2D's zero id and Jolt's default
// BodyID): every call given it throws sphys::Error. A handle, never a pointer: storage may move.
struct BodyId {
  std::uint32_t index = 0;       // the body's slot in the world's body store
  std::uint32_t generation = 0;  // the slot's generation when the body was added; 0: no body
  // The default id: no body ever had it.
  [[nodiscard]] bool is_null() const { return generation == 0; }
  // The same slot and generation: the same body.
  friend bool operator==(const BodyId&, const BodyId&) = default;
};

}  // namespace sphys
