#pragma once

// Islands of touching bodies, and sleep body by body: a body sleeps once it has been still for a
// while, touching no restless body; a sleeping body wakes alone, when a body touching it moves. A
// blow then wakes a sleeping heap only as far as it moves bodies, and a restless body keeps awake
// only its neighbours.

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "sphys/body_store.h"
#include "sphys/contact.h"
#include "sphys/parallel.h"
#include "sphys/world.h"

namespace sphys {

class SleepTracker final : public SlotArrays {
 public:
  // Sleep is the store's: the tracker puts its bodies to sleep and wakes them there, and its
  // per-body arrays grow with the store's. `bodies` must outlive the tracker.
  explicit SleepTracker(BodyStore& bodies);

  void grow_slots(std::uint32_t slots) override;
  // The threads its loops run on (none: the caller's alone), the same results whatever their
  // number. `parallel` must outlive the tracker's use or be replaced first.
  void use_threads(const Parallel* parallel) { parallel_ = parallel; }
  // Wakes a sleeping body, appending it to `woken`. Being asleep is being still: it keeps its
  // still time, up to half of settings.time, so that it sleeps again after half the sleep time
  // still rather than a whole one (or twice that while its island holds a restless body,
  // update()).
  void wake(std::uint32_t body, const SleepSettings& settings, std::vector<std::uint32_t>& woken);
  // The body was set moving from outside (a velocity, an impulse, a new body): restless until it
  // has been still for the sleep time again, and moving until count_still_time() counts it.
  void unsettle(std::uint32_t body);

  // The body pairs joints join (store slots, not the world): such bodies are one island, sleep
  // together and wake together. Replaces the last list.
  void set_joined(std::span<const std::pair<std::uint32_t, std::uint32_t>> joined) {
    joined_.assign(joined.begin(), joined.end());
  }

  // Islands: dynamic bodies touching by a contact or joined by a joint share one; a sleeping body
  // is in one of its own. Static bodies and the ground join nothing. An island's name is its
  // smallest slot, whatever order its bodies were joined in, so joining on the threads names it as
  // one thread does. They persist from step to step: link_islands() merges the islands that
  // contacts join, and an island whose bodies may have parted stays whole until split_islands()
  // builds them afresh, so an island may join more bodies than touch (a coarser grouping, which the
  // solver and sleep allow).
  void link_islands(std::span<const Contact> contacts);
  // Two dynamic bodies that touched have parted, or a body left: split at the next
  // split_islands().
  void parted() { split_ = true; }
  // Builds the islands afresh from `contacts`, if parted() was called since the last time.
  void split_islands(std::span<const Contact> contacts);
  // Per body, the island it is in (a name shared by the island's bodies). Valid until the next
  // call of any other member.
  [[nodiscard]] std::span<const std::uint32_t> islands();
  // Wakes every sleeping body that a contact joins to an awake body that moves (as fast as
  // settings.speed at the last count_still_time()), or that a joint joins to an awake body,
  // appending them to `woken`.
  void wake_disturbed(std::span<const Contact> contacts, const SleepSettings& settings,
                      std::vector<std::uint32_t>& woken);
  // An awake body finished after a collision pass of `pass_dt` (unit: s): its speed, the
  // store's measure of its fastest point, and how long it has been still. Touches the body's
  // own entries alone, so bodies may count on several threads.
  void count_still_time(std::uint32_t body, float pass_dt, const SleepSettings& settings) {
    speed_[body] = store_->fastest_point_speeds()[body];
    still_time_[body] = speed_[body] < settings.speed ? still_time_[body] + pass_dt : 0.0f;
  }
  // Puts to sleep every awake body still for long enough (settings.time, or more in an island
  // with a restless body) that touches no restless body, and whose joined bodies all may sleep
  // too, appending them to `fell_asleep`.
  // Returns the number of islands.
  std::uint32_t update(std::span<const Contact> contacts, const SleepSettings& settings,
                       std::vector<std::uint32_t>& fell_asleep);

 private:
  // Union-find over body slots, the smaller slot the root of a set: the root of the body's set,
  // halving its path (on any thread: each parent is changed by a compare-and-swap, to an
  // ancestor); and the union of two sets, on any thread.
  [[nodiscard]] std::uint32_t island(std::uint32_t body);
  void join(std::uint32_t a, std::uint32_t b);
  // Bodies joined (transitively) to one that may not fall asleep may not either: settles_ per
  // group of joined bodies. One thread, in the joints' order.
  void settle_joined();
  // A sleeping body about to wake: keeps its still time (see wake()) and counts it as measured
  // at rest; the caller wakes it in the store.
  void note_woken(std::uint32_t body, const SleepSettings& settings);
  // An awake dynamic body not still for settings.time yet.
  [[nodiscard]] bool restless(std::uint32_t body, const SleepSettings& settings) const {
    return store_->moving()[body] != 0 && still_time_[body] < settings.time;
  }

  BodyStore* store_;
  const Parallel* parallel_ = nullptr;
  std::vector<std::uint32_t> island_parent_;  // the islands
  bool split_ = false;
  std::vector<std::uint32_t> island_;  // islands(), scratch
  std::vector<float> still_time_;      // unit: s
  // The fastest point's at the last count_still_time(), as sleep sees it: a body set moving from
  // outside is moving, a woken one at rest, until counted again. unit: m/s
  std::vector<float> speed_;
  std::vector<std::uint8_t> has_restless_;  // per island root, scratch
  std::vector<std::uint8_t> settles_;       // per body: may fall asleep in this update, scratch
  std::vector<std::uint8_t> woken_;         // per body: wakes in wake_disturbed(), scratch
  std::vector<std::uint32_t> run_first_;    // place_in_runs()'s scratch
  std::vector<std::pair<std::uint32_t, std::uint32_t>> joined_;  // set_joined()'s
  std::vector<std::uint32_t> joined_group_;  // settle_joined()'s union-find, scratch
  std::vector<std::uint8_t> joined_awake_;   // per group root: a member stays awake, scratch
};

}  // namespace sphys
