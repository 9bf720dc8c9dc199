// Bodies as handles: ids with generations, removal at the world level, and a wake-up in the
// middle of a step that detects each pair once.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/world.h"
#include "support/cube_tree.h"

namespace sphys::bodies_test {
namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kBoxSide = 1.0f;  // the side of octree_cube_tree()'s cube. unit: m

// How far the cube's spheres reach below its centre: where it rests on a plane. unit: m
float resting_height() {
  const SphereTree& tree = *test::octree_cube_tree();
  float lowest = 0.0f;
  for (std::uint32_t node = 0; node < tree.size(); ++node) {
    if (tree.is_leaf(node)) {
      lowest = std::min(lowest, tree.sphere(node).center.y() - tree.sphere(node).radius);
    }
  }
  return -lowest;
}

BodyDesc cube(const Vec3& position) {
  BodyDesc desc;
  desc.tree = test::octree_cube_tree();
  desc.pose.translation = position;
  desc.mass = 1000.0f;
  desc.inertia = Mat3::Identity() * (desc.mass * kBoxSide * kBoxSide / 6.0f);
  desc.restitution = 0.0f;
  return desc;
}

WorldSettings on_plane() {
  WorldSettings settings;
  settings.collision.ground_plane_height = 0.0f;
  return settings;
}

// Steps until every body sleeps; false when they do not within `seconds`.
bool settle(World& world, float seconds) {
  for (int i = 0; i < static_cast<int>(seconds / kDt); ++i) {
    const StepStats& stats = world.step(kDt);
    if (stats.movable_bodies > 0 && stats.bodies_asleep == stats.movable_bodies) return true;
  }
  return false;
}

TEST(WorldBodies, TheIdOfARemovedBodyIsStaleEvenWhenItsSlotIsReused) {
  World world(on_plane());
  const BodyId first = world.add_body(cube(Vec3(0.0f, 2.0f, 0.0f)));
  world.remove_body(first);
  const BodyId second = world.add_body(cube(Vec3(3.0f, 2.0f, 0.0f)));
  ASSERT_EQ(second.index, first.index);  // the slot is reused...
  EXPECT_NE(second, first);              // ...under a new generation
  EXPECT_FALSE(world.alive(first));
  EXPECT_TRUE(world.alive(second));
  EXPECT_EQ(world.id_of(second.index), second);
  EXPECT_THROW((void)world.body(first), Error);
  EXPECT_THROW(world.set_velocity(first, Vec3::Zero(), Vec3::Zero()), Error);
  EXPECT_THROW(world.apply_impulse(first, Vec3::UnitX(), Vec3::Zero()), Error);
  EXPECT_THROW(world.set_pair_material(first, second, PairMaterial{}), Error);
  EXPECT_THROW((void)world.asleep(first), Error);
  EXPECT_THROW(world.remove_body(first), Error);
  EXPECT_THROW((void)world.body(BodyId{7, 1}), Error);  // never added
  EXPECT_THROW((void)world.id_of(7), Error);
  EXPECT_FLOAT_EQ(world.body(second).pose.translation.x(), 3.0f);
  try {
    (void)world.body(first);
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "no body with id 0.1 in the world (removed, or never added)");
  }
}

// The default id names no body, not the first one added (which sits in slot 0): every call
// taking an id refuses it, saying so.
TEST(WorldBodies, TheDefaultIdNamesNoBody) {
  World world(on_plane());
  const BodyId first = world.add_body(cube(Vec3(0.0f, 2.0f, 0.0f)));
  const BodyId second = world.add_body(cube(Vec3(3.0f, 2.0f, 0.0f)));
  ASSERT_EQ(first.index, 0u);
  EXPECT_FALSE(first.is_null());
  const BodyId none;
  EXPECT_TRUE(none.is_null());
  EXPECT_NE(none, first);
  EXPECT_FALSE(world.alive(none));
  const auto refused = [](const auto& call) {
    try {
      call();
    } catch (const Error& error) {
      return std::string(error.what()) == "the null body id (BodyId{}) names no body";
    }
    return false;
  };
  EXPECT_TRUE(refused([&] { (void)world.body(none); }));
  EXPECT_TRUE(refused([&] { world.set_velocity(none, Vec3::UnitX(), Vec3::Zero()); }));
  EXPECT_TRUE(refused([&] { world.apply_impulse(none, Vec3::UnitX(), Vec3::Zero()); }));
  EXPECT_TRUE(refused([&] { world.set_pair_material(none, second, PairMaterial{}); }));
  EXPECT_TRUE(refused([&] { world.set_pair_material(second, none, PairMaterial{}); }));
  EXPECT_TRUE(refused([&] { (void)world.asleep(none); }));
  EXPECT_TRUE(refused([&] { world.remove_body(none); }));
  // None of them touched the first body.
  EXPECT_TRUE(world.alive(first));
  EXPECT_EQ(world.body(first).linear_velocity, Vec3::Zero());
}

// A world moved onto another replaces it whole: the bodies, their ids and their contacts are the
// moved world's, and it steps and grows as before.
TEST(WorldBodies, AWorldMovedOntoAnotherIsThatWorld) {
  World moved(on_plane());
  const float rest = resting_height();
  const BodyId low = moved.add_body(cube(Vec3(0.0f, rest, 0.0f)));
  World target(on_plane());
  (void)target.add_body(cube(Vec3(5.0f, rest, 0.0f)));
  (void)target.add_body(cube(Vec3(8.0f, rest, 0.0f)));
  target = std::move(moved);
  EXPECT_EQ(target.body_slots(), 1u);
  EXPECT_TRUE(target.alive(low));
  const BodyId high = target.add_body(cube(Vec3(0.0f, 3.0f * rest, 0.0f)));
  ASSERT_TRUE(settle(target, 5.0f));
  EXPECT_NEAR(target.body(high).pose.translation.y(), 3.0f * rest, 0.01f);  // on the low one
}

// A slot's generations move on with each body it holds, so that no earlier id of the slot
// answers to a later body, however often the slot is reused.
TEST(WorldBodies, NoEarlierIdOfAReusedSlotAnswers) {
  World world(on_plane());
  std::vector<BodyId> earlier;
  BodyId current = world.add_body(cube(Vec3(0.0f, 2.0f, 0.0f)));
  for (int reuse = 0; reuse < 20; ++reuse) {
    earlier.push_back(current);
    world.remove_body(current);
    current = world.add_body(cube(Vec3(static_cast<float>(reuse), 2.0f, 0.0f)));
    ASSERT_EQ(current.index, earlier.front().index);
    EXPECT_EQ(world.id_of(current.index), current);
    for (const BodyId old : earlier) {
      EXPECT_FALSE(world.alive(old));
      EXPECT_THROW((void)world.body(old), Error);
    }
  }
}

// A box resting asleep on another: removing the bottom one wakes the top one, which falls to the
// plane; a new body in the removed slot meets nothing of the old one's.
TEST(WorldBodies, RemovingTheSupportOfASleepingStackLetsTheTopFall) {
  World world(on_plane());
  const float rest = resting_height();
  const BodyId bottom = world.add_body(cube(Vec3(0.0f, rest, 0.0f)));
  const BodyId top = world.add_body(cube(Vec3(0.0f, 3.0f * rest, 0.0f)));
  ASSERT_TRUE(settle(world, 5.0f)) << "the stack never fell asleep";
  const float top_before = world.body(top).pose.translation.y();
  EXPECT_NEAR(top_before, 3.0f * rest, 0.01f);

  world.remove_body(bottom);
  EXPECT_FALSE(world.asleep(top));  // it lost its support
  const StepStats& after = world.step(kDt);
  EXPECT_EQ(after.movable_bodies, 1u);
  for (const Contact& contact : world.contacts()) {
    EXPECT_NE(contact.body_a, bottom.index);
    EXPECT_NE(contact.body_b, bottom.index);
  }
  ASSERT_TRUE(settle(world, 5.0f));
  EXPECT_NEAR(world.body(top).pose.translation.y(), rest, 0.01f);  // on the plane now

  // The slot comes back far away: no contact between it and the top box.
  const BodyId far = world.add_body(cube(Vec3(10.0f, rest, 0.0f)));
  ASSERT_EQ(far.index, bottom.index);
  for (int i = 0; i < 10; ++i) world.step(kDt);
  for (const Contact& contact : world.contacts()) {
    EXPECT_EQ(contact.body_a, kGroundPlaneBody) << "only contacts with the plane";
  }
}

// A box asleep on a static one is not in its group (static bodies join none): removing the
// static box must wake it all the same, and it falls to the plane.
TEST(WorldBodies, RemovingAStaticSupportWakesWhatSleepsOnIt) {
  World world(on_plane());
  const float rest = resting_height();
  BodyDesc pillar = cube(Vec3(0.0f, rest, 0.0f));
  pillar.is_static = true;
  const BodyId support = world.add_body(pillar);
  const BodyId top = world.add_body(cube(Vec3(0.0f, 3.0f * rest, 0.0f)));
  ASSERT_TRUE(settle(world, 5.0f)) << "the top box never fell asleep";
  world.remove_body(support);
  EXPECT_FALSE(world.asleep(top));
  ASSERT_TRUE(settle(world, 5.0f));
  EXPECT_NEAR(world.body(top).pose.translation.y(), rest, 0.01f);
}

// A box dropped on a sleeping one wakes it in the middle of a step: the sleeping box's pair with
// the plane has its narrow phase then, once, and every figure of the step counts each pair once.
// Islands persist from step to step, and split once the bodies that joined them part: two boxes
// side by side are one island; one pushed away, they become two.
TEST(WorldBodies, AnIslandSplitsOnceItsBodiesPart) {
  WorldSettings settings = on_plane();
  settings.sleep.enabled = false;
  World world(settings);
  const float y = resting_height();
  world.add_body(cube(Vec3(0.0f, y, 0.0f)));
  const BodyId pushed = world.add_body(cube(Vec3(kBoxSide, y, 0.0f)));
  for (int i = 0; i < 10; ++i) world.step(kDt);
  EXPECT_EQ(world.stats().islands, 1u);                              // touching: one island
  world.set_velocity(pushed, Vec3(3.0f, 0.0f, 0.0f), Vec3::Zero());  // m/s, away
  std::uint32_t islands = 0;
  for (int i = 0; i < 60; ++i) islands = world.step(kDt).islands;
  // Sliding 0.9 m against friction (3² / (2 μ g), μ = 0.5): well apart.
  EXPECT_GT(world.body(pushed).pose.translation.x(), 1.5f * kBoxSide);
  EXPECT_EQ(islands, 2u);
}

TEST(WorldBodies, AWakeUpInTheMiddleOfAStepDetectsEachPairOnce) {
  WorldSettings settings = on_plane();
  settings.solver.contacts = ContactSet::kAll;  // one contact per leaf pair: countable
  settings.solver.reuse_distance = 0.0f;        // every pair descends
  settings.max_collision_passes = 1;
  World world(settings);
  const float rest = resting_height();
  const BodyId sleeper = world.add_body(cube(Vec3(0.0f, rest, 0.0f)));
  ASSERT_TRUE(settle(world, 5.0f));
  // Just above the sleeper, falling onto it: they touch within the next step.
  BodyDesc dropped = cube(Vec3(0.0f, 3.0f * rest + 0.005f, 0.0f));
  dropped.linear_velocity = Vec3(0.0f, -1.0f, 0.0f);
  world.add_body(dropped);

  const StepStats& stats = world.step(kDt);
  ASSERT_FALSE(world.asleep(sleeper)) << "the blow did not wake the sleeping box";
  // The pairs: dropped–sleeper and dropped–plane in the detection, sleeper–plane once woken.
  EXPECT_EQ(stats.descended_pairs, 3u);
  EXPECT_EQ(stats.reused_pairs, 0u);
  EXPECT_EQ(stats.candidate_pairs, 1u);
  // Every leaf pair found became one contact, counted once.
  EXPECT_EQ(stats.leaf_pairs, world.contacts().size());
  EXPECT_EQ(stats.contacts, world.contacts().size());
  bool sleeper_on_plane = false;
  for (const Contact& contact : world.contacts()) {
    sleeper_on_plane |= contact.body_a == kGroundPlaneBody && contact.body_b == sleeper.index;
  }
  EXPECT_TRUE(sleeper_on_plane) << "the woken box's contacts with the plane are missing";
}

}  // namespace
}  // namespace sphys::bodies_test
