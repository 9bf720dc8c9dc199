#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <string_view>

#include <climits>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/scenarios.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

using testing::HasSubstr;

// The first outputs of SplitMix64 seeded with 2008, computed with Python's unbounded integers
// straight from the recurrence in the benchmark specification (bench/SCENE.md), reducing modulo
// 2^64 after every addition and multiplication:
//   s = (s + 0x9E3779B97F4A7C15) % 2**64; z = s
//   z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) % 2**64
//   z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) % 2**64
//   z ^= z >> 31
constexpr std::uint64_t kFirstOutputs[] = {
    0x3e0b3c8bd4cfdcc7ull, 0xce12f321375fdad7ull, 0xd74621fd16212b9aull,
    0x5fa0b82a75314ca8ull, 0x86a2cebbd82cd473ull,
};
// The same draws as units, (z >> 11) / 2**53, printed by Python's repr (the shortest decimal
// that reads back to the same double, so equality is exact).
constexpr double kFirstUnits[] = {
    0.24235895551538478, 0.8049766498655794, 0.8409138911139321,
    0.37354613339011167, 0.5259217461208892,
};

TEST(SplitMix64, FirstOutputsForSeed2008MatchTheSpecification) {
  SplitMix64 random(kStacksSeed);
  EXPECT_EQ(kStacksSeed, 2008u);
  for (std::uint64_t expected : kFirstOutputs) EXPECT_EQ(random.next(), expected);
}

TEST(SplitMix64, UnitDrawsAreTheTop53BitsOverTwoToThe53) {
  SplitMix64 random(kStacksSeed);
  for (double expected : kFirstUnits) EXPECT_EQ(random.next_unit(), expected);

  // Each unit draw consumes exactly one output, so the two kinds interleave on one sequence.
  SplitMix64 mixed(kStacksSeed);
  EXPECT_EQ(mixed.next(), kFirstOutputs[0]);
  EXPECT_EQ(mixed.next_unit(), kFirstUnits[1]);
  EXPECT_EQ(mixed.next(), kFirstOutputs[2]);
}

TEST(SplitMix64, UnitDrawsStayInTheHalfOpenUnitInterval) {
  SplitMix64 random(7);
  double sum = 0.0;
  constexpr int kDraws = 20'000;
  for (int k = 0; k < kDraws; ++k) {
    const double u = random.next_unit();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  // The mean of 20,000 uniform draws has a standard deviation of about 0.002.
  EXPECT_NEAR(sum / kDraws, 0.5, 0.01);
}

// The grid the specification gives for S stacks, written out per test rather than recomputed.
struct Grid {
  int cols;
  int rows;
};

// The experiment's scene keeps the paper's octree ground; the preset stands on the exact plane, off
// which nothing can slide.
constexpr GroundSpec::Kind kPaperGround = GroundSpec::Kind::kOctreeBox;
constexpr GroundSpec::Kind kPresetGround = GroundSpec::Kind::kPlane;

// Checks every body of an S x N stacks scene against the specification: body b = s·N + i sits at
// x = (col − (cols − 1)/2)·1.5, z = (row − (rows − 1)/2)·1.5, y = 1 + 1.2·i, turned about +y by
// 2π·u with u the b-th unit draw of SplitMix64(2008).
void expect_stacks_layout(const Scene& scene, int stacks, int per_stack, Grid grid, int tree_depth,
                          GroundSpec::Kind ground) {
  ASSERT_EQ(scene.bodies.size(), static_cast<std::size_t>(stacks * per_stack));
  EXPECT_EQ(scene.name, "stacks:" + std::to_string(stacks) + "x" + std::to_string(per_stack));
  EXPECT_EQ(scene.ground.kind, ground);
  EXPECT_EQ(scene.ground.height, 0.0);
  EXPECT_EQ(scene.gravity, Vec3(0.0f, -9.81f, 0.0f));
  EXPECT_EQ(scene.time_step, 1.0 / 60.0);
  EXPECT_EQ(scene.frames, 880);
  // The runtime's default response, plausible; the experiment asks for the paper's itself.
  EXPECT_EQ(scene.response, ResponseMode::kPlausible);
  EXPECT_EQ(scene.response, WorldSettings{}.response);

  SplitMix64 random(2008);
  for (int s = 0; s < stacks; ++s) {
    const int col = s % grid.cols;
    const int row = s / grid.cols;
    ASSERT_LT(row, grid.rows);
    const double x = (col - (grid.cols - 1) / 2.0) * 1.5;
    const double z = (row - (grid.rows - 1) / 2.0) * 1.5;
    for (int i = 0; i < per_stack; ++i) {
      const BodySpec& body = scene.bodies[static_cast<std::size_t>(s * per_stack + i)];
      SCOPED_TRACE("stack " + std::to_string(s) + ", level " + std::to_string(i));
      EXPECT_FLOAT_EQ(body.position.x(), static_cast<float>(x));
      EXPECT_FLOAT_EQ(body.position.y(), static_cast<float>(1.0 + 1.2 * i));
      EXPECT_FLOAT_EQ(body.position.z(), static_cast<float>(z));
      const double angle = 2.0 * std::numbers::pi * random.next_unit();
      EXPECT_FLOAT_EQ(body.orientation.w(), static_cast<float>(std::cos(angle / 2.0)));
      EXPECT_EQ(body.orientation.x(), 0.0f);
      EXPECT_FLOAT_EQ(body.orientation.y(), static_cast<float>(std::sin(angle / 2.0)));
      EXPECT_EQ(body.orientation.z(), 0.0f);

      EXPECT_EQ(body.mesh, "bunny");
      EXPECT_EQ(body.size, 1.0);
      EXPECT_FALSE(body.tree.sph_file.has_value());
      EXPECT_EQ(body.tree.method, BuildMethod::Combined);
      EXPECT_EQ(body.tree.branching, 8);
      EXPECT_EQ(body.tree.depth, tree_depth);
      EXPECT_EQ(body.linear_velocity, Vec3::Zero());
      EXPECT_EQ(body.angular_velocity, Vec3::Zero());
      EXPECT_EQ(body.density, 1000.0);
      EXPECT_FALSE(body.mass.has_value());
      EXPECT_FALSE(body.is_static);
    }
  }
}

TEST(BunnyStacks, FourStacksOfFiftyFollowTheSpecification) {
  const Scene scene = preset_scene("stacks:4x50");
  expect_stacks_layout(scene, 4, 50, {.cols = 2, .rows = 2}, 3, kPresetGround);
  if (scene.bodies.size() != 200) return;

  // A few bodies written out in full. The quaternions are cos(π·u), sin(π·u) of the first two
  // draws above, computed in Python and rounded to single precision.
  EXPECT_EQ(scene.bodies[0].position, Vec3(-0.75f, 1.0f, -0.75f));
  EXPECT_FLOAT_EQ(scene.bodies[0].orientation.w(), 0.7238755822181702f);
  EXPECT_FLOAT_EQ(scene.bodies[0].orientation.y(), 0.6899305582046509f);
  EXPECT_FLOAT_EQ(scene.bodies[1].position.y(), 2.2f);
  EXPECT_FLOAT_EQ(scene.bodies[1].orientation.w(), -0.818107545375824f);
  EXPECT_FLOAT_EQ(scene.bodies[1].orientation.y(), 0.5750652551651001f);
  // Body 50 opens the second stack, which the grid puts at +x.
  EXPECT_EQ(scene.bodies[50].position, Vec3(0.75f, 1.0f, -0.75f));
  EXPECT_EQ(scene.bodies[100].position, Vec3(-0.75f, 1.0f, 0.75f));
  EXPECT_FLOAT_EQ(scene.bodies[199].position.x(), 0.75f);
  EXPECT_FLOAT_EQ(scene.bodies[199].position.y(), 59.8f);
  EXPECT_FLOAT_EQ(scene.bodies[199].position.z(), 0.75f);
}

TEST(BunnyStacks, EightStacksOfTenFillThreeByThreeGrid) {
  const Scene scene = preset_scene("stacks:8x10");
  expect_stacks_layout(scene, 8, 10, {.cols = 3, .rows = 3}, 3, kPresetGround);
  if (scene.bodies.size() != 80) return;
  EXPECT_EQ(scene.bodies[0].position, Vec3(-1.5f, 1.0f, -1.5f));
  EXPECT_EQ(scene.bodies[40].position, Vec3(0.0f, 1.0f, 0.0f));  // stack 4: the centre
  EXPECT_EQ(scene.bodies[70].position, Vec3(0.0f, 1.0f, 1.5f));  // stack 7: last row, middle
  EXPECT_FLOAT_EQ(scene.bodies[2].orientation.w(), -0.8776862025260925f);
  EXPECT_FLOAT_EQ(scene.bodies[2].orientation.y(), 0.4792357385158539f);
}

TEST(BunnyStacks, ThreeStacksLeaveTheLastCellOfTheGridEmpty) {
  const Scene scene = preset_scene("stacks:3x2");
  expect_stacks_layout(scene, 3, 2, {.cols = 2, .rows = 2}, 3, kPresetGround);
  if (scene.bodies.size() != 6) return;
  EXPECT_EQ(scene.bodies[4].position, Vec3(-0.75f, 1.0f, 0.75f));
  EXPECT_FLOAT_EQ(scene.bodies[5].position.y(), 2.2f);
}

TEST(BunnyStacks, TreeDepthIsTheCallersChoice) {
  expect_stacks_layout(bunny_stacks_scene(1, 3, 2), 1, 3, {.cols = 1, .rows = 1}, 2, kPaperGround);
  expect_stacks_layout(bunny_stacks_scene(2, 1, 6), 2, 1, {.cols = 2, .rows = 1}, 6, kPaperGround);
  // A single stack stands on the origin.
  EXPECT_EQ(bunny_stacks_scene(1, 1, 1).bodies.at(0).position, Vec3(0.0f, 1.0f, 0.0f));
}

TEST(BunnyStacks, IsPresetLooksOnlyAtThePrefix) {
  EXPECT_TRUE(is_preset("stacks:4x50"));
  EXPECT_TRUE(is_preset("stacks:nonsense"));
  EXPECT_FALSE(is_preset("stacks.json"));
  EXPECT_FALSE(is_preset("scenes/stacks:4x50.json"));
  EXPECT_FALSE(is_preset(""));
}

TEST(BunnyStacks, LoadSceneTakesPresetsAndFiles) {
  expect_stacks_layout(load_scene("stacks:3x2"), 3, 2, {.cols = 2, .rows = 2}, 3, kPresetGround);

  const test::TempDir dir;
  const auto file = dir.write("two.json", R"({"format": "sphys-scene", "version": 1,
      "bodies": [{"position": [0, 1, 0]}, {"position": [0, 3, 0]}]})");
  const Scene scene = load_scene(file.string());
  ASSERT_EQ(scene.bodies.size(), 2u);
  EXPECT_EQ(scene.bodies[1].position, Vec3(0.0f, 3.0f, 0.0f));
}

// The message of the Error that reading `preset` throws.
std::string preset_error(std::string_view preset) {
  try {
    (void)preset_scene(preset);
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error for " << preset;
  return "";
}

TEST(BunnyStacks, MalformedPresetsAreRefusedByName) {
  for (std::string_view bad :
       {"stacks:0x5", "stacks:4x0", "stacks:4x", "stacks:x4", "stacks:ax3", "stacks:4x5x6",
        "stacks:-1x2", "stacks:2x-1", "stacks:", "stacks:4", "stacks: 4x5", "stacks:4x5 ",
        "stacks:2.5x4", "stacks:99999999999x1", "bunnies:4x5"}) {
    const std::string message = preset_error(bad);
    EXPECT_THAT(message, HasSubstr("unknown preset '" + std::string(bad) + "'"));
    EXPECT_THAT(message, HasSubstr("stacks:SxN"));
  }
}

TEST(BunnyStacks, OutOfRangeCountsAndDepthsAreRefused) {
  EXPECT_THAT(preset_error("stacks:1001x1000"), HasSubstr("at most 1000000 bunnies"));
  // The product would overflow an int; it must still be refused, not wrap.
  EXPECT_THROW((void)bunny_stacks_scene(INT_MAX, INT_MAX, 3), Error);
  EXPECT_THROW((void)bunny_stacks_scene(0, 5, 3), Error);
  EXPECT_THROW((void)bunny_stacks_scene(5, -1, 3), Error);
  for (int depth : {0, 7, -1}) {
    try {
      (void)bunny_stacks_scene(4, 5, depth);
      ADD_FAILURE() << "depth " << depth << " accepted";
    } catch (const Error& error) {
      EXPECT_THAT(error.what(), HasSubstr("depth must be 1 to 6, got " + std::to_string(depth)));
    }
  }
}

}  // namespace
}  // namespace sphys::tools
