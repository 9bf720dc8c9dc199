#pragma once

// Keeps calls on one world from racing (docs/reliability.md): a step or a change holds the world
// alone, reads share it. A call that finds the world held in a way it cannot share throws
// sphys::Error at once instead of waiting: two threads calling into one world without taking
// turns is a bug in the caller, and waiting would hide it (Box2D's world lock asserts for the
// same reason). Python's bindings take turns with a lock of their own before calling. The cost is
// one atomic read-modify-write at each end of a call.

#include <atomic>
#include <cstdint>
#include <string_view>

namespace sphys {

class WorldAccess {
 public:
  // Why a call holds the world alone; the error of a call it turns away names it.
  enum class Holder : std::uint8_t { kStep, kChange };

  // `call` names the call in the sphys::Error thrown when the world cannot be held so.
  void hold_alone(Holder holder, std::string_view call);
  void release_alone();
  void hold_shared(std::string_view call);
  void release_shared();

  // Held alone for a step or a change, for a scope.
  class Alone {
   public:
    Alone(WorldAccess& access, Holder holder, std::string_view call) : access_(access) {
      access_.hold_alone(holder, call);
    }
    ~Alone() { access_.release_alone(); }
    Alone(const Alone&) = delete;
    Alone& operator=(const Alone&) = delete;

   private:
    WorldAccess& access_;
  };

  // Held for reading, shared with other reads (of this thread or others), for a scope.
  class Shared {
   public:
    Shared(WorldAccess& access, std::string_view call) : access_(access) {
      access_.hold_shared(call);
    }
    ~Shared() { access_.release_shared(); }
    Shared(const Shared&) = delete;
    Shared& operator=(const Shared&) = delete;

   private:
    WorldAccess& access_;
  };

 private:
  // While a step or change holds the world, its bit (world_access.cpp); else the reads under way.
  std::atomic<std::uint32_t> state_{0};
};

}  // namespace sphys
