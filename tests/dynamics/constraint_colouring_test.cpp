// The constraint graph's colours: no moving body twice in a colour, checked by brute force over
// random piles; immovable bodies shared freely; manifolds with an immovable body coloured first;
// the overflow taking what no colour can.

#include "dynamics/constraint_colouring.h"

#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace sphys {
namespace {

TEST(ConstraintColouring, NoMovingBodyAppearsTwiceInAColour) {
  std::mt19937 random(7);
  constexpr std::uint32_t kPile = 300;
  std::uniform_int_distribution<std::uint32_t> body(0, kPile - 1);
  std::bernoulli_distribution moves(0.8);
  std::vector<ManifoldBodies> manifolds;
  for (int k = 0; k < 2000; ++k) {
    manifolds.push_back({body(random), body(random), moves(random), moves(random)});
  }
  ConstraintColouring colouring;
  std::vector<std::uint32_t> colours;
  colouring.colour(manifolds, kPile, colours);
  ASSERT_EQ(colours.size(), manifolds.size());
  std::set<std::pair<std::uint32_t, std::uint32_t>> seen;  // (colour, moving body)
  std::uint32_t coloured = 0;
  for (std::size_t k = 0; k < manifolds.size(); ++k) {
    if (colours[k] == kOverflowColour) continue;
    ASSERT_LT(colours[k], kColours);
    ++coloured;
    const ManifoldBodies& m = manifolds[k];
    if (m.a_moves) {
      EXPECT_TRUE(seen.insert({colours[k], m.a}).second) << "manifold " << k;
    }
    if (m.b_moves && !(m.a_moves && m.a == m.b)) {
      EXPECT_TRUE(seen.insert({colours[k], m.b}).second) << "manifold " << k;
    }
  }
  // 2,000 manifolds over 300 bodies: about 13 a body, within the 24 colours for most.
  EXPECT_GT(coloured, 1900u);
}

TEST(ConstraintColouring, ImmovableBodiesAreSharedAndColouredFirst) {
  // Ten bodies in a column on the ground (slot 10, immovable): each on the ground or on the one
  // below. Listed from the top down, the ground contacts last.
  std::vector<ManifoldBodies> manifolds;
  for (std::uint32_t i = 9; i > 0; --i) manifolds.push_back({i - 1, i, true, true});
  manifolds.push_back({10, 0, false, true});
  ConstraintColouring colouring;
  std::vector<std::uint32_t> colours;
  colouring.colour(manifolds, 11, colours);
  // The ground contact takes colour 0; the column's contacts alternate above it.
  EXPECT_EQ(colours.back(), 0u);
  for (std::size_t k = 0; k + 1 < manifolds.size(); ++k) EXPECT_LT(colours[k], 3u);
  // Many bodies on one immovable body: all in colour 0.
  std::vector<ManifoldBodies> on_ground;
  for (std::uint32_t i = 0; i < 50; ++i) on_ground.push_back({50, i, false, true});
  colouring.colour(on_ground, 51, colours);
  for (const std::uint32_t colour : colours) EXPECT_EQ(colour, 0u);
}

TEST(ConstraintColouring, ABodyInMoreManifoldsThanColoursOverflows) {
  // Body 0 touches 30 others: 24 of its manifolds take the 24 colours, 6 overflow.
  std::vector<ManifoldBodies> manifolds;
  for (std::uint32_t i = 1; i <= 30; ++i) manifolds.push_back({0, i, true, true});
  ConstraintColouring colouring;
  std::vector<std::uint32_t> colours;
  colouring.colour(manifolds, 31, colours);
  for (std::uint32_t k = 0; k < 30; ++k) {
    EXPECT_EQ(colours[k], k < kColours ? k : kOverflowColour) << "manifold " << k;
  }
}

}  // namespace
}  // namespace sphys
