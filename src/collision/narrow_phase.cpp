// The narrow phase of the collision detector: each job's leaf spheres within its pair's gap,
// reused from its record or from a sphere-tree descent (or the ground plane's), and the contacts
// and manifolds made from them (paper eq. 1-3, reduction per pair). Runs on one chunk of jobs at a
// time, on any thread; the detector (collision_detector.cpp) plans the chunks and places their
// contacts.

#include <algorithm>
#include <cmath>

#include "collision/collision_detector.h"
#include "collision/narrow_chunk.h"
#include "core/stopwatch.h"

namespace sphys {
namespace {

// Body b's pose in body a's frame.
Transform relative_pose(const Transform& a, const Transform& b) {
  const Quat inverse = a.rotation.conjugate();
  return {inverse * b.rotation, inverse * (b.translation - a.translation)};
}

// How far any point of a body within `extent` of its origin can have moved between two of its
// poses (relative ones here): the origin's move plus the turn's reach. unit: m
float pose_change(const Transform& from, const Transform& to, float extent) {
  Quat turn = from.rotation.conjugate() * to.rotation;
  const float angle = 2.0f * std::atan2(turn.vec().norm(), std::abs(turn.w()));
  return (to.translation - from.translation).norm() + angle * extent;
}

// The part of a tree a node lies in: its first-level ancestor (the root for the root). A node's
// parent has a smaller index, so the walk ends within the tree's depth.
std::uint32_t part_of(const SphereTree& tree, std::uint32_t node) {
  while (tree.parent(node) > 0) node = static_cast<std::uint32_t>(tree.parent(node));
  return node;
}

// The deepest a crowd's root contact reports, as a share of the smaller root's radius (see
// make_contacts()). unit: dimensionless
constexpr float kCrowdDepth = 0.5f;

}  // namespace

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

void CollisionDetector::narrow_phase(NarrowChunk& chunk, StepClock::time_point start) {
  for (std::size_t j = chunk.begin; j < chunk.end; ++j) pair_leaves(jobs_[j], chunk, start);
}

// A pair whose bodies barely moved relative to each other since its last descent, within the gap
// that descent looked up to, keeps its leaf pairs: they are placed at the new poses.
bool CollisionDetector::reuse(PairRecord& record, const Transform& relative, float margin,
                              float extent_b, std::uint32_t body_a, std::uint32_t body_b,
                              NarrowChunk& chunk) {
  if (settings_.reuse_distance <= 0.0f || budget() || record.descent_margin < 0.0f) return false;
  const float moved = pose_change(record.relative, relative, extent_b);
  if (!(moved <= settings_.reuse_distance && margin + moved <= record.descent_margin)) {
    return false;
  }
  const Body& b = bodies_[body_b];
  for (std::uint32_t i = record.first; i < record.first + record.count; ++i) {
    const Contact& old = cache_.previous_contacts()[i];
    LeafSpheres leaves{body_a, body_b, old.leaf_a, old.leaf_b, Sphere{}, Sphere{}};
    const Sphere& leaf_b = b.tree->sphere(old.leaf_b);
    leaves.sphere_b = {pose_of(body_b).apply(leaf_b.center), leaf_b.radius};
    if (body_a != kGroundPlaneBody) {
      const Sphere& leaf_a = bodies_[body_a].tree->sphere(old.leaf_a);
      leaves.sphere_a = {pose_of(body_a).apply(leaf_a.center), leaf_a.radius};
    }
    chunk.leaves.push_back(leaves);
  }
  ++chunk.counters.reused_pairs;
  return true;
}

// The leaf spheres of one job within its pair's gap: reused from its record, or from a descent.
void CollisionDetector::pair_leaves(const Job& job, NarrowChunk& chunk,
                                    StepClock::time_point start) {
  PairLeaves pair;
  pair.plane = job.plane;
  pair.leaves_begin = static_cast<std::uint32_t>(chunk.leaves.size());
  if (job.plane) {
    Body& body = bodies_[job.index];
    body.ground_done = true;
    const Transform& pose = pose_of(job.index);
    PairRecord& record = cache_.ground_record(job.index);
    pair.record = &record;
    const float margin = plane_margin(body);
    pair.reused = reuse(record, pose, margin, store_->extents()[job.index], kGroundPlaneBody,
                        job.index, chunk);
    if (!pair.reused) {
      const float looked = margin + (budget() ? 0.0f : settings_.reuse_distance);
      ground_plane_leaves(job.index, *settings_.ground_plane_height + looked, chunk);
      record.relative = pose;
      record.descent_margin = looked;
      ++chunk.counters.descended_pairs;
    }
  } else {
    PairRecord& record = cache_.records()[job.index];
    pair.record = &record;
    const std::uint32_t ia = body_of_proxy_[record.proxies.a];
    const std::uint32_t ib = body_of_proxy_[record.proxies.b];
    const Body& a = bodies_[ia];
    const Body& b = bodies_[ib];
    const float margin = pair_margin(a, b);
    // Parts say where two bodies will meet only while they close by less than the smaller's
    // extent: beyond, every part pair of the two falls within the gap (a 1 km bunny thrown at
    // 10⁴ m/s went non-finite with them), and the manifold is as good a guess.
    const float reach = margin - settings_.contact_margin;
    pair.fast = reach > settings_.fast_pair_reach &&
                reach <= std::min(store_->extents()[ia], store_->extents()[ib]);
    const Transform& pose_a = pose_of(ia);
    const Transform& pose_b = pose_of(ib);
    const Transform relative = relative_pose(pose_a, pose_b);
    // Two crowded bodies touch at their roots alone: a crowd has pairs by the square of its
    // bodies, each of whose descents would overlap at every level.
    const bool crowd = crowded(ia) && crowded(ib);
    pair.crowd = crowd;
    pair.reused = !crowd && reuse(record, relative, margin, store_->extents()[ib], ia, ib, chunk);
    if (!pair.reused) {
      const float looked = margin + (budget() ? 0.0f : settings_.reuse_distance);
      chunk.node_pairs.clear();
      // The clock is read only for a time budget: a read per pair cost 1.7% of a step at 1,000
      // bunnies.
      const double spent = settings_.max_microseconds > 0.0 ? 1e3 * elapsed_ms(start) : 0.0;
      DescentSettings settings = descent_budget(spent, chunk.counters.sphere_tests, looked);
      if (crowd) {
        settings.depth_a = 1;
        settings.depth_b = 1;
      }
      const DescentStats descent =
          chunk.descent.descend(*a.tree, pose_a, *b.tree, pose_b, settings, chunk.node_pairs);
      chunk.counters.sphere_tests += descent.sphere_tests;
      chunk.counters.leaf_pairs += descent.leaf_pairs;
      chunk.counters.pairs_cut_short += descent.cut_short_pairs;
      for (const NodePair& nodes : chunk.node_pairs) {
        chunk.leaves.push_back({ia, ib, nodes.node_a, nodes.node_b,
                                chunk.descent.world_sphere_a(*a.tree, nodes.node_a),
                                chunk.descent.world_sphere_b(*b.tree, nodes.node_b)});
      }
      record.relative = relative;
      record.descent_margin = crowd ? -1.0f : looked;  // roots' contacts are not to be reused
      ++chunk.counters.descended_pairs;
    }
    record.done = true;
  }
  pair.leaves_end = static_cast<std::uint32_t>(chunk.leaves.size());
  chunk.pairs.push_back(pair);
}

// Descends one body's tree against the half-space y <= height: a subtree is skipped when its
// bound is above `reach_down` (the plane's height plus the body's gap); each leaf sphere within it
// is kept.
void CollisionDetector::ground_plane_leaves(std::uint32_t index, float reach_down,
                                            NarrowChunk& chunk) const {
  const SphereTree& tree = *bodies_[index].tree;
  const Transform& pose = pose_of(index);
  const std::uint32_t leaves_begin = tree.level_begin(tree.last_level(settings_.tree_depth));
  std::vector<std::uint32_t>& stack = chunk.plane_stack;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const std::uint32_t node = stack.back();
    stack.pop_back();
    const Sphere& sphere = tree.sphere(node);
    const Vec3 center = pose.apply(sphere.center);
    ++chunk.counters.sphere_tests;
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
    ++chunk.counters.leaf_pairs;
  }
}

// One contact per pair of leaf spheres (paper eq. 1-3), in the narrow phase's order; then, pair by
// pair, the reduction to a manifold, or for a reused pair its contacts' own depth offsets and
// normals.
void CollisionDetector::make_contacts(NarrowChunk& chunk) const {
  const bool measure = settings_.measure_penetration;
  for (PairLeaves& pair : chunk.pairs) {
    pair.contacts_begin = static_cast<std::uint32_t>(chunk.contacts.size());
    if (pair.leaves_end == pair.leaves_begin) continue;
    const LeafSpheres& first = chunk.leaves[pair.leaves_begin];
    const bool plane = first.body_a == kGroundPlaneBody;
    // The pairs of one body pair share one fallback normal.
    const Vec3 fallback = plane ? Vec3::UnitY()
                                : fallback_normal(pose_of(first.body_a).translation,
                                                  pose_of(first.body_b).translation,
                                                  pair_key(first.body_a, first.body_b));
    chunk.run.clear();
    for (std::uint32_t l = pair.leaves_begin; l < pair.leaves_end; ++l) {
      const LeafSpheres& leaves = chunk.leaves[l];
      Contact contact;
      contact.body_a = leaves.body_a;
      contact.body_b = leaves.body_b;
      contact.leaf_a = leaves.leaf_a;
      contact.leaf_b = leaves.leaf_b;
      if (plane) {
        sphere_plane_contact(*settings_.ground_plane_height, leaves.sphere_b, contact);
      } else if (sphere_sphere_contact(leaves.sphere_a, leaves.sphere_b, fallback, contact)) {
        ++chunk.counters.coincident_centres;
      }
      if (measure && contact.depth > 0.0f) {
        chunk.deepest_penetration = std::max(chunk.deepest_penetration, contact.depth);
        chunk.penetration_sum += contact.depth;
        ++chunk.penetrating_contacts;
      }
      if (pair.crowd) {
        // The soft step pushes a pair apart the faster the deeper it overlaps, and a crowd's
        // pushes add up from body to body: at the full depth of bodies spawned on each other, a
        // crowd bursts at several m/s. Capped, it parts as a pile of bodies overlapping a little.
        contact.depth = std::min(
            contact.depth, kCrowdDepth * std::min(leaves.sphere_a.radius, leaves.sphere_b.radius));
      }
      chunk.run.push_back(contact);
    }
    const Quat rotation_a = plane ? Quat::Identity() : pose_of(first.body_a).rotation;
    if (pair.reused) {
      const std::uint32_t old_first = pair.record->first;
      for (std::size_t i = 0; i < chunk.run.size(); ++i) {
        const ContactShape& shape = cache_.previous_shapes()[old_first + i];
        Contact contact = chunk.run[i];
        contact.depth += shape.depth_offset;
        contact.normal = rotation_a * shape.normal_in_a;
        chunk.contacts.push_back(contact);
        chunk.shapes.push_back(shape);
      }
      continue;
    }
    const std::size_t reduced_begin = chunk.contacts.size();
    if (settings_.manifold_points == 0) {
      chunk.contacts.insert(chunk.contacts.end(), chunk.run.begin(), chunk.run.end());
    } else if (pair.fast) {
      const SphereTree& tree_a = *bodies_[first.body_a].tree;
      const SphereTree& tree_b = *bodies_[first.body_b].tree;
      chunk.parts.clear();
      for (const Contact& contact : chunk.run) {
        chunk.parts.push_back(std::uint64_t{part_of(tree_a, contact.leaf_a)} << 32 |
                              part_of(tree_b, contact.leaf_b));
      }
      chunk.reducer.reduce_by_parts(chunk.run, chunk.parts, cache_.last_contacts(*pair.record),
                                    chunk.contacts);
    } else {
      chunk.reducer.reduce(chunk.run, settings_.manifold_points, cache_.last_contacts(*pair.record),
                           chunk.contacts);
    }
    for (std::size_t k = reduced_begin; k < chunk.contacts.size(); ++k) {
      const Contact& contact = chunk.contacts[k];
      float own_depth = contact.depth;
      for (const Contact& leaf : chunk.run) {
        if (leaf.leaf_a == contact.leaf_a && leaf.leaf_b == contact.leaf_b) {
          own_depth = leaf.depth;
          break;
        }
      }
      chunk.shapes.push_back({contact.depth - own_depth, rotation_a.conjugate() * contact.normal});
    }
  }
}

}  // namespace sphys
