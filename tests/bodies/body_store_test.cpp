#include "sphys/body_store.h"

#include <limits>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace sphys {
namespace {

// A box of mass 2 kg with three different moments of inertia (kg·m²).
RigidBody moving_box(const Vec3& position) {
  RigidBody body;
  body.pose.translation = position;
  body.linear_velocity = Vec3(1.0f, 2.0f, 3.0f);
  body.angular_velocity = Vec3(0.5f, 0.0f, -0.5f);
  body.inverse_mass = 0.5f;
  body.inertia_body = Vec3(1.0f, 2.0f, 4.0f).asDiagonal();
  body.inverse_inertia_body = body.inertia_body.inverse();
  body.restitution = 0.25f;
  body.friction = 0.75f;
  return body;
}

std::vector<std::uint32_t> awake_of(const BodyStore& store) {
  const std::span<const std::uint32_t> awake = store.awake();
  return {awake.begin(), awake.end()};
}

TEST(BodyStore, KeepsEachBodyInItsSlotAndReusesTheLastFreed) {
  BodyStore store;
  EXPECT_EQ(store.add(moving_box(Vec3(0.0f, 1.0f, 0.0f)), 0.5f), 0u);
  EXPECT_EQ(store.add(moving_box(Vec3(0.0f, 2.0f, 0.0f)), 0.5f), 1u);
  EXPECT_EQ(store.add(moving_box(Vec3(0.0f, 3.0f, 0.0f)), 0.5f), 2u);
  const RigidBody copy = store.body(1);
  EXPECT_EQ(copy.pose.translation, Vec3(0.0f, 2.0f, 0.0f));
  EXPECT_EQ(copy.linear_velocity, Vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(copy.inverse_mass, 0.5f);
  EXPECT_EQ(copy.inertia_body, moving_box(Vec3::Zero()).inertia_body);
  EXPECT_EQ(copy.restitution, 0.25f);
  EXPECT_EQ(copy.friction, 0.75f);
  EXPECT_FALSE(copy.is_static);

  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 1, 2}));
  store.remove(1);
  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 2}));
  store.remove(0);
  EXPECT_FALSE(store.alive(1));
  EXPECT_EQ(store.dynamic()[1], 0);
  EXPECT_EQ(store.moving()[1], 0);
  EXPECT_EQ(awake_of(store), std::vector<std::uint32_t>{2});
  EXPECT_EQ(store.add(moving_box(Vec3::Zero()), 0.5f), 0u);  // the last freed first
  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 2}));
  RigidBody fixed = moving_box(Vec3::Zero());
  fixed.is_static = true;
  EXPECT_EQ(store.add(fixed, 0.5f), 1u);
  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 2}));  // a static body never moves
  EXPECT_EQ(store.add(moving_box(Vec3::Zero()), 0.5f), 3u);
  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 2, 3}));
  EXPECT_EQ(store.slots(), 4u);
  EXPECT_EQ(store.dynamic_bodies(), 3u);  // slot 1 holds the static one
}

TEST(BodyStore, AStaticBodyKeepsNoVelocityOrInverseMass) {
  BodyStore store;
  RigidBody ground = moving_box(Vec3::Zero());
  ground.is_static = true;
  const std::uint32_t slot = store.add(ground, 1.0f);
  EXPECT_TRUE(store.is_static(slot));
  EXPECT_FALSE(store.asleep(slot));
  EXPECT_EQ(store.linear_velocities()[slot], Vec3::Zero());
  EXPECT_EQ(store.angular_velocities()[slot], Vec3::Zero());
  EXPECT_EQ(store.inverse_masses()[slot], 0.0f);
  EXPECT_EQ(store.inverse_inertias_world()[slot], Mat3::Zero());
  EXPECT_EQ(store.kinetic_energy(slot), 0.0);
  EXPECT_TRUE(awake_of(store).empty());
  store.set_asleep(slot, true);  // nothing to put to sleep
  EXPECT_FALSE(store.asleep(slot));
  EXPECT_TRUE(store.body(slot).is_static);
}

TEST(BodyStore, ListsTheAwakeBodiesInSlotOrderAndStopsThoseThatSleep) {
  BodyStore store;
  for (int i = 0; i < 5; ++i) store.add(moving_box(Vec3::Zero()), 0.5f);
  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  store.set_asleep(3, true);
  store.set_asleep(1, true);
  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 2, 4}));
  EXPECT_TRUE(store.asleep(3));
  EXPECT_EQ(store.dynamic()[3], 1);
  EXPECT_EQ(store.moving()[3], 0);
  EXPECT_EQ(store.linear_velocities()[3], Vec3::Zero());
  EXPECT_EQ(store.angular_velocities()[3], Vec3::Zero());
  store.set_asleep(3, false);
  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 2, 3, 4}));
  EXPECT_EQ(store.linear_velocities()[3], Vec3::Zero());  // woken at rest
  EXPECT_EQ(store.linear_velocities()[2], Vec3(1.0f, 2.0f, 3.0f));
}

TEST(BodyStore, PutsManyBodiesToSleepOrWakesThemAtOnce) {
  BodyStore store;
  for (int i = 0; i < 6; ++i) store.add(moving_box(Vec3::Zero()), 0.5f);
  const std::vector<std::uint32_t> some{4, 1, 2};
  store.set_asleep(some, true);
  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 3, 5}));
  // Waking a body already awake changes nothing of it.
  const std::vector<std::uint32_t> wake{2, 3, 4};
  store.set_asleep(wake, false);
  EXPECT_EQ(awake_of(store), (std::vector<std::uint32_t>{0, 2, 3, 4, 5}));
  EXPECT_EQ(store.linear_velocities()[3], Vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(store.linear_velocities()[2], Vec3::Zero());
}

// The store says which body a slot holds: generations count from 1, so the default id names no
// body, and a slot's generation moves on when its body leaves.
TEST(BodyStore, IdsCountGenerationsFromOneSoTheDefaultIdNamesNothing) {
  BodyStore store;
  const std::uint32_t slot = store.add(moving_box(Vec3::Zero()), 0.5f);
  const BodyId first = store.id_of(slot);
  EXPECT_EQ(first, (BodyId{0, 1}));
  EXPECT_TRUE(store.alive(first));
  EXPECT_FALSE(store.alive(BodyId{}));
  EXPECT_FALSE(store.alive(BodyId{1, 1}));  // no such slot
  store.remove(slot);
  EXPECT_FALSE(store.alive(first));
  EXPECT_FALSE(store.alive(store.id_of(slot)));  // free: the next body's id, not alive yet
  ASSERT_EQ(store.add(moving_box(Vec3::Zero()), 0.5f), slot);
  EXPECT_EQ(store.id_of(slot), (BodyId{0, 2}));
  EXPECT_TRUE(store.alive(store.id_of(slot)));
  EXPECT_FALSE(store.alive(first));
}

// Another owner's per-slot arrays, grown by the store.
class Column final : public SlotArrays {
 public:
  void grow_slots(std::uint32_t slots) override {
    ++grown;
    values.resize(slots, -1);
  }
  std::vector<int> values;
  int grown = 0;
};

TEST(BodyStore, AttachedArraysGrowWithTheStoreUntilDetached) {
  BodyStore store;
  store.add(moving_box(Vec3::Zero()), 0.5f);
  store.add(moving_box(Vec3::Zero()), 0.5f);
  Column column;
  store.attach(column);
  EXPECT_EQ(column.values.size(), 2u);  // grown to the store at once
  column.values[1] = 7;
  store.add(moving_box(Vec3::Zero()), 0.5f);
  EXPECT_EQ(column.values, (std::vector<int>{-1, 7, -1}));
  store.remove(0);
  const int grown = column.grown;
  store.add(moving_box(Vec3::Zero()), 0.5f);  // slot 0 again: nothing to grow
  EXPECT_EQ(column.grown, grown);
  // A copy is a snapshot of the bodies: what it adds grows nothing attached to the original.
  BodyStore copy = store;
  copy.add(moving_box(Vec3::Zero()), 0.5f);
  EXPECT_EQ(column.values.size(), 3u);
  // Given more bodies, the store grows what is attached to it.
  store = copy;
  EXPECT_EQ(column.values.size(), 4u);
  store.detach(column);
  store.add(moving_box(Vec3::Zero()), 0.5f);
  EXPECT_EQ(store.slots(), 5u);
  EXPECT_EQ(column.values.size(), 4u);
}

// Store and arrays may die in either order, and arrays move from one store to another.
TEST(BodyStore, AttachedArraysAndTheirStoreLetGoOfEachOtherInEitherOrder) {
  Column outliving;
  {
    BodyStore store;
    store.attach(outliving);
    {
      Column short_lived;
      store.attach(short_lived);
    }
    store.add(moving_box(Vec3::Zero()), 0.5f);  // grows only what is still there
  }
  EXPECT_EQ(outliving.values.size(), 1u);
  BodyStore first;
  BodyStore second;
  second.add(moving_box(Vec3::Zero()), 0.5f);
  second.add(moving_box(Vec3::Zero()), 0.5f);
  first.attach(outliving);
  second.attach(outliving);  // leaves the first store
  first.add(moving_box(Vec3::Zero()), 0.5f);
  first.add(moving_box(Vec3::Zero()), 0.5f);
  first.add(moving_box(Vec3::Zero()), 0.5f);
  EXPECT_EQ(outliving.values.size(), 2u);
  second.add(moving_box(Vec3::Zero()), 0.5f);
  EXPECT_EQ(outliving.values.size(), 3u);
}

TEST(BodyStore, WorldInertiaAndEnergyFollowThePose) {
  BodyStore store;
  const std::uint32_t slot = store.add(moving_box(Vec3::Zero()), 0.5f);
  // A quarter turn about z swaps the x and y axes: the world inertia is diag(2, 1, 4) kg·m².
  store.poses()[slot].rotation =
      Quat(Eigen::AngleAxisf(0.5f * std::numbers::pi_v<float>, Vec3::UnitZ()));
  store.update_world_inertia(slot);
  const Mat3 expected = Vec3(0.5f, 1.0f, 0.25f).asDiagonal();
  EXPECT_LT((store.inverse_inertias_world()[slot] - expected).cwiseAbs().maxCoeff(), 1e-6f);
  // ½ m v² + ½ ωᵀ I ω = ½·2·14 + ½ (2·0.25 + 4·0.25) = 14.75 J.
  EXPECT_NEAR(store.kinetic_energy(slot), 14.75, 1e-5);
  // |v| + |ω| · extent = √14 + √0.5 · 0.5 m/s, measured when the body was added and kept until
  // measured again; zero once asleep.
  const float speed = std::sqrt(14.0f) + std::sqrt(0.5f) * 0.5f;
  EXPECT_NEAR(store.fastest_point_speeds()[slot], speed, 1e-6f);
  store.linear_velocities()[slot] = Vec3::Zero();
  EXPECT_NEAR(store.fastest_point_speeds()[slot], speed, 1e-6f);
  EXPECT_NEAR(store.measure_fastest_point_speed(slot), std::sqrt(0.5f) * 0.5f, 1e-6f);
  store.set_asleep(slot, true);
  EXPECT_EQ(store.fastest_point_speeds()[slot], 0.0f);
}

TEST(BodyStore, FiniteFindsNanAndInfinityAnywhereInTheState) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  BodyStore store;
  const std::uint32_t slot = store.add(moving_box(Vec3::Zero()), 0.5f);
  EXPECT_TRUE(store.finite(slot));
  const auto broken = [&](const auto& breaks) {
    BodyStore one;
    const std::uint32_t i = one.add(moving_box(Vec3::Zero()), 0.5f);
    breaks(one, i);
    return !one.finite(i);
  };
  EXPECT_TRUE(broken([&](BodyStore& s, std::uint32_t i) { s.poses()[i].translation.y() = inf; }));
  EXPECT_TRUE(broken([&](BodyStore& s, std::uint32_t i) { s.poses()[i].rotation.w() = nan; }));
  EXPECT_TRUE(broken([&](BodyStore& s, std::uint32_t i) { s.linear_velocities()[i].z() = -inf; }));
  EXPECT_TRUE(broken([&](BodyStore& s, std::uint32_t i) { s.angular_velocities()[i].x() = nan; }));
  // A rotation that is no longer a unit quaternion has failed too.
  EXPECT_TRUE(broken([](BodyStore& s, std::uint32_t i) {
    s.poses()[i].rotation.coeffs() = Eigen::Vector4f(0.0f, 0.0f, 0.0f, 0.0f);
  }));
}

}  // namespace
}  // namespace sphys
