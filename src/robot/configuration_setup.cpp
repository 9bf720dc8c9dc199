// A ConfigurationChecker made from its settings: the spheres in runs of one link, the groups its
// filter sees, those within the reach, the level of the trees it answers at, and the pairs of
// spheres checked for self-collision.

#include <algorithm>
#include <cmath>
#include <string>

#include "query/body_filter.h"
#include "query/snapshot.h"
#include "sphys/configuration_check.h"
#include "sphys/error.h"

namespace sphys {
namespace {

using query_detail::LeafGroup;
using query_detail::Snapshot;

}  // namespace

ConfigurationChecker::ConfigurationChecker(const WorldQuery& query,
                                           std::vector<std::int32_t> sphere_links,
                                           ConfigurationCheckSettings settings)
    : query_(&query), links_(std::move(sphere_links)) {
  if (links_.empty()) throw Error("sphere_links: no spheres");
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i] < 0) {
      throw Error("sphere_links[" + std::to_string(i) + "]: negative link " +
                  std::to_string(links_[i]));
    }
    link_count_ = std::max(link_count_, static_cast<std::size_t>(links_[i]) + 1);
    if (runs_.empty() || runs_.back().link != static_cast<std::size_t>(links_[i])) {
      runs_.push_back({i, i, static_cast<std::size_t>(links_[i])});
    }
    runs_.back().end = i + 1;
  }
  const Snapshot& snapshot = query.snapshot();
  const query_detail::BodyFilter filter(snapshot, settings.filter);
  group_seen_.reserve(snapshot.groups.size());
  for (const LeafGroup& group : snapshot.groups) {
    group_seen_.push_back(filter.sees(group.body) ? 1 : 0);
  }
  if (settings.reach) {
    const Sphere& ball = *settings.reach;
    if (!ball.center.allFinite() || !std::isfinite(ball.radius) || ball.radius < 0.0f) {
      throw Error("reach: a ball with a finite centre and a finite radius >= 0 is needed");
    }
    reach_box_ = Aabb::around_sphere(ball.center, ball.radius);
    for (std::uint32_t g = 0; g < snapshot.groups.size(); ++g) {
      if (group_seen_[g] != 0 && snapshot.groups[g].bounds.overlaps(*reach_box_)) {
        reachable_groups_.push_back(g);
      }
    }
  }
  if (settings.tree_depth < 0 || settings.tree_depth > kMostTreeDepth) {
    throw Error("tree_depth: " + std::to_string(settings.tree_depth) + " levels; give 0 (the " +
                "world's) to " + std::to_string(kMostTreeDepth));
  }
  if (settings.tree_depth > 0) {
    // A check looks at the world's leaves or below them, never above: it must not be free where
    // the world's own contacts would not be.
    if (snapshot.tree_depth == 0 || settings.tree_depth < snapshot.tree_depth) {
      throw Error("tree_depth: " + std::to_string(settings.tree_depth) +
                  " levels is shallower than the world's " +
                  (snapshot.tree_depth == 0 ? std::string("(every level)")
                                            : std::to_string(snapshot.tree_depth)) +
                  "; a check may only look deeper");
    }
    if (settings.tree_depth > snapshot.tree_depth) {
      deeper_depth_ = settings.tree_depth;
      rotations_.reserve(snapshot.poses.size());
      for (const Transform& pose : snapshot.poses) {
        rotations_.push_back(pose.rotation.toRotationMatrix());
      }
    }
  }
  if (!settings.self_collision) return;
  // Allowed link pairs as a table, either order.
  std::vector<std::uint8_t> allowed(link_count_ * link_count_, 0);
  for (const auto& [a, b] : settings.allowed_link_pairs) {
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= link_count_ ||
        static_cast<std::size_t>(b) >= link_count_) {
      throw Error("allowed_link_pairs: (" + std::to_string(a) + ", " + std::to_string(b) +
                  ") names a link no sphere has (links 0.." + std::to_string(link_count_ - 1) +
                  ")");
    }
    allowed[a * link_count_ + b] = 1;
    allowed[b * link_count_ + a] = 1;
  }
  for (std::size_t i = 0; i < links_.size(); ++i) {
    for (std::size_t j = i + 1; j < links_.size(); ++j) {
      if (links_[i] != links_[j] && allowed[links_[i] * link_count_ + links_[j]] == 0) {
        self_pairs_.push_back({static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)});
      }
    }
  }
}

}  // namespace sphys
