// Threads change how fast a world steps, never what it computes: bunny piles stepped on one
// thread and on two end in bit-identical states, with the same contacts and counts at every step.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"
#include "sphys/world.h"
#include "support/sanitized_run.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

// FNV-1a over the bits of every value, so that any difference in rounding shows.
class StateHash {
 public:
  void add(std::uint64_t value) {
    for (int byte = 0; byte < 8; ++byte) {
      hash_ = (hash_ ^ ((value >> (8 * byte)) & 0xffu)) * 0x100000001b3u;
    }
  }
  void add(float value) { add(std::uint64_t{std::bit_cast<std::uint32_t>(value)}); }
  void add(const Vec3& v) {
    for (int i = 0; i < 3; ++i) add(v[i]);
  }
  [[nodiscard]] std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325u;
};

struct ThreadedRun {
  std::uint64_t final_state = 0;  // every body's pose and velocities at the end
  std::uint64_t steps = 0;        // every step's counts and contacts
  std::uint32_t asleep = 0;
};

ThreadedRun run_scene(const Scene& scene, std::uint32_t threads, int frames,
                      const std::filesystem::path& tree_cache,
                      std::optional<BroadPhaseKind> broad_phase = std::nullopt) {
  BuildWorldOptions options;
  options.threads = threads;
  options.broad_phase = broad_phase;
  options.cache_dir = tree_cache;
  options.plausibility_figures = true;
  const SimulationSetup setup = build_world(scene, options);
  World& world = *setup.world;
  EXPECT_EQ(world.settings().threads, threads);
  ThreadedRun result;
  StateHash steps;
  for (int frame = 0; frame < frames; ++frame) {
    const StepStats& stats = world.step(static_cast<float>(scene.time_step));
    EXPECT_FALSE(stats.non_finite_body) << "frame " << frame;
    steps.add(std::uint64_t{stats.contacts});
    steps.add(stats.sphere_tests);
    steps.add(std::uint64_t{stats.leaf_pairs});
    steps.add(std::uint64_t{stats.substeps});
    steps.add(std::uint64_t{stats.bodies_asleep});
    steps.add(stats.deepest_penetration);
    for (const Contact& contact : world.contacts()) {
      steps.add((std::uint64_t{contact.body_a} << 32) | contact.body_b);
      steps.add(contact.point);
      steps.add(contact.normal);
      steps.add(contact.depth);
    }
  }
  StateHash state;
  for (const BodyId body : setup.bodies) {
    const RigidBody& b = world.body(body);
    state.add(b.pose.translation);
    state.add(b.pose.rotation.coeffs().x());
    state.add(b.pose.rotation.coeffs().y());
    state.add(b.pose.rotation.coeffs().z());
    state.add(b.pose.rotation.coeffs().w());
    state.add(b.linear_velocity);
    state.add(b.angular_velocity);
  }
  result.final_state = state.value();
  result.steps = steps.value();
  result.asleep = world.stats().bodies_asleep;
  return result;
}

// Returns the two-thread run.
ThreadedRun expect_same_on_one_and_two_threads(const Scene& scene, int frames) {
  // The trees are built once and read back for the later runs.
  const test::TempDir tree_cache;
  const ThreadedRun one = run_scene(scene, 1, frames, tree_cache.path());
  const ThreadedRun two = run_scene(scene, 2, frames, tree_cache.path());
  EXPECT_EQ(two.steps, one.steps) << "a step's contacts or counts differ";
  EXPECT_EQ(two.final_state, one.final_state) << "the final poses or velocities differ";
  EXPECT_EQ(two.asleep, one.asleep);
  // Two runs of one thread agree too (nothing depends on addresses or the clock).
  EXPECT_EQ(run_scene(scene, 1, frames, tree_cache.path()).final_state, one.final_state);
  return two;
}

// The soft step: its contacts coloured into blocks of SIMD lanes, the blocks of a colour and the
// bodies' integration threaded. One, two and four threads end in the same bits, and those bits are
// the committed ones (as Box2D's determinism test does): a change of the arithmetic shows here,
// and must come with a new hash and a reason. The lanes' width does not enter: a colour's lanes
// share no body, and each does the same arithmetic (contact_lanes_test.cpp).
TEST(Determinism, SoftStepPilesAreBitIdenticalOnOneTwoAndFourThreadsAndAsCommitted) {
  Scene scene = bunny_stacks_scene(8, 6, 3);
  scene.ground.kind = GroundSpec::Kind::kPlane;
  const int frames = test::sanitized_run() ? 25 : 300;
  const test::TempDir tree_cache;
  const ThreadedRun one = run_scene(scene, 1, frames, tree_cache.path());
  for (const std::uint32_t threads : {2u, 4u}) {
    const ThreadedRun many = run_scene(scene, threads, frames, tree_cache.path());
    EXPECT_EQ(many.steps, one.steps) << threads << " threads: a step's contacts or counts differ";
    EXPECT_EQ(many.final_state, one.final_state) << threads << " threads: the final state differs";
  }
  if (!test::sanitized_run()) {
    // The optimised build's state after 300 frames (the sanitizer's build runs fewer). Changed
    // when the soft step became the only solver: six substeps, rigid within the slop, static
    // friction's anchors, rolling resistance in the relax pass, the integrator that keeps spin,
    // the effective masses summed body by body.
    EXPECT_EQ(one.final_state, 0xb28780d4fe63af7eu) << std::hex << one.final_state;
  }
}

// The paper's octree ground, a static body in the broad phase, and the paper's response.
TEST(Determinism, PaperModeOnTheOctreeGroundIsBitIdenticalOnOneAndTwoThreads) {
  Scene scene = bunny_stacks_scene(4, 5, 3);
  scene.response = ResponseMode::kPaper;
  expect_same_on_one_and_two_threads(scene, test::sanitized_run() ? 15 : 200);
}

// The broad phases list the same pairs in the same order, so plausible mode runs the same with
// either: the cells (its own) and the paper's one Sweep & Prune, piles spread over several cells.
TEST(Determinism, BothBroadPhasesGiveTheSameBits) {
  Scene scene = bunny_stacks_scene(8, 6, 3);
  scene.ground.kind = GroundSpec::Kind::kPlane;
  const int frames = test::sanitized_run() ? 25 : 300;
  const test::TempDir tree_cache;
  const ThreadedRun cells = run_scene(scene, 2, frames, tree_cache.path(), BroadPhaseKind::kCells);
  const ThreadedRun single =
      run_scene(scene, 2, frames, tree_cache.path(), BroadPhaseKind::kSweepAndPrune);
  EXPECT_EQ(single.steps, cells.steps) << "a step's contacts or counts differ";
  EXPECT_EQ(single.final_state, cells.final_state) << "the final poses or velocities differ";
  EXPECT_EQ(run_scene(scene, 2, frames, tree_cache.path()).final_state, cells.final_state)
      << "plausible mode's own broad phase is the cells";
}

TEST(Determinism, TooManyThreadsAreRefused) {
  WorldSettings settings;
  settings.threads = 100000;
  EXPECT_THROW(World{settings}, Error);
}

}  // namespace
}  // namespace sphys::tools
