// Slots and generations (core/slot_store.h, sphys/slot_id.h): ids count from 1 and go stale with
// their item, freed slots are taken again last freed first, and each kind's id is its own type.

#include "core/slot_store.h"

#include <type_traits>

#include <gtest/gtest.h>

#include "sphys/body_id.h"
#include "sphys/joint.h"
#include "sphys/robot_world.h"

namespace sphys {
namespace {

static_assert(!std::is_convertible_v<JointId, BodyId>);
static_assert(!std::is_convertible_v<BodyId, JointId>);
static_assert(!std::is_convertible_v<RobotId, BodyId>);
static_assert(!std::is_convertible_v<RobotId, JointId>);

struct Item {
  int value = 0;
  bool alive = false;
};

struct ItemTag;
using ItemId = SlotId<ItemTag>;

TEST(SlotStore, IdsCountFromOneAndGoStaleWithTheirItem) {
  SlotStore<ItemId, Item> store;
  const ItemId first = store.add({7});
  const ItemId second = store.add({8});
  EXPECT_EQ(first, (ItemId{0, 1}));
  EXPECT_EQ(second, (ItemId{1, 1}));
  EXPECT_TRUE(store.alive(first));
  EXPECT_EQ(store.at(1).value, 8);
  store.remove(first.index);
  EXPECT_FALSE(store.alive(first));
  EXPECT_FALSE(store.at(0).alive);
  EXPECT_EQ(store.all().size(), 2u);  // the freed slot stays, dead
  EXPECT_EQ(store.id_of(0), first);   // until a later add takes it
  const ItemId again = store.add({9});
  EXPECT_EQ(again, (ItemId{0, 2}));
  EXPECT_FALSE(store.alive(first));
  EXPECT_TRUE(store.alive(again));
  EXPECT_EQ(store.at(0).value, 9);
}

TEST(SlotStore, TakesTheLastFreedSlotFirst) {
  SlotStore<ItemId, Item> store;
  for (int i = 0; i < 3; ++i) (void)store.add({i});
  store.remove(0);
  store.remove(2);
  EXPECT_EQ(store.add({}).index, 2u);
  EXPECT_EQ(store.add({}).index, 0u);
  EXPECT_EQ(store.add({}).index, 3u);
}

TEST(SlotStore, TheNullIdAndUnknownIdsNameNothing) {
  SlotStore<ItemId, Item> store;
  (void)store.add({});
  EXPECT_TRUE(ItemId{}.is_null());
  EXPECT_FALSE(store.alive(ItemId{}));
  EXPECT_FALSE(store.alive(ItemId{0, 2}));  // a generation not yet given
  EXPECT_FALSE(store.alive(ItemId{1, 1}));  // a slot not yet made
}

}  // namespace
}  // namespace sphys
