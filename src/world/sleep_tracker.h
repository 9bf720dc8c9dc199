#pragma once

// Islands of touching bodies and their sleep (Box2D's scheme): an island whose bodies have all
// been still for a while sleeps, and wakes as a whole when a body that is not still joins it.

#include <cstdint>
#include <span>
#include <vector>

#include "sphys/contact.h"
#include "sphys/world.h"

namespace sphys {

class SleepTracker {
 public:
  // Slots for `bodies` bodies; new slots are awake.
  void resize(std::size_t bodies);
  [[nodiscard]] bool asleep(std::uint32_t body) const { return asleep_[body] != 0; }
  // Wakes a sleeping body and every body it fell asleep with, appending them to `woken`.
  void wake(std::uint32_t body, std::vector<std::uint32_t>& woken);

  // Islands: moving bodies (`dynamic[i] != 0`) touching by a contact share one; a sleeping body
  // is in one with the bodies it fell asleep with. Static bodies and the ground join nothing.
  void build_islands(std::span<const Contact> contacts, std::span<const std::uint8_t> dynamic);
  // Per body, the island it is in (a name shared by the island's bodies), as of the last
  // build_islands(). Valid until the next call of any other member.
  [[nodiscard]] std::span<const std::uint32_t> islands();
  // Wakes the sleeping bodies of every island that holds an awake body not still for long enough,
  // appending them to `woken`.
  void wake_disturbed(const SleepSettings& settings, std::vector<std::uint32_t>& woken);
  // Counts how long each awake moving body has been still (`speeds[i]`: its fastest point's
  // speed, unit: m/s), then puts to sleep every island whose bodies have all been still for
  // settings.time, appending them to `fell_asleep`. Returns the number of islands.
  std::uint32_t update(std::span<const float> speeds, std::span<const std::uint8_t> dynamic,
                       float dt, const SleepSettings& settings,
                       std::vector<std::uint32_t>& fell_asleep);

 private:
  [[nodiscard]] std::uint32_t root(std::uint32_t body);
  void join(std::uint32_t a, std::uint32_t b);

  std::vector<std::uint32_t> parent_;  // union-find of the islands
  std::vector<std::uint32_t> island_;  // islands(), scratch
  std::vector<std::uint8_t> asleep_;
  std::vector<float> still_time_;           // unit: s
  std::vector<std::uint32_t> next_asleep_;  // circular list of the bodies that fell asleep together
  std::vector<std::uint8_t> flags_;         // per island root, scratch
  std::vector<std::uint32_t> ring_first_;   // per island root, scratch
  std::vector<std::uint32_t> ring_last_;
};

}  // namespace sphys
