// Crowds in the broad phases (docs/collision.md, "Crowds"): boxes piled on each other. Past the
// limit, Sweep & Prune lists every pair with a box that is not crowded and, among crowded boxes,
// each one's nearest partners; checked update by update against every pair of boxes tested by
// hand and the rule applied to them, as a crowd forms, spreads out and is gone.
#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "collision/broad_phase_scene.h"
#include "collision/cell_sweep_and_prune.h"
#include "collision/sweep_and_prune.h"

namespace sphys::test {
namespace {

constexpr std::uint32_t kLimit = 8;  // overlapping boxes per box

// The rule of SweepAndPrune::set_crowd_limit applied to every pair of boxes tested by hand, with
// the crowd's state carried from one update to the next as the broad phase carries it.
class CrowdOracle {
 public:
  struct Listing {
    std::vector<ProxyPair> pairs;
    std::vector<std::uint8_t> crowded;  // per id
    std::uint64_t deferred = 0;
    bool crowd = false;
  };

  Listing update(const std::vector<Proxy>& proxies) {
    const std::vector<ProxyPair> all = brute_force(proxies);
    std::vector<std::uint32_t> overlaps(proxies.size(), 0);
    for (const ProxyPair& pair : all) {
      ++overlaps[pair.a];
      ++overlaps[pair.b];
    }
    const auto live = static_cast<double>(
        std::count_if(proxies.begin(), proxies.end(), [](const Proxy& p) { return p.alive; }));
    const double share = crowd_ ? 0.5 : 1.0;
    const auto limit = static_cast<std::uint64_t>(share * 0.5 * kLimit * live);
    const bool was_crowded = crowd_;
    crowd_ = all.size() > limit;
    Listing out;
    out.crowd = crowd_;
    out.crowded.assign(proxies.size(), 0);
    std::vector<std::uint8_t> over_limit(proxies.size(), 0);
    for (ProxyId id = 0; id < proxies.size(); ++id) {
      over_limit[id] = overlaps[id] > kLimit && proxies[id].kind == ProxyKind::kDynamic;
    }
    const std::vector<std::uint8_t> before = over_limit_;
    over_limit_ = over_limit;
    if (!crowd_) {
      out.pairs = all;
      return out;
    }
    // The boxes that choose their nearest, and are reported crowded: those over the limit at the
    // update before while the crowd lasts, at this one as it forms.
    std::vector<std::uint8_t>& choosing = out.crowded;
    choosing = was_crowded ? before : over_limit;
    choosing.resize(proxies.size(), 0);
    std::set<std::uint64_t> listed;
    std::vector<std::vector<std::pair<float, ProxyId>>> partners(proxies.size());
    for (const ProxyPair& pair : all) {
      if (choosing[pair.a] == 0 || choosing[pair.b] == 0) {
        listed.insert(pair_key(pair));
        continue;
      }
      const Aabb& a = proxies[pair.a].box;
      const Aabb& b = proxies[pair.b].box;
      float distance2 = 0.0f;
      for (int k = 0; k < 3; ++k) {
        const float d = 0.5f * (a.min[k] + a.max[k] - b.min[k] - b.max[k]);
        distance2 += d * d;
      }
      partners[pair.a].emplace_back(distance2, pair.b);
      partners[pair.b].emplace_back(distance2, pair.a);
    }
    for (ProxyId id = 0; id < proxies.size(); ++id) {
      std::vector<std::pair<float, ProxyId>>& near = partners[id];
      std::sort(near.begin(), near.end());
      for (std::size_t i = 0; i < std::min<std::size_t>(near.size(), kLimit / 2); ++i) {
        listed.insert(pair_key(id, near[i].second));
      }
    }
    for (const std::uint64_t key : listed) out.pairs.push_back(pair_of(key));
    out.deferred = all.size() - out.pairs.size();
    return out;
  }

 private:
  bool crowd_ = false;
  std::vector<std::uint8_t> over_limit_;  // per id, at the last update
};

// A crowd of boxes about one point (jittered, so that distances differ), others spread out, and
// a static floor under all: the crowd spreads out by `growth` per update until it is gone.
struct CrowdScene {
  std::vector<Proxy> proxies;
  std::vector<Vec3> centres;

  explicit CrowdScene(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-0.05f, 0.05f);
    for (int i = 0; i < 60; ++i) centres.emplace_back(jitter(rng), 1.0f + jitter(rng), jitter(rng));
    for (int i = 0; i < 40; ++i) {
      centres.emplace_back(3.0f + 1.5f * static_cast<float>(i % 8), 1.0f,
                           3.0f + 1.5f * static_cast<float>(i / 8));
    }
    for (const Vec3& centre : centres) proxies.push_back({Aabb::around_sphere(centre, 0.5f)});
    proxies.push_back({Aabb{Vec3(-20, -1, -20), Vec3(20, 0.6f, 20)}, ProxyKind::kStatic});
  }

  void spread(float growth) {
    for (std::size_t i = 0; i < 60; ++i) {
      centres[i].x() *= growth;
      centres[i].z() *= growth;
      proxies[i].box = Aabb::around_sphere(centres[i], 0.5f);
    }
  }
};

TEST(SweepAndPruneCrowd, ListsWhatTheRuleKeepsAsACrowdFormsSpreadsAndGoes) {
  CrowdScene scene(3);
  SweepAndPrune sap;
  sap.set_crowd_limit(kLimit);
  for (Proxy& proxy : scene.proxies) {
    proxy.alive = true;
    (void)sap.add(proxy.box, proxy.kind);
  }
  CrowdOracle oracle;
  bool saw_crowd = false;
  for (int update = 0; update < 60; ++update) {
    sap.update();
    const CrowdOracle::Listing expected = oracle.update(scene.proxies);
    ASSERT_EQ(pairs_of(sap), expected.pairs) << "update " << update;
    ASSERT_EQ(sap.has_crowd(), expected.crowd) << "update " << update;
    ASSERT_EQ(sap.pairs_deferred(), expected.deferred) << "update " << update;
    for (ProxyId id = 0; id < scene.proxies.size(); ++id) {
      ASSERT_EQ(sap.crowded(id), expected.crowded[id] != 0) << "update " << update << " id " << id;
    }
    if (expected.crowd) {
      saw_crowd = true;
      // The floor is never crowded: every box keeps its pair with it.
      EXPECT_FALSE(sap.crowded(static_cast<ProxyId>(scene.proxies.size() - 1)));
    }
    scene.spread(1.08f);
    for (ProxyId id = 0; id < 60; ++id) sap.set_box(id, scene.proxies[id].box);
  }
  EXPECT_TRUE(saw_crowd);
  sap.update();
  EXPECT_FALSE(sap.has_crowd());  // spread out, the crowd is gone and every pair listed
  EXPECT_EQ(pairs_of(sap), brute_force(scene.proxies));
}

TEST(SweepAndPruneCrowd, WithoutALimitEveryPairIsListed) {
  CrowdScene scene(4);
  SweepAndPrune sap;
  for (Proxy& proxy : scene.proxies) {
    proxy.alive = true;
    (void)sap.add(proxy.box, proxy.kind);
  }
  sap.update();
  EXPECT_EQ(pairs_of(sap), brute_force(scene.proxies));
  EXPECT_FALSE(sap.has_crowd());
  EXPECT_EQ(sap.pairs_deferred(), 0u);
}

// A crowd grown by few adds at a time (the incremental path) is found as soon as its pairs pass
// the limit, and listed as the rule keeps them.
TEST(SweepAndPruneCrowd, ACrowdGrownOneAddAtATimeIsFoundAtTheLimit) {
  CrowdScene scene(5);
  SweepAndPrune sap;
  sap.set_crowd_limit(kLimit);
  CrowdOracle oracle;
  std::vector<Proxy> model(scene.proxies.size());
  bool saw_crowd = false;
  for (ProxyId id = 0; id < scene.proxies.size(); ++id) {
    model[id] = scene.proxies[id];
    model[id].alive = true;
    ASSERT_EQ(sap.add(model[id].box, model[id].kind), id);
    sap.update();
    const CrowdOracle::Listing expected = oracle.update(model);
    ASSERT_EQ(pairs_of(sap), expected.pairs) << "after add " << id;
    saw_crowd = saw_crowd || expected.crowd;
  }
  EXPECT_TRUE(saw_crowd);
}

// Per cell, the same rule: every pair with a box that is crowded in no cell is listed, nothing
// listed is not an overlapping pair, the count of what was left out is the cells', and once the
// crowd has spread out every pair is listed again. The same on one thread and on four.
TEST(CellSweepAndPruneCrowd, KeepsEveryPairOfABoxOutsideTheCrowdAndEndsWithEveryPair) {
  std::vector<std::vector<ProxyPair>> runs;
  for (const std::uint32_t threads : {1u, 4u}) {
    const Parallel parallel(threads);
    CrowdScene scene(6);
    CellSweepAndPrune cells(1.0f);
    cells.set_crowd_limit(kLimit);
    for (Proxy& proxy : scene.proxies) {
      proxy.alive = true;
      (void)cells.add(proxy.box, proxy.kind);
    }
    std::vector<ProxyPair> every_update;
    bool saw_crowd = false;
    for (int update = 0; update < 60; ++update) {
      cells.update(&parallel);
      const std::vector<ProxyPair> all = brute_force(scene.proxies);
      const std::vector<ProxyPair> listed = pairs_of(cells);
      ASSERT_TRUE(std::includes(all.begin(), all.end(), listed.begin(), listed.end()));
      for (const ProxyPair& pair : all) {
        if (cells.crowded(pair.a) && cells.crowded(pair.b)) continue;
        ASSERT_TRUE(std::binary_search(listed.begin(), listed.end(), pair))
            << "update " << update << ": " << pair.a << ", " << pair.b;
      }
      if (cells.has_crowd()) {
        saw_crowd = true;
        EXPECT_GE(cells.pairs_deferred(), all.size() - listed.size());
      } else {
        EXPECT_EQ(cells.pairs_deferred(), 0u);
      }
      every_update.insert(every_update.end(), listed.begin(), listed.end());
      scene.spread(1.08f);
      for (ProxyId id = 0; id < 60; ++id) cells.set_box(id, scene.proxies[id].box);
    }
    EXPECT_TRUE(saw_crowd);
    cells.update(&parallel);
    EXPECT_FALSE(cells.has_crowd());
    EXPECT_EQ(pairs_of(cells), brute_force(scene.proxies));
    runs.push_back(every_update);
  }
  EXPECT_EQ(runs[0], runs[1]);
}

// Boxes at one point, as a game spawns bodies: every pair overlaps at distance 0, so each box's
// nearest are the L/2 lowest ids but its own, and the pairs listed are those of a box among the
// first L/2 ids. 5,000 boxes overlap in 12,497,500 pairs, which the rule cuts before listing any.
constexpr ProxyId kBoxesAtOnePoint = 5000;
constexpr std::uint32_t kDefaultLimit = 32;  // overlapping boxes per box

std::vector<ProxyPair> pairs_of_the_lowest_ids() {
  std::vector<ProxyPair> pairs;
  for (ProxyId a = 0; a < kDefaultLimit / 2; ++a) {
    for (ProxyId b = a + 1; b < kBoxesAtOnePoint; ++b) pairs.push_back({a, b});
  }
  return pairs;
}

constexpr std::uint64_t kPairsAtOnePoint =
    std::uint64_t{kBoxesAtOnePoint} * (kBoxesAtOnePoint - 1) / 2;

TEST(SweepAndPruneCrowd, BoxesAtOnePointPairWithTheLowestIds) {
  SweepAndPrune sap;
  sap.set_crowd_limit(kDefaultLimit);
  for (ProxyId id = 0; id < kBoxesAtOnePoint; ++id) {
    (void)sap.add(box_at(0.0f, 1.0f, 0.0f, 0.05f), ProxyKind::kDynamic);
  }
  const std::vector<ProxyPair> expected = pairs_of_the_lowest_ids();
  for (int update = 0; update < 2; ++update) {  // as the crowd forms, and in it
    sap.update();
    ASSERT_EQ(pairs_of(sap), expected) << "update " << update;
    EXPECT_EQ(sap.pairs_deferred(), kPairsAtOnePoint - expected.size());
    for (ProxyId id = 0; id < kBoxesAtOnePoint; ++id) ASSERT_TRUE(sap.crowded(id)) << id;
  }
}

// Per cell, on a corner of four cells: each cell lists the same pairs, and leaves out as many;
// the same on one thread, two and four.
TEST(CellSweepAndPruneCrowd, BoxesAtOnePointPairWithTheLowestIdsOnAnyThreads) {
  const std::vector<ProxyPair> expected = pairs_of_the_lowest_ids();
  for (const std::uint32_t threads : {1u, 2u, 4u}) {
    const Parallel parallel(threads);
    CellSweepAndPrune cells(1.0f);
    cells.set_crowd_limit(kDefaultLimit);
    for (ProxyId id = 0; id < kBoxesAtOnePoint; ++id) {
      (void)cells.add(box_at(0.0f, 0.5f, 0.0f, 0.05f), ProxyKind::kDynamic);
    }
    cells.update(&parallel);
    ASSERT_EQ(pairs_of(cells), expected) << threads << " threads";
    EXPECT_EQ(cells.pairs_deferred(), 4 * (kPairsAtOnePoint - expected.size()));
    EXPECT_EQ(cells.cell_count(), 4u);
  }
}

}  // namespace
}  // namespace sphys::test
