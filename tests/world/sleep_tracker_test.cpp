// Islands that persist from step to step: merged as contacts join them, built afresh only after
// bodies parted, and always at least as coarse as what touches (the solver's condition).
#include "world/sleep_tracker.h"

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
  SleepTracker tracker{&store};

  Bodies() {
    RigidBody body;
    body.inverse_mass = 1.0f;
    for (int i = 0; i < 5; ++i) store.add(body, 0.5f);
    body.is_static = true;
    store.add(body, 0.5f);
    tracker.resize(store.slots());
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

TEST(SleepTracker, ASleepingGroupStaysOneIslandAcrossASplit) {
  Bodies bodies;
  const std::vector<Contact> pair{touching(1, 2)};
  bodies.tracker.link_islands(pair);
  // Still for long enough, touching only each other: bodies 1 and 2 fall asleep as one group.
  std::vector<float> speeds(bodies.store.slots(), 0.0f);
  speeds[0] = speeds[3] = speeds[4] = 1.0f;  // m/s, restless
  SleepSettings settings;
  std::vector<std::uint32_t> fell_asleep;
  (void)bodies.tracker.update(speeds, pair, 2.0f * settings.time, settings, fell_asleep);
  EXPECT_EQ(fell_asleep, (std::vector<std::uint32_t>{1, 2}));
  EXPECT_TRUE(bodies.store.asleep(1));
  // Asleep, the pair makes no contacts; a split keeps the group together all the same.
  bodies.tracker.parted();
  bodies.tracker.split_islands({});
  EXPECT_EQ(bodies.islands(), (std::vector<std::uint32_t>{0, 1, 1, 3, 4}));
}

}  // namespace
}  // namespace sphys
