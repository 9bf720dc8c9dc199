#include "world/sleep_tracker.h"

#include <numeric>

namespace sphys {
namespace {

// Per group root: a body of the group falls asleep now.
constexpr std::uint8_t kFallsAsleep = 1;
// Per island root: an awake body of the island has not been still for long enough.
constexpr std::uint8_t kHasRestless = 2;
// How many times sleep.time a body waits before it sleeps while its island has a restless body.
constexpr float kPatience = 2.0f;
// A woken body keeps its still time (being asleep is being still) up to this share of
// sleep.time: restless a while yet, it keeps its neighbours awake and sleeps again only after
// its island has had time to settle what the disturbance pressed in. Kept up to the whole sleep
// time (not restless once woken), a heap woke only where it moved but slept again pressed in:
// 1,000 bunnies ended with one 1.4 mm into the plane, against 0.8 mm this way.
constexpr float kWokenStillShare = 0.5f;
constexpr std::uint32_t kNone = 0xFFFFFFFFu;

}  // namespace

void SleepTracker::resize(std::size_t bodies) {
  const std::size_t before = island_parent_.size();
  island_parent_.resize(bodies);
  group_parent_.resize(bodies);
  still_time_.resize(bodies, 0.0f);
  next_asleep_.resize(bodies);
  flags_.resize(bodies, 0);
  ring_first_.resize(bodies);
  ring_last_.resize(bodies);
  for (std::size_t i = before; i < bodies; ++i) {
    next_asleep_[i] = static_cast<std::uint32_t>(i);
    island_parent_[i] = static_cast<std::uint32_t>(i);  // an island of its own
  }
}

void SleepTracker::wake(std::uint32_t body, const SleepSettings& settings,
                        std::vector<std::uint32_t>& woken) {
  if (!store_->asleep(body)) return;
  std::uint32_t member = body;
  do {
    const std::uint32_t next = next_asleep_[member];
    store_->set_asleep(member, false);
    next_asleep_[member] = member;
    still_time_[member] = std::min(still_time_[member], kWokenStillShare * settings.time);
    woken.push_back(member);
    member = next;
  } while (member != body);
}

std::uint32_t SleepTracker::root(std::vector<std::uint32_t>& parent, std::uint32_t body) {
  while (parent[body] != body) {
    parent[body] = parent[parent[body]];  // path halving
    body = parent[body];
  }
  return body;
}

void SleepTracker::join(std::vector<std::uint32_t>& parent, std::uint32_t a, std::uint32_t b) {
  const std::uint32_t ra = root(parent, a);
  const std::uint32_t rb = root(parent, b);
  if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
}

void SleepTracker::link_islands(std::span<const Contact> contacts) {
  const std::span<const std::uint8_t> dynamic = store_->dynamic();
  for (const Contact& contact : contacts) {
    if (contact.body_a == kGroundPlaneBody) continue;
    if (dynamic[contact.body_a] != 0 && dynamic[contact.body_b] != 0) {
      join(island_parent_, contact.body_a, contact.body_b);
    }
  }
}

void SleepTracker::split_islands(std::span<const Contact> contacts) {
  if (!split_) return;
  split_ = false;
  std::iota(island_parent_.begin(), island_parent_.end(), 0u);
  link_islands(contacts);
  for (std::uint32_t i = 0; i < island_parent_.size(); ++i) {
    if (store_->asleep(i)) join(island_parent_, i, next_asleep_[i]);
  }
}

std::span<const std::uint32_t> SleepTracker::islands() {
  island_.resize(island_parent_.size());
  for (std::uint32_t i = 0; i < island_parent_.size(); ++i) island_[i] = island(i);
  return island_;
}

void SleepTracker::wake_disturbed(std::span<const Contact> contacts, const SleepSettings& settings,
                                  std::vector<std::uint32_t>& woken) {
  for (const Contact& contact : contacts) {
    if (contact.body_a == kGroundPlaneBody) continue;
    const std::uint32_t a = contact.body_a;
    const std::uint32_t b = contact.body_b;
    if (store_->asleep(a) && restless(b, settings)) wake(a, settings, woken);
    if (store_->asleep(b) && restless(a, settings)) wake(b, settings, woken);
  }
}

std::uint32_t SleepTracker::update(std::span<const float> speeds, std::span<const Contact> contacts,
                                   float dt, const SleepSettings& settings,
                                   std::vector<std::uint32_t>& fell_asleep) {
  const std::span<const std::uint8_t> dynamic = store_->dynamic();
  std::uint32_t islands = 0;
  for (std::uint32_t i = 0; i < island_parent_.size(); ++i) {
    if (dynamic[i] == 0) continue;
    if (island(i) == i) ++islands;
    if (store_->asleep(i)) continue;
    still_time_[i] = speeds[i] < settings.speed ? still_time_[i] + dt : 0.0f;
  }
  if (!settings.enabled) return islands;
  // Who settles: awake, still for long enough, and touching no restless body. A restless body
  // keeps its neighbours awake, so that what it pushes against yields; beyond them a heap sleeps
  // (1,000 bunnies in one heap stayed awake for 7 s while a few of them rocked).
  // In an island with a restless body a body waits kPatience times longer: time for its
  // penetration recovery to finish under the load of what still moves above it.
  std::fill(flags_.begin(), flags_.end(), std::uint8_t{0});
  for (std::uint32_t i = 0; i < island_parent_.size(); ++i) {
    if (restless(i, settings)) flags_[island(i)] = kHasRestless;
  }
  settles_.assign(island_parent_.size(), 0);
  for (std::uint32_t i = 0; i < island_parent_.size(); ++i) {
    const float wait =
        flags_[island(i)] == kHasRestless ? kPatience * settings.time : settings.time;
    settles_[i] = dynamic[i] != 0 && !store_->asleep(i) && still_time_[i] >= wait ? 1 : 0;
  }
  for (const Contact& contact : contacts) {
    if (contact.body_a == kGroundPlaneBody) continue;
    if (restless(contact.body_b, settings)) settles_[contact.body_a] = 0;
    if (restless(contact.body_a, settings)) settles_[contact.body_b] = 0;
  }
  // Groups: the settling bodies joined by their contacts to one another and to sleeping bodies,
  // whose groups they join.
  std::iota(group_parent_.begin(), group_parent_.end(), 0u);
  for (std::uint32_t i = 0; i < group_parent_.size(); ++i) {
    if (store_->asleep(i)) join(group_parent_, i, next_asleep_[i]);
  }
  const auto sleeps = [&](std::uint32_t body) {
    return settles_[body] != 0 || store_->asleep(body);
  };
  for (const Contact& contact : contacts) {
    if (contact.body_a == kGroundPlaneBody) continue;
    if (sleeps(contact.body_a) && sleeps(contact.body_b)) {
      join(group_parent_, contact.body_a, contact.body_b);
    }
  }
  std::fill(flags_.begin(), flags_.end(), std::uint8_t{0});
  for (std::uint32_t i = 0; i < island_parent_.size(); ++i) {
    if (settles_[i] != 0) flags_[root(group_parent_, i)] |= kFallsAsleep;
  }
  // Every body of a group that gains a sleeper, the ones already asleep in it included, goes
  // into one circular list, so that waking any of them wakes them all.
  std::fill(ring_last_.begin(), ring_last_.end(), kNone);
  for (std::uint32_t i = 0; i < island_parent_.size(); ++i) {
    if (!sleeps(i)) continue;
    const std::uint32_t group = root(group_parent_, i);
    if ((flags_[group] & kFallsAsleep) == 0) continue;
    if (!store_->asleep(i)) {
      store_->set_asleep(i, true);
      fell_asleep.push_back(i);
    }
    if (ring_last_[group] == kNone) {
      ring_first_[group] = i;
    } else {
      next_asleep_[ring_last_[group]] = i;
    }
    ring_last_[group] = i;
  }
  for (std::uint32_t group = 0; group < island_parent_.size(); ++group) {
    if (ring_last_[group] != kNone) next_asleep_[ring_last_[group]] = ring_first_[group];
  }
  return islands;
}

}  // namespace sphys
