// Calls on one world from several threads: a call that meets a step, a change or a read it cannot
// share throws sphys::Error naming what holds the world, instead of racing (world/world_access.h).
#include "world/world_access.h"

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/world.h"
#include "sphys/world_query.h"
#include "support/query_worlds.h"
#include "support/world_scenes.h"

namespace sphys::access_test {
namespace {

using testing::HasSubstr;

TEST(WorldAccess, AStepOrChangeHoldsTheWorldAloneAndReadsShareIt) {
  WorldAccess access;
  {
    const WorldAccess::Alone step(access, WorldAccess::Holder::kStep, "step");
    EXPECT_EQ(test::error_message([&] { const WorldAccess::Shared read(access, "poses"); }),
              "poses: the world is being stepped on another thread (calls on one world must "
              "take turns: docs/reliability.md)");
    EXPECT_THAT(test::error_message([&] {
                  const WorldAccess::Alone add(access, WorldAccess::Holder::kChange, "add_body");
                }),
                HasSubstr("add_body: the world is being stepped"));
  }
  {
    const WorldAccess::Alone change(access, WorldAccess::Holder::kChange, "remove_body");
    EXPECT_THAT(test::error_message([&] {
                  const WorldAccess::Alone step(access, WorldAccess::Holder::kStep, "step");
                }),
                HasSubstr("step: the world is being changed"));
  }
  {
    const WorldAccess::Shared first(access, "bodies");
    const WorldAccess::Shared second(access, "contacts");  // reads share
    EXPECT_THAT(test::error_message([&] {
                  const WorldAccess::Alone step(access, WorldAccess::Holder::kStep, "step");
                }),
                HasSubstr("step: the world is being read"));
  }
  // Every hold above let go, the refused ones included: the world is free again.
  const WorldAccess::Alone step(access, WorldAccess::Holder::kStep, "step");
}

World pile(int bodies) {
  WorldSettings settings;
  settings.collision.ground_plane_height = 0.0f;
  World world(settings);
  for (int i = 0; i < bodies; ++i) {
    world.add_body(test::cube(
        Vec3(0.1f * static_cast<float>(i % 3), 0.6f + 1.05f * static_cast<float>(i), 0.0f), 0.5f));
  }
  return world;
}

TEST(WorldAccess, AReadingHeldTurnsAwayStepsAndChanges) {
  World world = pile(3);
  const BodyId first = world.id_of(0);
  {
    const World::Reading reading(world);
    EXPECT_THAT(test::error_message([&] { world.step(test::kDt); }),
                HasSubstr("step: the world is being read"));
    EXPECT_THAT(test::error_message([&] { world.remove_body(first); }),
                HasSubstr("remove_body: the world is being read"));
    EXPECT_TRUE(world.alive(first));  // reads go on beside it
    const WorldQuery query(world);    // and so does a query's reading of the world
  }
  world.step(test::kDt);
  world.remove_body(first);
  EXPECT_FALSE(world.alive(first));
}

// A call on another thread during a step throws; one that comes between steps goes through, and a
// step that comes during the call throws in turn. The stepping thread steps until the other has
// seen its call turned away (or 30 s have passed).
TEST(WorldAccess, CallsDuringAStepOnAnotherThreadThrowAndLeaveTheWorldWhole) {
  World world = pile(40);
  const BodyId first = world.id_of(0);
  std::atomic<bool> refused = false;
  std::atomic<int> steps = 0;
  std::thread stepper([&] {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!refused && std::chrono::steady_clock::now() < give_up) {
      try {
        world.step(test::kDt);
        ++steps;
      } catch (const Error& error) {
        EXPECT_THAT(error.what(), HasSubstr("step: the world is being changed on another thread"));
      }
    }
  });
  std::string step_message;
  while (!refused) {
    try {
      world.set_velocity(first, Vec3(0.0f, 0.0f, 0.0f), Vec3::Zero());
    } catch (const Error& error) {
      step_message = error.what();
      refused = true;
    }
  }
  stepper.join();
  EXPECT_THAT(step_message,
              HasSubstr("set_velocity: the world is being stepped on another thread"));
  for (const BodyId id : {world.id_of(0), world.id_of(39)}) {
    EXPECT_TRUE(world.body(id).pose.translation.allFinite());
  }
  EXPECT_FALSE(world.stopped());
}

}  // namespace
}  // namespace sphys::access_test
