// Expand reduction (Bradshaw & O'Sullivan 2004, §4.4): every medial sphere grows until its error
// reaches a common tolerance; a greedy set cover then picks few of the grown spheres. The
// tolerance is searched for the smallest that needs no more than the allowed number of spheres.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "reducers_impl.h"

namespace sphys::tools::build {
namespace {

// Bisection steps on the tolerance: 2^-24 of the starting interval is far below the sampling.
constexpr int kExpandSearchSteps = 24;

class Expander {
 public:
  Expander(const Region& region, const MedialAxis& axis) : region_(region) {
    // Candidates: for each point the least-error sphere through it. Growing the other spheres
    // too would mostly duplicate these at many times the cost.
    for (std::size_t i = 0; i < region.points.size(); ++i) {
      const std::vector<std::uint32_t>& through = axis.point_spheres[i];
      if (through.empty()) continue;
      candidates_.push_back(
          *std::min_element(through.begin(), through.end(), [&](std::uint32_t a, std::uint32_t b) {
            return axis.spheres[a].error < axis.spheres[b].error;
          }));
    }
    std::sort(candidates_.begin(), candidates_.end());
    candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());
    for (const std::uint32_t s : candidates_) {
      const MedialSphere& sphere = axis.spheres[s];
      spheres_.push_back({sphere.ball, sphere.error - sphere.ball.radius, {}});
    }
    // A sphere centred at c with offset o (its centre's signed distance) that reaches p has
    // error |p - c| + o: the tolerance at which the grown sphere takes p in.
    const std::size_t n = region.points.size();
    words_ = (n + 63) / 64;
    needed_.resize(spheres_.size() * n);
    for (std::size_t m = 0; m < spheres_.size(); ++m) {
      for (std::size_t i = 0; i < n; ++i) {
        needed_[m * n + i] =
            (region.points[i] - spheres_[m].ball.center).norm() + spheres_[m].offset;
      }
    }
  }

  bool empty() const { return spheres_.empty(); }

  std::vector<Cluster> reduce(int max_balls) const {
    const std::size_t n = region_.points.size();
    // One sphere grown far enough covers everything: the search's upper end.
    double high = std::numeric_limits<double>::infinity();
    double low = high;
    for (std::size_t m = 0; m < spheres_.size(); ++m) {
      const auto row = std::span(needed_).subspan(m * n, n);
      high = std::min(high, *std::max_element(row.begin(), row.end()));
      low = std::min(low, spheres_[m].error());
    }
    std::vector<std::uint32_t> best = select(high, max_balls);
    for (int step = 0; step < kExpandSearchSteps; ++step) {
      const double middle = 0.5 * (low + high);
      std::vector<std::uint32_t> chosen = select(middle, max_balls);
      if (chosen.empty()) {
        low = middle;
      } else {
        high = middle;
        best = std::move(chosen);
      }
    }
    return clusters(best);
  }

 private:
  // Greedy set cover at the given tolerance; empty if it needs more than max_balls spheres.
  std::vector<std::uint32_t> select(double tolerance, int max_balls) const {
    const std::size_t n = region_.points.size();
    std::vector<std::uint64_t> covers(spheres_.size() * words_, 0);
    std::vector<std::uint64_t> uncovered(words_, 0);
    for (std::size_t m = 0; m < spheres_.size(); ++m) {
      for (std::size_t i = 0; i < n; ++i) {
        if (needed_[m * n + i] <= tolerance) {
          covers[m * words_ + i / 64] |= std::uint64_t{1} << (i % 64);
          uncovered[i / 64] |= std::uint64_t{1} << (i % 64);
        }
      }
    }
    std::size_t remaining = 0;
    for (const std::uint64_t w : uncovered) remaining += static_cast<std::size_t>(std::popcount(w));
    if (remaining < n) return {};  // some point no grown sphere reaches
    std::vector<std::uint32_t> chosen;
    while (remaining > 0) {
      if (static_cast<int>(chosen.size()) == max_balls) return {};
      std::size_t best = 0;
      int best_gain = -1;
      for (std::size_t m = 0; m < spheres_.size(); ++m) {
        int gain = 0;
        for (std::size_t w = 0; w < words_; ++w) {
          gain += std::popcount(covers[m * words_ + w] & uncovered[w]);
        }
        if (gain > best_gain) {
          best_gain = gain;
          best = m;
        }
      }
      for (std::size_t w = 0; w < words_; ++w) uncovered[w] &= ~covers[best * words_ + w];
      remaining -= static_cast<std::size_t>(best_gain);
      chosen.push_back(static_cast<std::uint32_t>(best));
    }
    return chosen;
  }

  // Each point to the chosen sphere that needs the least tolerance for it.
  std::vector<Cluster> clusters(const std::vector<std::uint32_t>& chosen) const {
    const std::size_t n = region_.points.size();
    std::vector<Cluster> result;
    for (const std::uint32_t m : chosen) {
      result.push_back({{spheres_[m].ball.center, 0.0}, spheres_[m].offset, {}});
    }
    for (std::uint32_t i = 0; i < n; ++i) {
      std::size_t best = 0;
      for (std::size_t k = 1; k < chosen.size(); ++k) {
        if (needed_[chosen[k] * n + i] < needed_[chosen[best] * n + i]) best = k;
      }
      Cluster& c = result[best];
      c.members.push_back(i);
      c.ball.radius = std::max(c.ball.radius, (region_.points[i] - c.ball.center).norm());
    }
    return result;
  }

  const Region& region_;
  std::vector<std::uint32_t> candidates_;
  std::vector<Cluster> spheres_;
  std::size_t words_ = 0;
  std::vector<double> needed_;  // per sphere, per point: the tolerance that covers it
};

}  // namespace

std::vector<Cluster> expand_clusters(const Region& region, const MedialAxis& axis,
                                     const ErrorMeasure& measure, int max_balls) {
  const Expander expander(region, axis);
  if (expander.empty()) {
    std::vector<std::uint32_t> all(region.points.size());
    for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    return {fit_cluster(region, measure, std::move(all))};
  }
  return expander.reduce(max_balls);
}

}  // namespace sphys::tools::build
