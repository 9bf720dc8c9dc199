#include "world/sleep_tracker.h"

#include <numeric>

namespace sphys {
namespace {

// Per island root, what its members are.
constexpr std::uint8_t kHasSleeper = 1;
constexpr std::uint8_t kHasRestless = 2;  // an awake body not still for long enough
constexpr std::uint8_t kHasAwake = 4;
constexpr std::uint8_t kFallsAsleep = 8;
constexpr std::uint32_t kNone = 0xFFFFFFFFu;

}  // namespace

void SleepTracker::resize(std::size_t bodies) {
  const std::size_t before = asleep_.size();
  parent_.resize(bodies);
  asleep_.resize(bodies, 0);
  still_time_.resize(bodies, 0.0f);
  next_asleep_.resize(bodies);
  flags_.resize(bodies, 0);
  ring_first_.resize(bodies);
  ring_last_.resize(bodies);
  for (std::size_t i = before; i < bodies; ++i) {
    next_asleep_[i] = static_cast<std::uint32_t>(i);
  }
}

void SleepTracker::wake(std::uint32_t body, std::vector<std::uint32_t>& woken) {
  if (asleep_[body] == 0) {
    still_time_[body] = 0.0f;
    return;
  }
  std::uint32_t member = body;
  do {
    const std::uint32_t next = next_asleep_[member];
    asleep_[member] = 0;
    still_time_[member] = 0.0f;
    next_asleep_[member] = member;
    woken.push_back(member);
    member = next;
  } while (member != body);
}

std::uint32_t SleepTracker::root(std::uint32_t body) {
  while (parent_[body] != body) {
    parent_[body] = parent_[parent_[body]];  // path halving
    body = parent_[body];
  }
  return body;
}

void SleepTracker::join(std::uint32_t a, std::uint32_t b) {
  const std::uint32_t ra = root(a);
  const std::uint32_t rb = root(b);
  if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
}

void SleepTracker::build_islands(std::span<const Contact> contacts,
                                 std::span<const std::uint8_t> dynamic) {
  std::iota(parent_.begin(), parent_.end(), 0u);
  for (const Contact& contact : contacts) {
    if (contact.body_a == kGroundPlaneBody) continue;
    if (dynamic[contact.body_a] != 0 && dynamic[contact.body_b] != 0) {
      join(contact.body_a, contact.body_b);
    }
  }
  for (std::uint32_t i = 0; i < asleep_.size(); ++i) {
    if (asleep_[i] != 0) join(i, next_asleep_[i]);
  }
}

std::span<const std::uint32_t> SleepTracker::islands() {
  island_.resize(parent_.size());
  for (std::uint32_t i = 0; i < parent_.size(); ++i) island_[i] = root(i);
  return island_;
}

void SleepTracker::wake_disturbed(const SleepSettings& settings,
                                  std::vector<std::uint32_t>& woken) {
  std::fill(flags_.begin(), flags_.end(), std::uint8_t{0});
  for (std::uint32_t i = 0; i < asleep_.size(); ++i) {
    if (asleep_[i] != 0) {
      flags_[root(i)] |= kHasSleeper;
    } else if (still_time_[i] < settings.time) {
      flags_[root(i)] |= kHasRestless;
    }
  }
  for (std::uint32_t i = 0; i < asleep_.size(); ++i) {
    const std::uint8_t flags = flags_[root(i)];
    if (asleep_[i] != 0 && (flags & kHasRestless) != 0) wake(i, woken);
  }
}

std::uint32_t SleepTracker::update(std::span<const float> speeds,
                                   std::span<const std::uint8_t> dynamic, float dt,
                                   const SleepSettings& settings,
                                   std::vector<std::uint32_t>& fell_asleep) {
  std::fill(flags_.begin(), flags_.end(), std::uint8_t{0});
  std::uint32_t islands = 0;
  for (std::uint32_t i = 0; i < asleep_.size(); ++i) {
    if (dynamic[i] == 0) continue;
    const std::uint32_t island = root(i);
    if (island == i) ++islands;
    if (asleep_[i] != 0) continue;
    still_time_[i] = speeds[i] < settings.speed ? still_time_[i] + dt : 0.0f;
    flags_[island] |= kHasAwake;
    if (still_time_[i] < settings.time) flags_[island] |= kHasRestless;
  }
  if (!settings.enabled) return islands;
  for (std::uint32_t i = 0; i < asleep_.size(); ++i) {
    std::uint8_t& flags = flags_[root(i)];
    if (dynamic[i] != 0 && (flags & kHasAwake) != 0 && (flags & kHasRestless) == 0) {
      flags |= kFallsAsleep;
    }
  }
  // Every body of a falling island, the ones already asleep in it included, goes into one
  // circular list, so that waking any of them wakes them all.
  std::fill(ring_last_.begin(), ring_last_.end(), kNone);
  for (std::uint32_t i = 0; i < asleep_.size(); ++i) {
    if (dynamic[i] == 0) continue;
    const std::uint32_t island = root(i);
    if ((flags_[island] & kFallsAsleep) == 0) continue;
    if (asleep_[i] == 0) {
      asleep_[i] = 1;
      fell_asleep.push_back(i);
    }
    if (ring_last_[island] == kNone) {
      ring_first_[island] = i;
    } else {
      next_asleep_[ring_last_[island]] = i;
    }
    ring_last_[island] = i;
  }
  for (std::uint32_t island = 0; island < asleep_.size(); ++island) {
    if (ring_last_[island] != kNone) next_asleep_[ring_last_[island]] = ring_first_[island];
  }
  return islands;
}

}  // namespace sphys
