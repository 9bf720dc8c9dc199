// Batched configuration checks. Per configuration, each link's spheres are bounded by one box,
// and one walk of the snapshot's hierarchy (or, inside a known reach, a scan of the groups within
// it), the links' boxes in lanes, collects the groups near each link; then sphere after sphere of
// the links near any is tested against its link's groups only (kLaneWidth leaves at a time),
// stopping at the first sphere that touches; then, if asked, the pairs of spheres of links that
// may collide. Configurations run in runs on the threads.

#include "sphys/configuration_check.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

#include "query/body_filter.h"
#include "query/bvh_walk.h"
#include "query/configuration_layout.h"
#include "query/group_tests.h"
#include "query/snapshot.h"
#include "sphys/error.h"

namespace sphys {
namespace {

using query_detail::kGroupLeaves;
using query_detail::kLaneWidth;
using query_detail::Lanes;
using query_detail::LeafGroup;
using query_detail::Snapshot;

// What touches_below's stack holds at most: a group's leaves, then (branching - 1) more nodes for
// each level below them (SphereTree's branching is 8 at most).
constexpr std::size_t kGroupLeavesAndLevelsBelow = kGroupLeaves + 7 * kMostTreeDepth;

// The squared distance from a point to a box. unit: m²
float squared_distance(const Aabb& box, float x, float y, float z) {
  const float dx = std::max({box.min.x() - x, x - box.max.x(), 0.0f});
  const float dy = std::max({box.min.y() - y, y - box.max.y(), 0.0f});
  const float dz = std::max({box.min.z() - z, z - box.max.z(), 0.0f});
  return dx * dx + dy * dy + dz * dz;
}

void check_results(std::span<const ConfigurationResult> results, std::size_t configurations) {
  if (results.size() != configurations) {
    throw Error("results: " + std::to_string(results.size()) + " entries for " +
                std::to_string(configurations) + " configurations");
  }
}

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

namespace {

// Calls visit(group index) for every group whose box, and every box above it in the hierarchy,
// the sphere reaches; visit returns false to stop.
template <class Visit>
void walk_near(const Snapshot& snapshot, float x, float y, float z, float radius,
               const Visit& visit) {
  const float radius_squared = radius * radius;
  const auto reached = [&](const Aabb& box) {
    return squared_distance(box, x, y, z) <= radius_squared;
  };
  query_detail::walk_boxes(snapshot, reached, [&](const LeafGroup& group) {
    return !reached(group.bounds) ||
           visit(static_cast<std::uint32_t>(&group - snapshot.groups.data()));
  });
}

}  // namespace

// Per link of one configuration (or of several gathered: Run::gather), the box around its
// spheres, and the groups near it.
struct ConfigurationChecker::Scratch {
  // Groups kept per link; a link near more is checked sphere by sphere through the hierarchy.
  static constexpr std::uint32_t kMostCandidates = 32;
  static constexpr std::int32_t kTooMany = -2;

  Scratch(std::span<const std::int32_t> links, std::size_t link_count)
      : row_length((link_count + kLaneWidth - 1) / kLaneWidth * kLaneWidth),
        box(6 * row_length, 0.0f),
        spheres(link_count),
        candidates(link_count * kMostCandidates),
        candidate_count(link_count) {
    for (const std::int32_t link : links) ++spheres[static_cast<std::size_t>(link)];
  }

  // Row r of the links' boxes (0..2 low x, y, z, 3..5 high x, y, z), a link a column.
  float* row(std::size_t r) { return box.data() + r * row_length; }
  const float* row(std::size_t r) const { return box.data() + r * row_length; }

  // Every link's box empty, for the min and max of what it holds.
  void empty_links() {
    for (std::size_t a = 0; a < 3; ++a) {
      std::fill_n(row(a), spheres.size(), std::numeric_limits<float>::infinity());
      std::fill_n(row(3 + a), spheres.size(), -std::numeric_limits<float>::infinity());
    }
  }

  // Link l's box grown to hold the box [low, high] (x, y, z each).
  void hold(std::size_t l, const float* low, const float* high) {
    for (std::size_t a = 0; a < 3; ++a) {
      row(a)[l] = std::min(row(a)[l], low[a]);
      row(3 + a)[l] = std::max(row(3 + a)[l], high[a]);
    }
  }

  // Each link's box: around its spheres, a run of one link's spheres bounded in registers
  // before its box holds them.
  void bound_links(const float* posed, std::span<const std::int32_t> links) {
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

  // For configurations gathered together: each sphere's (x, y, z, radius) least and greatest
  // over all of them, for every sphere or (near_links_only) those of links near a group alone.
  // Whether each of those spheres is finite.
  bool bound_spheres(const float* posed, std::size_t configurations,
                     std::span<const std::int32_t> links, bool near_links_only) {
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

  // Each link's box around its spheres' boxes (bound_spheres, every sphere) grown by their
  // radii.
  void box_links_from_spheres(std::span<const std::int32_t> links) {
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

  // Rounding c ± r to float may leave a sphere's surface up to half an ulp outside its link's
  // box: each box is widened by a millionth of its size and distance from the origin, far more
  // than that. A link without spheres keeps its empty box (infinities, which the margin would
  // turn into NaN).
  void widen_links() {
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

  // Whole lanes: collect_candidates loads the rows a register at a time. unit: links
  std::size_t row_length;
  // Each link's box: rows low x, y, z, high x, y, z (row()), a link a column. unit: m
  query_detail::LaneFloats box;
  std::vector<std::uint32_t> spheres;  // each link's count
  std::vector<std::uint32_t> candidates;
  std::vector<std::int32_t> candidate_count;
  // Gathered configurations: each sphere's (x, y, z, radius) least and greatest over them, and
  // the spheres whose bound touches a leaf, in order, once known.
  query_detail::LaneFloats least;
  query_detail::LaneFloats greatest;
  std::vector<std::uint32_t> bounded;  // the spheres bound_spheres bounded
  std::vector<std::uint32_t> near;
  bool near_known = false;
  // The box around every link's, where the caller bounded the links (Run::bound): a group
  // outside it meets none of them. unit: m
  Aabb around;
  bool around_known = false;
};

void ConfigurationChecker::collect_candidates(Scratch& scratch) const {
  for (std::size_t first = 0; first < link_count_; first += kLinksPerWalk) {
    collect_candidates(first, std::min(link_count_, first + kLinksPerWalk), scratch);
  }
}

void ConfigurationChecker::collect_candidates(std::size_t first, std::size_t end,
                                              Scratch& scratch) const {
  const Snapshot& snapshot = query_->snapshot();
  // The links' boxes in lanes, link first + k in lane k; a link without spheres meets nothing
  // (its lanes, and those past the last link, are never among the links a test asks about).
  const float* low_x = scratch.row(0) + first;
  const float* low_y = scratch.row(1) + first;
  const float* low_z = scratch.row(2) + first;
  const float* high_x = scratch.row(3) + first;
  const float* high_y = scratch.row(4) + first;
  const float* high_z = scratch.row(5) + first;
  const std::size_t registers = (end - first + kLaneWidth - 1) / kLaneWidth;
  std::uint32_t walking = 0;  // bit k: link first + k is still collecting
  for (std::size_t k = 0; k < end - first; ++k) {
    scratch.candidate_count[first + k] = 0;
    if (scratch.spheres[first + k] != 0) walking |= 1u << k;
  }
  if (walking == 0 || snapshot.bvh.empty()) return;
  // Bit k: link first + k, among `among`, has a box that meets this one (touching counts).
  const auto reached = [&](const Aabb& box, std::uint32_t among) {
    std::uint32_t out = 0;
    for (std::size_t r = 0; r < registers; ++r) {
      const std::size_t lane = r * kLaneWidth;
      if (((among >> lane) & ((1u << kLaneWidth) - 1)) == 0) continue;
      const auto meets = [&](const float* lows, const float* highs, float box_low, float box_high) {
        return (Lanes::load(&lows[lane]) <= Lanes::splat(box_high)) &
               (Lanes::splat(box_low) <= Lanes::load(&highs[lane]));
      };
      out |= bits(meets(low_x, high_x, box.min.x(), box.max.x()) &
                  meets(low_y, high_y, box.min.y(), box.max.y()) &
                  meets(low_z, high_z, box.min.z(), box.max.z()))
             << lane;
    }
    return out & among;
  };
  // Groups a link's box meets, in the order a walk of the hierarchy meets them (a group's box
  // lies inside every box above it, so a walk reaches exactly the groups whose boxes meet the
  // link's): each appended to the candidates of the links in `hit`.
  const auto take = [&](std::uint32_t g, std::uint32_t hit) {
    for (; hit != 0; hit &= hit - 1) {
      const auto k = static_cast<std::size_t>(std::countr_zero(hit));
      std::int32_t& count = scratch.candidate_count[first + k];
      if (count == static_cast<std::int32_t>(Scratch::kMostCandidates)) {
        // Near too many: this link's spheres walk the hierarchy one by one.
        count = Scratch::kTooMany;
        walking &= ~(1u << k);
        continue;
      }
      scratch.candidates[(first + k) * Scratch::kMostCandidates + count++] = g;
    }
  };
  // Every link inside the reach's box: the groups that meet that box, scanned in order.
  if (reach_box_) {
    std::uint32_t inside = 0;
    for (std::size_t r = 0; r < registers; ++r) {
      const std::size_t lane = r * kLaneWidth;
      const auto within = [&](const float* lows, const float* highs, float box_low,
                              float box_high) {
        return (Lanes::splat(box_low) <= Lanes::load(&lows[lane])) &
               (Lanes::load(&highs[lane]) <= Lanes::splat(box_high));
      };
      const Aabb& box = *reach_box_;
      inside |= bits(within(low_x, high_x, box.min.x(), box.max.x()) &
                     within(low_y, high_y, box.min.y(), box.max.y()) &
                     within(low_z, high_z, box.min.z(), box.max.z()))
                << lane;
    }
    if ((inside & walking) == walking) {
      for (const std::uint32_t g : reachable_groups_) {
        if (walking == 0) return;
        const Aabb& bounds = snapshot.groups[g].bounds;
        // Most groups miss the box around every link: one test spares each link's.
        if (scratch.around_known && !scratch.around.overlaps(bounds)) continue;
        take(g, reached(bounds, walking));
      }
      return;
    }
  }
  // One walk for every link, depth first and left first as each link's own walk would go, so
  // that each link's groups come in the same order: a node is entered by the links that reach
  // it and every box above it.
  struct Entry {
    std::uint32_t node;
    std::uint32_t links;
  };
  std::array<Entry, query_detail::kMaxBvhDepth> stack;
  int top = 0;
  const std::uint32_t at_root = reached(snapshot.bvh[0].bounds, walking);
  if (at_root != 0) stack[top++] = {0, at_root};
  while (top > 0) {
    const Entry entry = stack[--top];
    const std::uint32_t links = entry.links & walking;
    if (links == 0) continue;
    const query_detail::BvhNode& node = snapshot.bvh[entry.node];
    if (node.count == 0) {
      const std::uint32_t right = reached(snapshot.bvh[node.first + 1].bounds, links);
      const std::uint32_t left = reached(snapshot.bvh[node.first].bounds, links);
      if (right != 0) stack[top++] = {node.first + 1, right};
      if (left != 0) stack[top++] = {node.first, left};
      continue;
    }
    for (std::uint32_t g = node.first; g < node.first + node.count; ++g) {
      if (group_seen_[g] != 0) take(g, reached(snapshot.groups[g].bounds, links & walking));
    }
  }
}

std::int32_t ConfigurationChecker::sphere_touches(const float* s, std::size_t link,
                                                  const Scratch& scratch) const {
  const std::int32_t count = scratch.candidate_count[link];
  if (count == Scratch::kTooMany) return touched_body(s[0], s[1], s[2], s[3]);
  return touched_body(s[0], s[1], s[2], s[3],
                      std::span(scratch.candidates.data() + link * Scratch::kMostCandidates,
                                static_cast<std::size_t>(count)));
}

std::int32_t ConfigurationChecker::self_collision(const float* spheres, std::int32_t& other) const {
  for (const auto& [i, j] : self_pairs_) {
    const float* a = spheres + i * kFloatsPerSphere;
    const float* b = spheres + j * kFloatsPerSphere;
    const float dx = a[0] - b[0];
    const float dy = a[1] - b[1];
    const float dz = a[2] - b[2];
    const float reach = a[3] + b[3];
    if (dx * dx + dy * dy + dz * dz <= reach * reach) {
      other = j;
      return i;
    }
  }
  return -1;
}

bool ConfigurationChecker::group_touches(std::uint32_t group, const Vec3& centre,
                                         float radius) const {
  const Snapshot& snapshot = query_->snapshot();
  return query_detail::group_touches_sphere(snapshot, snapshot.groups[group], centre, radius) &&
         (deeper_depth_ == 0 || touches_below(group, centre, radius));
}

bool ConfigurationChecker::touches_below(std::uint32_t group_index, const Vec3& centre,
                                         float radius) const {
  const Snapshot& snapshot = query_->snapshot();
  const LeafGroup& group = snapshot.groups[group_index];
  const SphereTree& tree = *snapshot.trees[group.body];
  const Transform& pose = snapshot.poses[group.body];
  const Mat3& rotation = rotations_[group.body];
  // Nodes from here on answer as spheres: the level asked, or a tree's last.
  const std::uint32_t answer_from = tree.level_begin(tree.last_level(deeper_depth_));
  // Depth first; each node pops once and pushes at most a branching's children, so the stack
  // holds at most the group's leaves and (branching - 1) more per level below them.
  std::array<std::uint32_t, kGroupLeavesAndLevelsBelow> stack;
  int top = 0;
  for (std::uint32_t i = group.first; i < group.first + group.count; ++i) {
    stack[top++] = snapshot.node[i];
  }
  while (top > 0) {
    const std::uint32_t n = stack[--top];
    const Vec3 at = rotation * tree.sphere(n).center + pose.translation;
    const float distance_squared = (at - centre).squaredNorm();
    if (n >= answer_from || tree.is_leaf(n)) {
      const float reach = tree.sphere(n).radius + radius;
      if (distance_squared <= reach * reach) return true;
      continue;
    }
    // With the bounds' relative margin against the rounding of the placed centre.
    const float reach = (tree.subtree_radius(n) + radius) * (1.0f + 1e-5f);
    if (distance_squared > reach * reach) continue;
    for (std::uint32_t c = tree.first_child(n); c < tree.first_child(n) + tree.child_count(n);
         ++c) {
      stack[top++] = c;
    }
  }
  return false;
}

std::int32_t ConfigurationChecker::touched_body(float x, float y, float z, float radius) const {
  const Snapshot& snapshot = query_->snapshot();
  const Vec3 centre(x, y, z);
  std::int32_t body = -1;
  walk_near(snapshot, x, y, z, radius, [&](std::uint32_t g) {
    if (group_seen_[g] != 0 && group_touches(g, centre, radius)) {
      body = static_cast<std::int32_t>(snapshot.groups[g].body);
      return false;
    }
    return true;
  });
  return body;
}

std::int32_t ConfigurationChecker::touched_body(float x, float y, float z, float radius,
                                                std::span<const std::uint32_t> candidates) const {
  const Snapshot& snapshot = query_->snapshot();
  const Vec3 centre(x, y, z);
  const float radius_squared = radius * radius;
  for (const std::uint32_t g : candidates) {
    const LeafGroup& group = snapshot.groups[g];
    if (squared_distance(group.bounds, x, y, z) <= radius_squared &&
        group_touches(g, centre, radius)) {
      return static_cast<std::int32_t>(group.body);
    }
  }
  return -1;
}

ConfigurationResult ConfigurationChecker::check_one(const float* spheres, Scratch& scratch) const {
  scratch.bound_links(spheres, links_);
  collect_candidates(scratch);
  return answer(spheres, scratch, true);
}

ConfigurationResult ConfigurationChecker::answer(const float* spheres, const Scratch& scratch,
                                                 bool every_sphere_given) const {
  ConfigurationResult result;
  const auto collide = [&](std::size_t sphere, std::int32_t body, std::int32_t other) {
    result.free = false;
    result.sphere = static_cast<std::int32_t>(sphere);
    result.body = body;
    result.other_sphere = other;
    return result;
  };
  for (const SphereRun& run : runs_) {
    const bool near_link = scratch.candidate_count[run.link] != 0;
    if (!near_link && !every_sphere_given) continue;  // not given
    for (std::size_t i = run.first; i < run.end; ++i) {
      const float* s = spheres + i * kFloatsPerSphere;
      // A sum of the four is finite only when each is: a NaN or infinite sphere is never free.
      if (!std::isfinite(s[0] + s[1] + s[2] + s[3]) || s[3] < 0.0f) return collide(i, -1, -1);
      if (!near_link) continue;
      const std::int32_t body = sphere_touches(s, run.link, scratch);
      if (body >= 0) return collide(i, body, -1);
    }
  }
  std::int32_t other = -1;
  const std::int32_t sphere = self_collision(spheres, other);
  if (sphere >= 0) return collide(static_cast<std::size_t>(sphere), -1, other);
  return result;
}

template <class Check>
void ConfigurationChecker::run_configurations(std::size_t count, const Parallel* parallel,
                                              const Check& check) const {
  for_each_on(parallel, (count + kConfigurationsPerRun - 1) / kConfigurationsPerRun,
              [&](std::size_t run) {
                Scratch scratch(links_, link_count_);
                const std::size_t end = std::min(count, (run + 1) * kConfigurationsPerRun);
                for (std::size_t c = run * kConfigurationsPerRun; c < end; ++c) check(c, scratch);
              });
}

ConfigurationChecker::Run::Run(const ConfigurationChecker& checker)
    : checker_(&checker),
      scratch_(std::make_unique<Scratch>(checker.links_, checker.link_count_)) {}

ConfigurationChecker::Run::~Run() = default;

ConfigurationResult ConfigurationChecker::Run::check(const float* spheres) {
  gathered_count_ = 0;  // the scratch is this configuration's now
  return checker_->check_one(spheres, *scratch_);
}

void ConfigurationChecker::Run::gather(const float* spheres, std::size_t configurations) {
  gathered_finite_ = scratch_->bound_spheres(spheres, configurations, checker_->links_, false);
  scratch_->box_links_from_spheres(checker_->links_);
  checker_->collect_candidates(*scratch_);
  scratch_->near_known = false;
  gathered_ = spheres;
  gathered_count_ = configurations;
  gathered_bounded_ = false;
}

void ConfigurationChecker::Run::gather_bounded(const float* spheres, std::size_t configurations) {
  if (checker_->reads_every_sphere()) {
    throw Error("gather_bounded: self-collision reads every sphere; gather them all instead");
  }
  gathered_finite_ = scratch_->bound_spheres(spheres, configurations, checker_->links_, true);
  scratch_->near_known = false;
  gathered_ = spheres;
  gathered_count_ = configurations;
  gathered_bounded_ = true;
}

ConfigurationResult ConfigurationChecker::Run::check_gathered(std::size_t configuration) {
  Scratch& scratch = *scratch_;
  const ConfigurationChecker& checker = *checker_;
  if (configuration >= gathered_count_) {
    throw Error("check_gathered: configuration " + std::to_string(configuration) + " of " +
                std::to_string(gathered_count_) + " gathered");
  }
  const std::size_t per = checker.links_.size() * kFloatsPerSphere;
  const float* spheres = gathered_ + configuration * per;
  // A non-finite sphere anywhere: each configuration on its own (which names the sphere), the
  // scratch bounding that configuration alone each time, or, bounded, within the links' boxes
  // given.
  if (!gathered_finite_) {
    return gathered_bounded_ ? checker.answer(spheres, scratch, false)
                             : checker.check_one(spheres, scratch);
  }
  if (!scratch.near_known) {
    scratch.near.clear();
    // A sphere whose box over all the gathered configurations, as a sphere, touches nothing
    // cannot touch anything in any of them.
    for (std::size_t i = 0; i < checker.links_.size(); ++i) {
      const auto link = static_cast<std::size_t>(checker.links_[i]);
      if (scratch.candidate_count[link] == 0) continue;
      // With the bounds' relative margin against the rounding of the half diagonal.
      const float* lo = &scratch.least[i * kFloatsPerSphere];
      const float* hi = &scratch.greatest[i * kFloatsPerSphere];
      const Vec3 middle = 0.5f * (Vec3(lo[0], lo[1], lo[2]) + Vec3(hi[0], hi[1], hi[2]));
      const float reach =
          (0.5f * (Vec3(hi[0], hi[1], hi[2]) - Vec3(lo[0], lo[1], lo[2])).norm() + hi[3]) *
          (1.0f + 1e-5f);
      const float bound[4] = {middle.x(), middle.y(), middle.z(), reach};
      if (checker.sphere_touches(bound, link, scratch) >= 0) {
        scratch.near.push_back(static_cast<std::uint32_t>(i));
      }
    }
    scratch.near_known = true;
  }
  ConfigurationResult result;
  for (const std::uint32_t i : scratch.near) {
    const std::int32_t body = checker.sphere_touches(
        spheres + i * kFloatsPerSphere, static_cast<std::size_t>(checker.links_[i]), scratch);
    if (body >= 0) return {false, static_cast<std::int32_t>(i), body, -1};
  }
  std::int32_t other = -1;
  const std::int32_t sphere = checker.self_collision(spheres, other);
  if (sphere >= 0) return {false, sphere, -1, other};
  return result;
}

void ConfigurationChecker::Run::bound(const float* boxes, std::size_t stride) {
  gathered_count_ = 0;  // the scratch is this configuration's now
  Scratch& scratch = *scratch_;
  // The box around the links that have spheres (no other is walked). A NaN is left out of it
  // (std::min and max keep the first operand against it), as it leaves its link meeting nothing.
  Vec3 low = Vec3::Constant(std::numeric_limits<float>::infinity());
  Vec3 high = -low;
  for (std::size_t l = 0; l < checker_->link_count_; ++l) {
    for (std::size_t a = 0; a < 3; ++a) {
      const float link_low = boxes[(6 * l + a) * stride];
      const float link_high = boxes[(6 * l + 3 + a) * stride];
      scratch.row(a)[l] = link_low;
      scratch.row(3 + a)[l] = link_high;
      if (scratch.spheres[l] == 0) continue;
      low[a] = std::min(low[a], link_low);
      high[a] = std::max(high[a], link_high);
    }
  }
  scratch.around = {low, high};
  scratch.around_known = true;
  checker_->collect_candidates(scratch);
}

bool ConfigurationChecker::Run::near(std::size_t link) const {
  return scratch_->candidate_count[link] != 0;
}

ConfigurationResult ConfigurationChecker::Run::check_bounded(const float* spheres) {
  return checker_->answer(spheres, *scratch_, checker_->reads_every_sphere());
}

void ConfigurationChecker::check(std::span<const float> spheres,
                                 std::span<ConfigurationResult> results,
                                 const Parallel* parallel) const {
  const std::size_t per_configuration = links_.size() * kFloatsPerSphere;
  if (spheres.size() % per_configuration != 0) {
    throw Error("spheres: " + std::to_string(spheres.size()) +
                " floats is no whole number of configurations of " + std::to_string(links_.size()) +
                " spheres × 4 (x, y, z, radius)");
  }
  const std::size_t count = spheres.size() / per_configuration;
  check_results(results, count);
  run_configurations(count, parallel, [&](std::size_t c, Scratch& scratch) {
    results[c] = check_one(spheres.data() + c * per_configuration, scratch);
  });
}

void ConfigurationChecker::check_link_poses(std::span<const Transform> link_poses,
                                            std::span<const Sphere> link_spheres,
                                            std::span<ConfigurationResult> results,
                                            const Parallel* parallel) const {
  if (link_spheres.size() != links_.size()) {
    throw Error("link_spheres: " + std::to_string(link_spheres.size()) + " spheres for " +
                std::to_string(links_.size()) + " sphere links");
  }
  if (link_poses.size() % link_count_ != 0) {
    throw Error("link_poses: " + std::to_string(link_poses.size()) +
                " poses is no whole number of configurations of " + std::to_string(link_count_) +
                " links");
  }
  const std::size_t count = link_poses.size() / link_count_;
  check_results(results, count);
  // Each run poses its configurations in its own buffer.
  for_each_on(
      parallel, (count + kConfigurationsPerRun - 1) / kConfigurationsPerRun, [&](std::size_t run) {
        Scratch scratch(links_, link_count_);
        std::vector<Mat3> rotations(link_count_);
        std::vector<float> posed_run(links_.size() * kFloatsPerSphere);
        const std::size_t end = std::min(count, (run + 1) * kConfigurationsPerRun);
        for (std::size_t c = run * kConfigurationsPerRun; c < end; ++c) {
          const Transform* poses = link_poses.data() + c * link_count_;
          for (std::size_t l = 0; l < link_count_; ++l) {
            rotations[l] = poses[l].rotation.toRotationMatrix();
          }
          for (std::size_t i = 0; i < links_.size(); ++i) {
            const auto link = static_cast<std::size_t>(links_[i]);
            const Vec3 centre = rotations[link] * link_spheres[i].center + poses[link].translation;
            float* out = posed_run.data() + i * kFloatsPerSphere;
            out[0] = centre.x();
            out[1] = centre.y();
            out[2] = centre.z();
            out[3] = link_spheres[i].radius;
          }
          results[c] = check_one(posed_run.data(), scratch);
        }
      });
}

}  // namespace sphys
