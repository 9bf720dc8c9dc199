#include "sphys/collision_detector.h"

#include <algorithm>
#include <chrono>

#include "sphys/error.h"

namespace sphys {
namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

bool finite(const Transform& pose) {
  return pose.translation.allFinite() && pose.rotation.coeffs().allFinite();
}

// The last level used of a tree: its nodes are the leaves.
int last_level(const SphereTree& tree, int tree_depth) {
  return (tree_depth <= 0 || tree_depth > tree.depth()) ? tree.depth() - 1 : tree_depth - 1;
}

// World bound of a body from one level's spheres, each grown to its subtree radius so that every
// deeper sphere is inside too.
Aabb world_bounds(const SphereTree& tree, const Transform& pose, int level) {
  const int used = std::min(level, tree.depth() - 1);
  Aabb box;
  for (std::uint32_t node = tree.level_begin(used); node < tree.level_end(used); ++node) {
    box.extend(
        Aabb::around_sphere(pose.apply(tree.sphere(node).center), tree.subtree_radius(node)));
  }
  // Leaves above the level (trees need not be complete) bound parts of the body too.
  for (std::uint32_t node = 0; node < tree.level_begin(used); ++node) {
    if (tree.is_leaf(node)) {
      box.extend(
          Aabb::around_sphere(pose.apply(tree.sphere(node).center), tree.sphere(node).radius));
    }
  }
  return box;
}

// Candidate pairs, and bodies against the plane, per run of the narrow phase: enough work per run
// to outweigh handing it to a thread, and runs enough to share among threads.
constexpr std::size_t kPairsPerChunk = 64;
constexpr std::size_t kBodiesPerChunk = 256;

}  // namespace

CollisionDetector::CollisionDetector(const CollisionSettings& settings) : settings_(settings) {}

BodyId CollisionDetector::add_body(std::shared_ptr<const SphereTree> tree, const Transform& pose,
                                   bool is_static) {
  if (!tree || tree->empty()) throw Error("a body needs a non-empty sphere-tree");
  if (!finite(pose)) throw Error("a body's pose must be finite");
  std::uint32_t index = 0;
  if (free_bodies_.empty()) {
    index = static_cast<std::uint32_t>(bodies_.size());
    bodies_.emplace_back();
  } else {
    index = free_bodies_.back();
    free_bodies_.pop_back();
  }
  Body& body = bodies_[index];
  body.tree = std::move(tree);
  body.pose = pose;
  body.is_static = is_static;
  body.alive = true;
  body.proxy =
      broad_phase_.add(broad_phase_box(body), is_static ? ProxyKind::kStatic : ProxyKind::kDynamic);
  if (body_of_proxy_.size() <= body.proxy) body_of_proxy_.resize(body.proxy + 1);
  body_of_proxy_[body.proxy] = index;
  return {index};
}

void CollisionDetector::remove_body(BodyId id) {
  Body& body = bodies_[id.index];
  broad_phase_.remove(body.proxy);
  body = Body{};
  free_bodies_.push_back(id.index);
}

void CollisionDetector::set_pose(BodyId id, const Transform& pose) {
  Body& body = bodies_[id.index];
  body.pose = pose;
  if (body.is_static) broad_phase_.set_box(body.proxy, broad_phase_box(body));
}

void CollisionDetector::set_motion(BodyId id, const Vec3& displacement, float turn_reach) {
  Body& body = bodies_[id.index];
  body.displacement = displacement;
  body.turn_reach = turn_reach;
}

void CollisionDetector::set_asleep(BodyId id, bool asleep) { bodies_[id.index].asleep = asleep; }

// The body's bound, grown by half the contact margin (two grown boxes meet when the bodies are
// within the margin) and, with speculative contacts, by how far the body can move this step.
Aabb CollisionDetector::broad_phase_box(const Body& body) const {
  float grow = 0.5f * settings_.contact_margin;
  if (settings_.speculative) grow += body.displacement.norm() + body.turn_reach;
  Aabb box = world_bounds(*body.tree, body.pose, settings_.bounds_level);
  box.min.array() -= grow;
  box.max.array() += grow;
  return box;
}

// The gap up to which two bodies' spheres make contacts: the margin plus, with speculative
// contacts, a bound on how much closer any two of their points can come in the step.
float CollisionDetector::pair_margin(const Body& a, const Body& b) const {
  if (!settings_.speculative) return settings_.contact_margin;
  return settings_.contact_margin + (b.displacement - a.displacement).norm() + a.turn_reach +
         b.turn_reach;
}

float CollisionDetector::plane_margin(const Body& body) const {
  if (!settings_.speculative) return settings_.contact_margin;
  return settings_.contact_margin + std::max(-body.displacement.y(), 0.0f) + body.turn_reach;
}

Aabb CollisionDetector::bounds(BodyId id) const {
  return broad_phase_.box(bodies_[id.index].proxy);
}

const CollisionStats& CollisionDetector::detect(std::vector<Contact>& contacts) {
  contacts.clear();
  stats_ = {};
  stats_.bodies = static_cast<std::uint32_t>(broad_phase_.size());

  const Clock::time_point broad_start = Clock::now();
  for (const Body& body : bodies_) {
    if (body.alive && !body.is_static && !body.asleep) {
      broad_phase_.set_box(body.proxy, broad_phase_box(body));
    }
  }
  broad_phase_.update();
  stats_.candidate_pairs = static_cast<std::uint32_t>(broad_phase_.pairs().size());
  stats_.broad_phase_ms = elapsed_ms(broad_start);

  const Clock::time_point narrow_start = Clock::now();
  narrow_phase();
  stats_.narrow_phase_ms = elapsed_ms(narrow_start);

  const Clock::time_point contacts_start = Clock::now();
  std::size_t total = 0;
  for (std::size_t c = 0; c < chunks_used_; ++c) {
    chunks_[c].first_contact = total;
    total += chunks_[c].leaves.size();
  }
  contacts.resize(total);
  run_chunks([&](NarrowChunk& chunk) { make_contacts(chunk, contacts); });
  for (std::size_t c = 0; c < chunks_used_; ++c) {
    stats_.coincident_centres += chunks_[c].coincident_centres;
  }
  stats_.contacts_ms = elapsed_ms(contacts_start);
  stats_.contacts = static_cast<std::uint32_t>(contacts.size());
  return stats_;
}

// What is left of the time-critical budgets after `spent_microseconds` and `spent_tests` sphere
// tests in this call.
DescentSettings CollisionDetector::descent_budget(double spent_microseconds,
                                                  std::uint64_t spent_tests, float margin) const {
  DescentSettings descent;
  descent.margin = margin;
  descent.depth_a = settings_.tree_depth;
  descent.depth_b = settings_.tree_depth;
  // A budget that is on never reaches 0 (which would mean "off"): a pair met after the budget
  // is spent is resolved at its roots.
  if (settings_.max_sphere_tests > 0) {
    descent.max_sphere_tests =
        settings_.max_sphere_tests > spent_tests ? settings_.max_sphere_tests - spent_tests : 1;
  }
  if (settings_.max_microseconds > 0.0) {
    descent.max_microseconds = std::max(settings_.max_microseconds - spent_microseconds, 1e-3);
  }
  return descent;
}

// Splits the candidate pairs, then the bodies for the ground plane, into runs of fixed length
// (the same whatever the thread count). A budget is shared by the pairs in order: then all pairs
// are one run.
void CollisionDetector::plan_chunks(bool budget) {
  const std::size_t pairs = broad_phase_.pairs().size();
  const std::size_t pair_run = budget ? std::max<std::size_t>(pairs, 1) : kPairsPerChunk;
  const std::size_t bodies = settings_.ground_plane_height ? bodies_.size() : std::size_t{0};
  chunks_used_ = 0;
  const auto add = [&](std::size_t begin, std::size_t end, bool plane) {
    if (chunks_.size() <= chunks_used_) chunks_.emplace_back();
    NarrowChunk& chunk = chunks_[chunks_used_++];
    chunk.begin = begin;
    chunk.end = end;
    chunk.plane = plane;
    chunk.leaves.clear();
    chunk.sphere_tests = 0;
    chunk.leaf_pairs = 0;
    chunk.cut_short_pairs = 0;
    chunk.coincident_centres = 0;
  };
  for (std::size_t begin = 0; begin < pairs; begin += pair_run) {
    add(begin, std::min(begin + pair_run, pairs), false);
  }
  for (std::size_t begin = 0; begin < bodies; begin += kBodiesPerChunk) {
    add(begin, std::min(begin + kBodiesPerChunk, bodies), true);
  }
}

void CollisionDetector::narrow_phase() {
  const bool budget = settings_.max_sphere_tests > 0 || settings_.max_microseconds > 0.0;
  plan_chunks(budget);
  const Clock::time_point start = Clock::now();
  const auto work = [&](NarrowChunk& chunk) {
    if (!chunk.plane) {
      descend_pairs(chunk, start);
      return;
    }
    for (std::size_t i = chunk.begin; i < chunk.end; ++i) {
      const Body& body = bodies_[i];
      if (body.alive && !body.is_static && !body.asleep) {
        ground_plane_leaves(static_cast<std::uint32_t>(i), *settings_.ground_plane_height, chunk);
      }
    }
  };
  if (budget) {
    for (std::size_t c = 0; c < chunks_used_; ++c) work(chunks_[c]);
  } else {
    run_chunks(work);
  }
  for (std::size_t c = 0; c < chunks_used_; ++c) {
    const NarrowChunk& chunk = chunks_[c];
    stats_.sphere_tests += chunk.sphere_tests;
    stats_.leaf_pairs += chunk.leaf_pairs;
    stats_.pairs_cut_short += chunk.cut_short_pairs;
  }
}

void CollisionDetector::descend_pairs(NarrowChunk& chunk, Clock::time_point start) const {
  const std::span<const ProxyPair> pairs = broad_phase_.pairs();
  for (std::size_t p = chunk.begin; p < chunk.end; ++p) {
    const std::uint32_t ia = body_of_proxy_[pairs[p].a];
    const std::uint32_t ib = body_of_proxy_[pairs[p].b];
    const Body& a = bodies_[ia];
    const Body& b = bodies_[ib];
    const bool a_moves = !a.is_static && !a.asleep;
    const bool b_moves = !b.is_static && !b.asleep;
    if (!a_moves && !b_moves) continue;
    chunk.node_pairs.clear();
    const DescentSettings settings =
        descent_budget(1e3 * elapsed_ms(start), chunk.sphere_tests, pair_margin(a, b));
    const DescentStats descent =
        chunk.descent.descend(*a.tree, a.pose, *b.tree, b.pose, settings, chunk.node_pairs);
    chunk.sphere_tests += descent.sphere_tests;
    chunk.leaf_pairs += descent.leaf_pairs;
    chunk.cut_short_pairs += descent.cut_short_pairs;
    for (const NodePair& nodes : chunk.node_pairs) {
      chunk.leaves.push_back({ia, ib, nodes.node_a, nodes.node_b,
                              chunk.descent.world_sphere_a(*a.tree, nodes.node_a),
                              chunk.descent.world_sphere_b(*b.tree, nodes.node_b)});
    }
  }
}

// Descends one body's tree against the half-space y <= height: a subtree is skipped when its
// bound is above the plane by more than the body's margin; each leaf sphere within it is kept.
void CollisionDetector::ground_plane_leaves(std::uint32_t index, float height,
                                            NarrowChunk& chunk) const {
  const Body& body = bodies_[index];
  const SphereTree& tree = *body.tree;
  const std::uint32_t leaves_begin = tree.level_begin(last_level(tree, settings_.tree_depth));
  const float reach_down = height + plane_margin(body);
  std::vector<std::uint32_t>& stack = chunk.plane_stack;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const std::uint32_t node = stack.back();
    stack.pop_back();
    const Sphere& sphere = tree.sphere(node);
    const Vec3 center = body.pose.apply(sphere.center);
    ++chunk.sphere_tests;
    const bool leaf = tree.is_leaf(node) || node >= leaves_begin;
    if (center.y() - (leaf ? sphere.radius : tree.subtree_radius(node)) > reach_down) continue;
    if (!leaf) {
      for (std::uint32_t c = tree.first_child(node) + tree.child_count(node);
           c-- > tree.first_child(node);) {
        stack.push_back(c);
      }
      continue;
    }
    chunk.leaves.push_back({kGroundPlaneBody, index, 0, node, Sphere{}, {center, sphere.radius}});
    ++chunk.leaf_pairs;
  }
}

// One contact per pair of leaf spheres (paper eq. 1-3), in the narrow phase's order.
void CollisionDetector::make_contacts(NarrowChunk& chunk, std::vector<Contact>& contacts) const {
  std::uint32_t fallback_a = kGroundPlaneBody;
  std::uint32_t fallback_b = kGroundPlaneBody;
  Vec3 fallback = Vec3::UnitY();
  std::size_t out = chunk.first_contact;
  for (const LeafSpheres& leaves : chunk.leaves) {
    Contact& contact = contacts[out++];
    contact = Contact{};
    contact.body_a = leaves.body_a;
    contact.body_b = leaves.body_b;
    contact.leaf_a = leaves.leaf_a;
    contact.leaf_b = leaves.leaf_b;
    if (leaves.body_a == kGroundPlaneBody) {
      sphere_plane_contact(*settings_.ground_plane_height, leaves.sphere_b, contact);
    } else {
      // The pairs of one body pair are consecutive: one fallback normal serves them all.
      if (leaves.body_a != fallback_a || leaves.body_b != fallback_b) {
        fallback_a = leaves.body_a;
        fallback_b = leaves.body_b;
        fallback = fallback_normal(bodies_[fallback_a].pose.translation,
                                   bodies_[fallback_b].pose.translation);
      }
      if (sphere_sphere_contact(leaves.sphere_a, leaves.sphere_b, fallback, contact)) {
        ++chunk.coincident_centres;
      }
    }
  }
}

}  // namespace sphys
