// Islands that persist from step to step: merged as contacts join them, built afresh only after
// bodies parted, and always at least as coarse as what touches (the solver's condition); and
// sleep body by body: who settles, and who wakes whom.
#include "world/sleep_tracker.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

namespace sphys {
namespace {

Contact touching(std::uint32_t a, std::uint32_t b) {
  Contact contact;
  contact.body_a = a;
  contact.body_b = b;
  return contact;
}

// Five dynamic bodies and a static one (slot 5).
struct Bodies {
  BodyStore store;
  SleepTracker tracker{store};

  Bodies() {
    RigidBody body;
    body.inverse_mass = 1.0f;
    for (int i = 0; i < 5; ++i) store.add(body, 0.5f);
    body.is_static = true;
    store.add(body, 0.5f);
  }

  // Each awake body's speed (`speeds[i]`, m/s), finished as a collision pass of `dt` (unit: s)
  // finishes it: its speed measured, its still time counted.
  void move_at(const std::vector<float>& speeds, float dt, const SleepSettings& settings) {
    for (const std::uint32_t i : store.awake()) {
      store.linear_velocities()[i] = Vec3(speeds[i], 0.0f, 0.0f);
      store.measure_fastest_point_speed(i);
      tracker.count_still_time(i, dt, settings);
    }
  }

  // The bodies of each island, by the island's name.
  std::vector<std::uint32_t> islands() {
    const std::span<const std::uint32_t> island = tracker.islands();
    return {island.begin(), island.end() - 1};  // the static body's is of no concern
  }
};

TEST(SleepTracker, IslandsMergeWhereContactsJoinThem) {
  Bodies bodies;
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));  // each its own
  const std::vector<Contact> first{touching(0, 1), touching(3, 4), touching(kGroundPlaneBody, 2)};
  bodies.tracker.link_islands(first);
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 0, 2, 3, 3}));
  // A static body joins nothing: 2 and 3 both touch it and stay apart.
  const std::vector<Contact> through_static{touching(2, 5), touching(5, 3)};
  bodies.tracker.link_islands(through_static);
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 0, 2, 3, 3}));
  const std::vector<Contact> bridge{touching(1, 3)};
  bodies.tracker.link_islands(bridge);
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 0, 2, 0, 0}));
}

TEST(SleepTracker, IslandsPersistUntilBodiesPartThenSplitOnce) {
  Bodies bodies;
  const std::vector<Contact> chain{touching(0, 1), touching(1, 2), touching(2, 3)};
  bodies.tracker.link_islands(chain);
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 0, 0, 0, 4}));
  // The middle link is gone, but nobody said a pair parted: the island stays whole (coarser
  // than what touches, which the solver allows).
  const std::vector<Contact> broken{touching(0, 1), touching(2, 3)};
  bodies.tracker.split_islands(broken);
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 0, 0, 0, 4}));
  bodies.tracker.parted();
  bodies.tracker.split_islands(broken);
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 0, 2, 2, 4}));
  // Joined again, and no pair parted since the split: the next split keeps them joined.
  bodies.tracker.link_islands(chain);
  bodies.tracker.split_islands(broken);
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 0, 0, 0, 4}));
}

// Still for twice the sleep time, at `speeds` (m/s), touching by `contacts`.
std::vector<std::uint32_t> settle(Bodies& bodies, const std::vector<float>& speeds,
                                  const std::vector<Contact>& contacts) {
  std::vector<std::uint32_t> fell_asleep;
  bodies.move_at(speeds, 2.0f * SleepSettings{}.time, SleepSettings{});
  (void)bodies.tracker.update(contacts, SleepSettings{}, fell_asleep);
  return fell_asleep;
}

TEST(SleepTracker, ASleepingBodyIsAnIslandOfItsOwnAcrossASplit) {
  Bodies bodies;
  const std::vector<Contact> pair{touching(1, 2)};
  bodies.tracker.link_islands(pair);
  // Still for long enough, touching only each other: bodies 1 and 2 fall asleep.
  std::vector<float> speeds(bodies.store.slots(), 0.0f);
  speeds[0] = speeds[3] = speeds[4] = 1.0f;  // m/s, restless
  EXPECT_EQ(settle(bodies, speeds, pair), (std::vector<std::uint32_t>{1, 2}));
  EXPECT_TRUE(bodies.store.asleep(1));
  // Asleep, the pair makes no contacts: a split leaves each on its own.
  bodies.tracker.parted();
  bodies.tracker.split_islands({});
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
}

// Body 1 touches a restless body: still for twice the sleep time, it stays awake; body 2 sleeps.
TEST(SleepTracker, ABodyTouchingARestlessOneWaitsLonger) {
  Bodies bodies;
  std::vector<float> speeds(bodies.store.slots(), 0.0f);
  speeds[0] = speeds[3] = speeds[4] = 1.0f;  // m/s, restless
  EXPECT_EQ(settle(bodies, speeds, {touching(0, 1)}), (std::vector<std::uint32_t>{2}));
}

// A row 0-1-2 and body 3 beside body 4, bodies 1, 2 and 4 asleep. Only a body that moves wakes
// what it touches, and that alone.
TEST(SleepTracker, ASleepingBodyWakesAloneWhenWhatTouchesItMoves) {
  Bodies bodies;
  std::vector<float> speeds(bodies.store.slots(), 0.0f);
  speeds[0] = speeds[3] = 1.0f;  // m/s, restless
  const std::vector<Contact> row{touching(0, 1), touching(1, 2)};
  ASSERT_EQ(settle(bodies, speeds, row), (std::vector<std::uint32_t>{2, 4}));
  // Body 0 drifts off for a while: body 1 settles.
  const std::vector<Contact> apart{touching(1, 2)};
  ASSERT_EQ(settle(bodies, speeds, apart), (std::vector<std::uint32_t>{1}));
  const SleepSettings settings;
  std::vector<std::uint32_t> woken;
  // Body 0 slower than the sleep speed, body 3 still: they wake nothing.
  // (Measured over no time: nobody settles.)
  std::vector<std::uint32_t> fell_asleep;
  speeds[0] = 0.5f * settings.speed;
  speeds[3] = 0.0f;
  bodies.move_at(speeds, 0.0f, settings);
  (void)bodies.tracker.update({}, settings, fell_asleep);
  bodies.tracker.wake_disturbed(row, settings, woken);
  EXPECT_TRUE(woken.empty());
  // Body 0 moves: body 1 wakes, body 2 beyond it sleeps on.
  speeds[0] = 2.0f * settings.speed;
  bodies.move_at(speeds, 0.0f, settings);
  (void)bodies.tracker.update({}, settings, fell_asleep);
  bodies.tracker.wake_disturbed(row, settings, woken);
  EXPECT_EQ(woken, (std::vector<std::uint32_t>{1}));
  EXPECT_TRUE(bodies.store.asleep(2));
  // Body 3, still, touching sleeping body 4, wakes nothing.
  woken.clear();
  const std::vector<Contact> beside{touching(3, 4)};
  bodies.tracker.wake_disturbed(beside, settings, woken);
  EXPECT_TRUE(woken.empty());
}

// Many contacts joined on four threads name each island by its smallest body, as a brute-force
// labelling does (each body the smallest it reaches through contacts), whatever order the joins
// came in.
TEST(SleepTracker, IslandsJoinedOnThreadsAreNamedByTheirSmallestBody) {
  constexpr std::uint32_t kBodies = 3000;
  BodyStore store;
  SleepTracker tracker{store};
  RigidBody body;
  body.inverse_mass = 1.0f;
  for (std::uint32_t i = 0; i < kBodies; ++i) store.add(body, 0.5f);
  const Parallel threads(4);
  tracker.use_threads(&threads);
  // Chains and clumps of random pairs, a fixed seed: islands of many sizes.
  std::vector<Contact> contacts;
  std::uint64_t state = 2008;
  const auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<std::uint32_t>(state >> 33) % kBodies;
  };
  for (int k = 0; k < 2000; ++k) contacts.push_back(touching(next(), next()));
  tracker.link_islands(contacts);

  std::vector<std::uint32_t> expected(kBodies);
  for (std::uint32_t i = 0; i < kBodies; ++i) expected[i] = i;
  for (bool changed = true; changed;) {
    changed = false;
    for (const Contact& contact : contacts) {
      const std::uint32_t least = std::min(expected[contact.body_a], expected[contact.body_b]);
      for (const std::uint32_t end : {contact.body_a, contact.body_b}) {
        if (expected[end] != least) {
          expected[end] = least;
          changed = true;
        }
      }
    }
  }
  const std::span<const std::uint32_t> islands = tracker.islands();
  EXPECT_EQ(std::vector<std::uint32_t>(islands.begin(), islands.end()), expected);
}

}  // namespace
}  // namespace sphys
