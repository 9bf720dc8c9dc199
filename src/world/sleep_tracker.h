#pragma once

// Islands of touching bodies, and sleep by neighbourhood: a body sleeps once it and every moving
// body it touches have been still for a while, so that a restless body keeps awake only its
// neighbours and not a whole heap; the bodies that fall asleep touching one another (or bodies
// asleep already) sleep as one group, and a restless body touching any of them wakes them all.

#include <cstdint>
#include <span>
#include <vector>

#include "sphys/body_store.h"
#include "sphys/contact.h"
#include "sphys/world.h"

namespace sphys {

class SleepTracker {
 public:
  // Sleep is the store's: the tracker puts its bodies to sleep and wakes them there. `bodies`
  // must outlive the tracker.
  explicit SleepTracker(BodyStore* bodies) : store_(bodies) {}
  // Slots for `bodies` bodies.
  void resize(std::size_t bodies);
  // Wakes a sleeping body and every body it fell asleep with, appending them to `woken`. Being
  // asleep is being still: they keep their still time, up to half of settings.time, so that they
  // sleep again after half the sleep time still rather than a whole one (or twice that while their
  // island holds a restless body, update()).
  void wake(std::uint32_t body, const SleepSettings& settings, std::vector<std::uint32_t>& woken);
  // The body was set moving from outside (a velocity or an impulse): restless until it has been
  // still for the sleep time again.
  void unsettle(std::uint32_t body) { still_time_[body] = 0.0f; }

  // Islands: dynamic bodies touching by a contact share one; a sleeping body is in one with the
  // bodies it fell asleep with. Static bodies and the ground join nothing. They persist from
  // step to step: link_islands() merges the islands that contacts join, and an island whose
  // bodies may have parted stays whole until split_islands() builds them afresh, so an island
  // may join more bodies than touch (a coarser grouping, which the solver and sleep allow).
  void link_islands(std::span<const Contact> contacts);
  // Two dynamic bodies that touched have parted, or a body left: split at the next
  // split_islands().
  void parted() { split_ = true; }
  // Builds the islands afresh from `contacts` and the sleeping groups, if parted() was called
  // since the last time.
  void split_islands(std::span<const Contact> contacts);
  // Per body, the island it is in (a name shared by the island's bodies). Valid until the next
  // call of any other member.
  [[nodiscard]] std::span<const std::uint32_t> islands();
  // Wakes the group of every sleeping body that a contact joins to a restless body (an awake
  // moving body not still for settings.time), appending them to `woken`.
  void wake_disturbed(std::span<const Contact> contacts, const SleepSettings& settings,
                      std::vector<std::uint32_t>& woken);
  // Counts how long each awake moving body has been still (`speeds[i]`: its fastest point's
  // speed, unit: m/s), then puts to sleep every body still for settings.time that touches no
  // restless body, appending them to `fell_asleep`. Returns the number of islands.
  std::uint32_t update(std::span<const float> speeds, std::span<const Contact> contacts, float dt,
                       const SleepSettings& settings, std::vector<std::uint32_t>& fell_asleep);

 private:
  // Union-find over body slots: path halving, the smaller slot the root of a set.
  [[nodiscard]] static std::uint32_t root(std::vector<std::uint32_t>& parent, std::uint32_t body);
  static void join(std::vector<std::uint32_t>& parent, std::uint32_t a, std::uint32_t b);
  [[nodiscard]] std::uint32_t island(std::uint32_t body) { return root(island_parent_, body); }
  // An awake dynamic body not still for settings.time yet.
  [[nodiscard]] bool restless(std::uint32_t body, const SleepSettings& settings) const {
    return store_->moving()[body] != 0 && still_time_[body] < settings.time;
  }

  BodyStore* store_;
  std::vector<std::uint32_t> island_parent_;  // the islands
  std::vector<std::uint32_t> group_parent_;   // update()'s sleeping groups, scratch
  bool split_ = false;
  std::vector<std::uint32_t> island_;       // islands(), scratch
  std::vector<float> still_time_;           // unit: s
  std::vector<std::uint32_t> next_asleep_;  // circular list of the bodies that fell asleep together
  std::vector<std::uint8_t> flags_;         // per island or sleep group root, scratch
  std::vector<std::uint8_t> settles_;       // per body: may fall asleep in this update, scratch
  std::vector<std::uint32_t> ring_first_;   // per sleep group root, scratch
  std::vector<std::uint32_t> ring_last_;
};

}  // namespace sphys
