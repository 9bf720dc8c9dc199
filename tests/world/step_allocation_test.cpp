// A step allocates nothing once the world's buffers have grown to the scene: a bunny pile settling
// in plausible mode (sleep off, so that every bunny stays in the step) and the same pile in paper
// mode, each counted over 200 steps. Buffers grow while the counts they hold reach new maxima: in
// the plausible pile the contacts creep up for some 700 steps as it settles (measured, in windows
// of 100 steps: 33 allocations in steps 300 to 400, 2 in 400 to 500, none in 500 to 600, 30 in
// 600 to 700 as the contacts reach their most, 367, and none from 700 to 1,200), in paper mode
// for about 300. Every allocation of
// this test program goes through the counting operator new below.

#include <atomic>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"
#include "sphys/world.h"
#include "support/sanitized_run.h"

namespace {

std::atomic<bool> counting{false};
std::atomic<std::size_t> allocations{0};

void* allocate(std::size_t size) {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
  if (void* memory = std::malloc(size == 0 ? 1 : size)) return memory;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete[](void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
void operator delete[](void* memory, std::size_t) noexcept { std::free(memory); }

namespace sphys::tools {
namespace {

// Steps a 4 × 25 bunny pile (depth 2) on the plane: `warm_up` steps, then `counted` steps whose
// allocations are returned.
std::size_t allocations_while_stepping(ResponseMode response, int warm_up, int counted) {
  Scene scene = bunny_stacks_scene(4, 25, 2);
  scene.ground.kind = GroundSpec::Kind::kPlane;
  scene.response = response;
  scene.sleep.enabled = false;
  const SimulationSetup setup = build_world(scene);
  World& world = *setup.world;
  const auto dt = static_cast<float>(scene.time_step);
  for (int i = 0; i < warm_up; ++i) world.step(dt);
  allocations = 0;
  counting = true;
  for (int i = 0; i < counted; ++i) world.step(dt);
  counting = false;
  return allocations.load();
}

TEST(StepAllocation, ASettlingPileInPlausibleModeAllocatesNothingOnceGrown) {
  if (test::sanitized_run()) GTEST_SKIP() << "the sanitizers allocate on their own";
  EXPECT_EQ(allocations_while_stepping(ResponseMode::kPlausible, 700, 200), 0u);
}

TEST(StepAllocation, PaperModeAllocatesNothingOnceGrown) {
  if (test::sanitized_run()) GTEST_SKIP() << "the sanitizers allocate on their own";
  EXPECT_EQ(allocations_while_stepping(ResponseMode::kPaper, 300, 200), 0u);
}

}  // namespace
}  // namespace sphys::tools
