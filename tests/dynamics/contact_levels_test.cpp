#include "dynamics/contact_levels.h"

#include <cstdint>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace sphys {
namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

std::vector<std::uint32_t> contact_levels(std::span<const std::uint8_t> immovable,
                                          const Pairs& contacts) {
  ContactLevels levels;
  const std::span<const std::uint32_t> result = levels.compute(immovable, contacts);
  return {result.begin(), result.end()};
}

TEST(ContactLevels, AColumnOnTheGroundCountsUpFromIt) {
  // Body 0 is the ground; 3 sits on 2, which sits on 1, which sits on the ground.
  const std::vector<std::uint8_t> immovable = {1, 0, 0, 0};
  const Pairs contacts = {{2, 3}, {0, 1}, {1, 2}};
  EXPECT_EQ(contact_levels(immovable, contacts), (std::vector<std::uint32_t>{0, 1, 2, 3}));
}

TEST(ContactLevels, ABodyHeldFromTwoSidesTakesTheNearerSupport) {
  // 0 and 4 cannot move; 1-2-3 bridge them: the middle is two contacts from either.
  const std::vector<std::uint8_t> immovable = {1, 0, 0, 0, 1};
  const Pairs contacts = {{0, 1}, {1, 2}, {2, 3}, {3, 4}};
  EXPECT_EQ(contact_levels(immovable, contacts), (std::vector<std::uint32_t>{0, 1, 2, 1, 0}));
}

TEST(ContactLevels, BodiesWithoutAPathToAnythingImmovableAreUnsupported) {
  // 1 and 2 touch each other only; 3 touches nothing; 4 and 5 are both immovable.
  const std::vector<std::uint8_t> immovable = {1, 0, 0, 0, 1, 1};
  const Pairs contacts = {{1, 2}, {4, 5}};
  EXPECT_EQ(contact_levels(immovable, contacts),
            (std::vector<std::uint32_t>{0, kUnsupported, kUnsupported, kUnsupported, 0, 0}));
}

TEST(ContactLevels, RepeatedContactsAndNoContactsAtAll) {
  const std::vector<std::uint8_t> immovable = {0, 1, 0};
  const Pairs twice = {{1, 0}, {0, 1}, {1, 0}, {2, 0}, {0, 2}};
  EXPECT_EQ(contact_levels(immovable, twice), (std::vector<std::uint32_t>{1, 0, 2}));
  EXPECT_EQ(contact_levels(immovable, Pairs{}),
            (std::vector<std::uint32_t>{kUnsupported, 0, kUnsupported}));
  EXPECT_TRUE(contact_levels({}, Pairs{}).empty());
}

// Against the definition, relaxed to a fixed point: a body's level is one more than the least of
// its neighbours'.
TEST(ContactLevels, RandomGraphsAgreeWithRelaxation) {
  std::mt19937 rng(20081);
  ContactLevels reused;  // its buffers carry over from graph to graph
  for (int trial = 0; trial < 200; ++trial) {
    const std::uint32_t bodies = std::uniform_int_distribution<std::uint32_t>(1, 40)(rng);
    std::vector<std::uint8_t> immovable(bodies);
    for (auto& flag : immovable) flag = std::bernoulli_distribution(0.1)(rng) ? 1 : 0;
    Pairs contacts(std::uniform_int_distribution<std::uint32_t>(0, 2 * bodies)(rng));
    std::uniform_int_distribution<std::uint32_t> any(0, bodies - 1);
    for (auto& [a, b] : contacts) {
      a = any(rng);
      b = any(rng);
    }

    std::vector<std::uint32_t> expected(bodies, kUnsupported);
    for (std::uint32_t i = 0; i < bodies; ++i) {
      if (immovable[i] != 0) expected[i] = 0;
    }
    for (bool changed = true; changed;) {
      changed = false;
      for (const auto& [a, b] : contacts) {
        for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}}) {
          if (expected[from] != kUnsupported && expected[from] + 1 < expected[to]) {
            expected[to] = expected[from] + 1;
            changed = true;
          }
        }
      }
    }
    EXPECT_EQ(contact_levels(immovable, contacts), expected) << "trial " << trial;
    const std::span<const std::uint32_t> again = reused.compute(immovable, contacts);
    EXPECT_EQ(std::vector<std::uint32_t>(again.begin(), again.end()), expected)
        << "trial " << trial << ", buffers reused";
  }
}

}  // namespace
}  // namespace sphys
