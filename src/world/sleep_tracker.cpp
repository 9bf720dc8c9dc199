#include "world/sleep_tracker.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <numeric>

#include "core/buffers.h"
#include "core/place_in_runs.h"

namespace sphys {
namespace {

// How many times sleep.time a body waits before it sleeps while its island has a restless body.
constexpr float kPatience = 2.0f;
// A woken body keeps its still time (being asleep is being still) up to this share of
// sleep.time: restless a while yet, it keeps its neighbours awake and sleeps again only after
// its island has had time to settle what the disturbance pressed in. Kept up to the whole sleep
// time (not restless once woken), a heap woke only where it moved but slept again pressed in:
// 1,000 bunnies ended with one 1.4 mm into the plane, against 0.8 mm this way.
constexpr float kWokenStillShare = 0.5f;
// The speed of a body set moving from outside until count_still_time() counts it: moving. unit: m/s
constexpr float kUnmeasured = std::numeric_limits<float>::infinity();

// Contacts or body slots per item of the threaded loops. unit: items
constexpr std::size_t kItemsPerRun = 256;

using Slot = std::atomic_ref<std::uint32_t>;

// Stores 1 in a byte that other threads may store the same into.
void mark(std::uint8_t& flag, std::uint8_t value) {
  std::atomic_ref<std::uint8_t>(flag).store(value, std::memory_order_relaxed);
}

}  // namespace

SleepTracker::SleepTracker(BodyStore& bodies) : store_(&bodies) { bodies.attach(*this); }

void SleepTracker::grow_slots(std::uint32_t slots) {
  const std::size_t before = island_parent_.size();
  island_parent_.resize(slots);
  still_time_.resize(slots, 0.0f);
  speed_.resize(slots, kUnmeasured);
  has_restless_.resize(slots, 0);
  for (std::size_t i = before; i < slots; ++i) {
    island_parent_[i] = static_cast<std::uint32_t>(i);  // an island of its own
  }
}

void SleepTracker::note_woken(std::uint32_t body, const SleepSettings& settings) {
  still_time_[body] = std::min(still_time_[body], kWokenStillShare * settings.time);
  speed_[body] = 0.0f;  // it slept at rest
}

void SleepTracker::wake(std::uint32_t body, const SleepSettings& settings,
                        std::vector<std::uint32_t>& woken) {
  if (!store_->asleep(body)) return;
  note_woken(body, settings);
  woken.push_back(body);
  store_->set_asleep(body, false);
}

void SleepTracker::unsettle(std::uint32_t body) {
  still_time_[body] = 0.0f;
  speed_[body] = kUnmeasured;
}

std::uint32_t SleepTracker::island(std::uint32_t body) {
  for (;;) {
    Slot parent(island_parent_[body]);
    std::uint32_t up = parent.load(std::memory_order_relaxed);
    if (up == body) return body;
    // Path halving: the parent skips to the grandparent, unless another thread moved it first.
    const std::uint32_t grand = Slot(island_parent_[up]).load(std::memory_order_relaxed);
    if (grand == up) return up;
    parent.compare_exchange_weak(up, grand, std::memory_order_relaxed);
    body = grand;
  }
}

// The larger root joins the smaller, once it is still a root when it does: each set's root is
// then its smallest slot, in whatever order the joins came.
void SleepTracker::join(std::uint32_t a, std::uint32_t b) {
  for (;;) {
    std::uint32_t larger = island(a);
    std::uint32_t smaller = island(b);
    if (larger == smaller) return;
    if (larger < smaller) std::swap(larger, smaller);
    std::uint32_t expected = larger;
    if (Slot(island_parent_[larger])
            .compare_exchange_strong(expected, smaller, std::memory_order_relaxed)) {
      return;
    }
  }
}

void SleepTracker::link_islands(std::span<const Contact> contacts) {
  const std::span<const std::uint8_t> dynamic = store_->dynamic();
  threads_or_caller(parallel_).for_each_run(
      contacts.size(), kItemsPerRun, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
          const Contact& contact = contacts[k];
          if (contact.body_a == kGroundPlaneBody) continue;
          if (dynamic[contact.body_a] != 0 && dynamic[contact.body_b] != 0) {
            join(contact.body_a, contact.body_b);
          }
        }
      });
  for (const auto& [a, b] : joined_) {
    if (dynamic[a] != 0 && dynamic[b] != 0) join(a, b);
  }
}

void SleepTracker::split_islands(std::span<const Contact> contacts) {
  if (!split_) return;
  split_ = false;
  threads_or_caller(parallel_).for_each_run(island_parent_.size(), kItemsPerRun,
                                            [&](std::size_t begin, std::size_t end) {
                                              for (std::size_t i = begin; i < end; ++i) {
                                                island_parent_[i] = static_cast<std::uint32_t>(i);
                                              }
                                            });
  link_islands(contacts);
}

std::span<const std::uint32_t> SleepTracker::islands() {
  island_.resize(island_parent_.size());
  for (std::uint32_t i = 0; i < island_parent_.size(); ++i) island_[i] = island(i);
  return island_;
}

void SleepTracker::wake_disturbed(std::span<const Contact> contacts, const SleepSettings& settings,
                                  std::vector<std::uint32_t>& woken) {
  // The store wakes them together after the pass (one listing of the awake bodies). A body
  // woken in the pass wakes no other in it: its speed is 0 until count_still_time() counts one,
  // slower than any positive sleep.speed (with sleep.speed 0 it wakes its neighbours in the world's
  // next round of waking instead).
  // Marked on the threads (who wakes depends on the store and the moving bodies' speeds alone,
  // which waking changes only after the pass), then listed in slot order.
  const Parallel& parallel = threads_or_caller(parallel_);
  const std::size_t first = woken.size();
  const auto wakes = [&](std::uint32_t sleeper, std::uint32_t other) {
    return store_->asleep(sleeper) && store_->moving()[other] != 0 &&
           speed_[other] >= settings.speed;
  };
  fill_buffer(woken_, island_parent_.size(), std::uint8_t{0});
  parallel.for_each_run(contacts.size(), kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const Contact& contact = contacts[k];
      if (contact.body_a == kGroundPlaneBody) continue;
      if (wakes(contact.body_a, contact.body_b)) mark(woken_[contact.body_a], 1);
      if (wakes(contact.body_b, contact.body_a)) mark(woken_[contact.body_b], 1);
    }
  });
  // A joint wakes its sleeping body whatever the speed of the other: a sleeping body counts as
  // static in the solve, and would hold an awake one where it fell asleep.
  for (const auto& [a, b] : joined_) {
    if (store_->asleep(a) && store_->moving()[b] != 0) woken_[a] = 1;
    if (store_->asleep(b) && store_->moving()[a] != 0) woken_[b] = 1;
  }
  compact_in_runs(
      parallel, woken_.size(), kItemsPerRun, [&](std::size_t i) { return woken_[i] != 0; },
      [&](std::size_t count) { woken.resize(first + count); },
      [&](std::size_t position, std::size_t i) {
        woken[first + position] = static_cast<std::uint32_t>(i);
      },
      run_first_);
  for (std::size_t k = first; k < woken.size(); ++k) note_woken(woken[k], settings);
  store_->set_asleep(std::span(woken).subspan(first), false);
}

void SleepTracker::settle_joined() {
  if (joined_.empty()) return;
  const std::span<const std::uint8_t> dynamic = store_->dynamic();
  joined_group_.resize(settles_.size());
  std::iota(joined_group_.begin(), joined_group_.end(), 0u);
  const auto group = [&](std::uint32_t body) {
    while (joined_group_[body] != body) {
      joined_group_[body] = joined_group_[joined_group_[body]];  // path halving
      body = joined_group_[body];
    }
    return body;
  };
  for (const auto& [a, b] : joined_) {
    if (dynamic[a] == 0 || dynamic[b] == 0) continue;
    const std::uint32_t ga = group(a);
    const std::uint32_t gb = group(b);
    if (ga != gb) joined_group_[std::max(ga, gb)] = std::min(ga, gb);
  }
  joined_awake_.assign(settles_.size(), 0);
  for (std::uint32_t i = 0; i < settles_.size(); ++i) {
    if (dynamic[i] != 0 && !store_->asleep(i) && settles_[i] == 0) joined_awake_[group(i)] = 1;
  }
  for (std::uint32_t i = 0; i < settles_.size(); ++i) {
    if (settles_[i] != 0 && joined_awake_[group(i)] != 0) settles_[i] = 0;
  }
}

std::uint32_t SleepTracker::update(std::span<const Contact> contacts, const SleepSettings& settings,
                                   std::vector<std::uint32_t>& fell_asleep) {
  const Parallel& parallel = threads_or_caller(parallel_);
  const std::span<const std::uint8_t> dynamic = store_->dynamic();
  const std::size_t slots = island_parent_.size();
  // An island's root is its own parent.
  std::atomic<std::uint32_t> islands{0};
  parallel.for_each_run(slots, kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    std::uint32_t roots = 0;
    for (std::size_t i = begin; i < end; ++i) {
      if (dynamic[i] != 0 && island_parent_[i] == i) ++roots;
    }
    islands.fetch_add(roots, std::memory_order_relaxed);
  });
  if (!settings.enabled) return islands.load();
  // Who settles: awake, still for long enough and touching no restless body. A restless body
  // keeps its neighbours awake, so that what it pushes against yields; beyond them a heap sleeps
  // (1,000 bunnies in one heap stayed awake for 7 s while a few of them rocked). In an island
  // with a restless body a body waits kPatience times longer: time for its contacts to settle
  // under the load of what still moves above it.
  fill_buffer(has_restless_, slots, std::uint8_t{0});
  parallel.for_each_run(slots, kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const auto body = static_cast<std::uint32_t>(i);
      if (restless(body, settings)) mark(has_restless_[island(body)], 1);
    }
  });
  resize_buffer(settles_, slots);
  parallel.for_each_run(slots, kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const auto body = static_cast<std::uint32_t>(i);
      settles_[i] = 0;
      if (dynamic[i] == 0 || store_->asleep(body)) continue;
      const float patience = has_restless_[island(body)] != 0 ? kPatience : 1.0f;
      settles_[i] = still_time_[i] >= patience * settings.time ? 1 : 0;
    }
  });
  parallel.for_each_run(contacts.size(), kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const Contact& contact = contacts[k];
      if (contact.body_a == kGroundPlaneBody) continue;
      if (restless(contact.body_b, settings)) mark(settles_[contact.body_a], 0);
      if (restless(contact.body_a, settings)) mark(settles_[contact.body_b], 0);
    }
  });
  settle_joined();
  const std::size_t first = fell_asleep.size();
  compact_in_runs(
      parallel, slots, kItemsPerRun, [&](std::size_t i) { return settles_[i] != 0; },
      [&](std::size_t count) { fell_asleep.resize(first + count); },
      [&](std::size_t position, std::size_t i) {
        fell_asleep[first + position] = static_cast<std::uint32_t>(i);
      },
      run_first_);
  store_->set_asleep(std::span(fell_asleep).subspan(first), true);
  return islands.load();
}

}  // namespace sphys
