#include "world/world_access.h"

#include <string>

#include "sphys/error.h"

namespace sphys {
namespace {

// WorldAccess::state_'s bits for a step or a change holding the world alone.
constexpr std::uint32_t kStepping = 1u << 31;
constexpr std::uint32_t kChanging = 1u << 30;

[[noreturn]] void turn_away(std::string_view call, std::uint32_t state) {
  const char* holder = (state & kStepping) != 0   ? "the world is being stepped"
                       : (state & kChanging) != 0 ? "the world is being changed"
                                                  : "the world is being read";
  throw Error(std::string(call) + ": " + holder +
              " on another thread (calls on one world must take turns: docs/reliability.md)");
}

}  // namespace

void WorldAccess::hold_alone(Holder holder, std::string_view call) {
  std::uint32_t idle = 0;
  const std::uint32_t held = holder == Holder::kStep ? kStepping : kChanging;
  if (!state_.compare_exchange_strong(idle, held, std::memory_order_acquire,
                                      std::memory_order_relaxed)) {
    turn_away(call, idle);
  }
}

void WorldAccess::release_alone() { state_.store(0, std::memory_order_release); }

void WorldAccess::hold_shared(std::string_view call) {
  std::uint32_t state = state_.load(std::memory_order_relaxed);
  do {
    if ((state & (kStepping | kChanging)) != 0) turn_away(call, state);
  } while (!state_.compare_exchange_weak(state, state + 1, std::memory_order_acquire,
                                         std::memory_order_relaxed));
}

void WorldAccess::release_shared() { state_.fetch_sub(1, std::memory_order_release); }

}  // namespace sphys
