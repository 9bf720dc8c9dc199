// Each link's box around its spheres, for one configuration or over several gathered together:
// what a check collects the groups near each link by (near_groups.cpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "robot/configuration_layout.h"
#include "robot/configuration_scratch.h"

namespace sphys {
namespace {

using query_detail::kLaneWidth;
using query_detail::Lanes;

}  // namespace

void ConfigurationChecker::Scratch::bound_links(const float* posed,
                                                std::span<const std::int32_t> links) {
  around_known = false;
  empty_links();
  // A sphere's x, y, z, radius in one register: lanes x, y, z of c - r and c + r (the last
  // lane, r -+ r, is not read); even and odd spheres kept apart, so that two chains of
  // dependent minima and maxima overlap.
  static_assert(kFloatsPerSphere == kLaneWidth);
  const Lanes none = Lanes::splat(std::numeric_limits<float>::infinity());
  for (std::size_t first = 0; first < links.size();) {
    const std::int32_t link = links[first];
    std::array<Lanes, 2> low = {none, none};
    std::array<Lanes, 2> high = {Lanes::splat(0.0f) - none, Lanes::splat(0.0f) - none};
    std::size_t i = first;
    for (; i < links.size() && links[i] == link; ++i) {
      const float* s = posed + i * kFloatsPerSphere;
      const Lanes sphere = Lanes::load_unaligned(s);
      const Lanes radius = Lanes::splat(s[3]);
      low[i & 1] = min(low[i & 1], sphere - radius);
      high[i & 1] = max(high[i & 1], sphere + radius);
    }
    alignas(32) std::array<float, kLaneWidth> lowest;
    alignas(32) std::array<float, kLaneWidth> highest;
    min(low[0], low[1]).store(lowest.data());
    max(high[0], high[1]).store(highest.data());
    hold(static_cast<std::size_t>(link), lowest.data(), highest.data());
    first = i;
  }
  widen_links();
}

bool ConfigurationChecker::Scratch::bound_spheres(const float* posed, std::size_t configurations,
                                                  std::span<const std::int32_t> links,
                                                  bool near_links_only) {
  const std::size_t floats = links.size() * kFloatsPerSphere;
  bounded.clear();
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (!near_links_only || candidate_count[static_cast<std::size_t>(links[i])] != 0) {
      bounded.push_back(static_cast<std::uint32_t>(i));
    }
  }
  // Each sphere's four floats (one register of lanes) least and greatest over the
  // configurations (the greatest radius among them), and their sum times zero, which stays 0
  // unless one is NaN or infinite. Spheres go kInterleaved at a time, so that the three stay
  // in registers over the configurations and the spheres' chains of dependent operations
  // overlap.
  static_assert(kFloatsPerSphere == kLaneWidth);
  constexpr std::size_t kInterleaved = 4;
  least.resize(floats);
  greatest.resize(floats);
  bool finite = true;
  for (std::size_t first = 0; first < bounded.size(); first += kInterleaved) {
    const std::size_t n = std::min(kInterleaved, bounded.size() - first);
    std::array<Lanes, kInterleaved> lo;
    std::array<Lanes, kInterleaved> hi;
    std::array<Lanes, kInterleaved> zero;
    lo.fill(Lanes::splat(std::numeric_limits<float>::infinity()));
    hi.fill(Lanes::splat(-std::numeric_limits<float>::infinity()));
    zero.fill(Lanes::splat(0.0f));
    for (std::size_t c = 0; c < configurations; ++c) {
      const float* state = posed + c * floats;
      for (std::size_t k = 0; k < n; ++k) {
        const Lanes v = Lanes::load_unaligned(state + bounded[first + k] * kFloatsPerSphere);
        lo[k] = min(lo[k], v);
        hi[k] = max(hi[k], v);
        zero[k] = zero[k] + v * Lanes::splat(0.0f);
      }
    }
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = bounded[first + k];
      lo[k].store(&least[i * kFloatsPerSphere]);
      hi[k].store(&greatest[i * kFloatsPerSphere]);
      alignas(32) std::array<float, kLaneWidth> sums{};
      zero[k].store(sums.data());
      finite = finite && std::ranges::all_of(sums, [](float sum) { return sum == 0.0f; }) &&
               least[i * kFloatsPerSphere + 3] >= 0.0f;
    }
  }
  return finite;
}

void ConfigurationChecker::Scratch::box_links_from_spheres(std::span<const std::int32_t> links) {
  around_known = false;
  empty_links();
  for (std::size_t i = 0; i < links.size(); ++i) {
    const float* lo = &least[i * kFloatsPerSphere];
    const float* hi = &greatest[i * kFloatsPerSphere];
    const float low[3] = {lo[0] - hi[3], lo[1] - hi[3], lo[2] - hi[3]};
    const float high[3] = {hi[0] + hi[3], hi[1] + hi[3], hi[2] + hi[3]};
    hold(static_cast<std::size_t>(links[i]), low, high);
  }
  widen_links();
}

void ConfigurationChecker::Scratch::widen_links() {
  for (std::size_t a = 0; a < 3; ++a) {
    float* lows = row(a);
    float* highs = row(3 + a);
    for (std::size_t l = 0; l < spheres.size(); ++l) {
      if (spheres[l] == 0) continue;
      float& low = lows[l];
      float& high = highs[l];
      const float margin = 1e-6f * (std::max(std::abs(low), std::abs(high)) + (high - low));
      low -= margin;
      high += margin;
    }
  }
}

}  // namespace sphys
