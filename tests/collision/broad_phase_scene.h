#pragma once

// Random scenes of boxes for the broad phases' tests (Sweep & Prune, and per cell), each update
// checked against testing every pair of boxes.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "collision/sweep_and_prune.h"
#include "sphys/math.h"

namespace sphys::test {

// A cube of half-side `half` (unit: m) about a point.
inline Aabb box_at(float x, float y, float z, float half = 0.5f) {
  return Aabb::around_sphere(Vec3(x, y, z), half);
}

// The oracle: every pair of live boxes tested with Aabb::overlaps, static pairs left out.
struct Proxy {
  Aabb box;
  ProxyKind kind = ProxyKind::kDynamic;
  bool alive = false;
};

inline std::vector<ProxyPair> brute_force(const std::vector<Proxy>& proxies) {
  std::vector<ProxyPair> pairs;
  for (ProxyId a = 0; a < proxies.size(); ++a) {
    if (!proxies[a].alive) continue;
    for (ProxyId b = a + 1; b < proxies.size(); ++b) {
      if (!proxies[b].alive) continue;
      if (proxies[a].kind == ProxyKind::kStatic && proxies[b].kind == ProxyKind::kStatic) continue;
      if (proxies[a].box.overlaps(proxies[b].box)) pairs.push_back({a, b});
    }
  }
  return pairs;
}

template <class BroadPhase>
std::vector<ProxyPair> pairs_of(const BroadPhase& sap) {
  return {sap.pairs().begin(), sap.pairs().end()};
}

// A random scene: boxes on a coarse lattice (so that endpoints are often equal), moved by small
// steps or by jumps, some added and removed, a few static. After every update the pairs must be
// the brute-force pairs, in (a, b) order.
struct SceneSettings {
  int proxies = 150;
  int steps = 300;
  float region = 12.0f;      // side of the cube the boxes live in. unit: m
  float small_step = 0.25f;  // largest small displacement per step. unit: m
  double jump_chance = 0.02;
  double churn_chance = 0.02;  // chance per proxy and step of a remove or an add
  float lattice = 0.25f;       // coordinates are multiples of this. unit: m
};

// Runs the scene and returns a hash of every step's pairs, for the determinism test.
template <class BroadPhase>
std::uint64_t run_scene(BroadPhase& sap, std::uint32_t seed, const SceneSettings& s) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto snap = [&](float x) { return std::round(x / s.lattice) * s.lattice; };
  const auto random_box = [&] {
    const Vec3 c(snap(unit(rng) * s.region), snap(unit(rng) * s.region),
                 snap(unit(rng) * s.region));
    const Vec3 half(snap(0.25f + unit(rng)), snap(0.25f + unit(rng)), snap(0.25f + unit(rng)));
    return Aabb{c - half, c + half};
  };

  std::vector<Proxy> model;
  const auto add = [&] {
    const ProxyKind kind = unit(rng) < 0.1f ? ProxyKind::kStatic : ProxyKind::kDynamic;
    const Aabb box = random_box();
    const ProxyId id = sap.add(box, kind);
    if (id >= model.size()) model.resize(id + 1);
    EXPECT_FALSE(model[id].alive);
    model[id] = {box, kind, true};
  };
  for (int i = 0; i < s.proxies; ++i) add();

  std::uint64_t hash = 1469598103934665603ull;
  std::vector<ProxyPair> before;
  for (int step = 0; step < s.steps; ++step) {
    sap.update();
    const std::vector<ProxyPair> expected = brute_force(model);
    EXPECT_EQ(pairs_of(sap), expected) << "seed " << seed << " step " << step;
    if (pairs_of(sap) != expected) return 0;
    if constexpr (requires { sap.pairs_entered(); }) {
      std::vector<ProxyPair> entered;
      std::vector<ProxyPair> left;
      std::set_difference(expected.begin(), expected.end(), before.begin(), before.end(),
                          std::back_inserter(entered));
      std::set_difference(before.begin(), before.end(), expected.begin(), expected.end(),
                          std::back_inserter(left));
      EXPECT_EQ(std::vector<ProxyPair>(sap.pairs_entered().begin(), sap.pairs_entered().end()),
                entered)
          << "seed " << seed << " step " << step;
      EXPECT_EQ(std::vector<ProxyPair>(sap.pairs_left().begin(), sap.pairs_left().end()), left)
          << "seed " << seed << " step " << step;
      before = expected;
    }
    EXPECT_EQ(sap.size(), static_cast<std::size_t>(std::count_if(
                              model.begin(), model.end(), [](const Proxy& p) { return p.alive; })));
    for (const ProxyPair& pair : sap.pairs()) {
      hash = (hash ^ (std::uint64_t{pair.a} << 32 | pair.b)) * 1099511628211ull;  // FNV-1a
    }

    for (ProxyId id = 0; id < model.size(); ++id) {
      Proxy& proxy = model[id];
      if (!proxy.alive) continue;
      if (unit(rng) < s.churn_chance) {
        sap.remove(id);
        proxy.alive = false;
        continue;
      }
      if (proxy.kind == ProxyKind::kStatic && unit(rng) < 0.9f) continue;
      if (unit(rng) < s.jump_chance) {
        proxy.box = random_box();
      } else {
        const Vec3 d(snap((unit(rng) - 0.5f) * 2 * s.small_step),
                     snap((unit(rng) - 0.5f) * 2 * s.small_step),
                     snap((unit(rng) - 0.5f) * 2 * s.small_step));
        proxy.box.min += d;
        proxy.box.max += d;
      }
      sap.set_box(id, proxy.box);
    }
    const int adds = std::binomial_distribution<int>(s.proxies, s.churn_chance)(rng);
    for (int i = 0; i < adds; ++i) add();
    // Now and then a burst of adds large enough to rebuild everything.
    if (step % 97 == 50) {
      for (int i = 0; i < 80; ++i) add();
    }
  }
  return hash;
}

}  // namespace sphys::test
