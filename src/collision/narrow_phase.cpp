// The narrow phase of the collision detector: each job's leaf spheres within its pair's gap,
// reused from its record or from a sphere-tree descent (or the ground plane's), and the contacts
// and manifolds made from them (paper eq. 1-3, reduction per pair). Runs on one chunk of jobs at a
// time, on any thread; the detector (collision_detector.cpp) plans the chunks and places their
// contacts.

#include <algorithm>

#include "collision/collision_detector.h"
#include "collision/crowd.h"
#include "collision/narrow_chunk.h"
#include "collision/pair_kind.h"
#include "core/stopwatch.h"

namespace sphys {
namespace {

// Body b's pose in body a's frame.
Transform relative_pose(const Transform& a, const Transform& b) {
  const Quat inverse = a.rotation.conjugate();
  return {inverse * b.rotation, inverse * (b.translation - a.translation)};
}

// The part of a tree a node lies in: its first-level ancestor (the root for the root). A node's
// parent has a smaller index, so the walk ends within the tree's depth.
std::uint32_t part_of(const SphereTree& tree, std::uint32_t node) {
  while (tree.parent(node) > 0) node = static_cast<std::uint32_t>(tree.parent(node));
  return node;
}

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

// The gap a descent looks up to: the pair's, and beyond it by the reuse distance, so that the next
// narrow phases may reuse its leaf pairs (no pair is reused under a time-critical budget). unit: m
float CollisionDetector::descent_gap(float margin) const {
  return margin + (settings_.has_budget() ? 0.0f : settings_.reuse_distance);
}

// What is left of the time-critical budgets after `spent_microseconds` and `spent_tests` sphere
// tests in this call, for a descent within the gap `margin`.
DescentSettings CollisionDetector::descent_budget(double spent_microseconds,
                                                  std::uint64_t spent_tests, float margin) const {
  DescentSettings descent;
  descent.margin = margin;
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

// A reused pair's leaf pairs: the record's contacts' leaves, placed at the new poses.
void CollisionDetector::kept_leaves(const PairRecord& record, std::uint32_t body_a,
                                    std::uint32_t body_b, NarrowChunk& chunk) const {
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
}

// The leaf spheres of one job within its pair's gap, as its kind says: the record's kept leaf
// pairs, or a descent (the ground plane's, or the trees', to the roots alone for a crowd). The
// descent is written here, at its one call, where the compiler keeps it inline.
void CollisionDetector::pair_leaves(const Job& job, NarrowChunk& chunk,
                                    StepClock::time_point start) {
  PairLeaves pair;
  pair.plane = job.plane;
  pair.leaves_begin = static_cast<std::uint32_t>(chunk.leaves.size());
  const std::span<const float> extents = store_->extents();
  if (job.plane) {
    Body& body = bodies_[job.index];
    body.ground_done = true;
    const Transform& pose = pose_of(job.index);
    PairRecord& record = cache_.ground_record(job.index);
    pair.record = &record;
    const float margin = plane_margin(body);
    pair.kind = pair_kind({.record = &record,
                           .relative = &pose,
                           .margin = margin,
                           .extent_b = extents[job.index],
                           .plane = true},
                          settings_);
    if (pair.kind == PairKind::kReused) {
      kept_leaves(record, kGroundPlaneBody, job.index, chunk);
    } else {
      const float looked = descent_gap(margin);
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
    const Transform& pose_a = pose_of(ia);
    const Transform& pose_b = pose_of(ib);
    const Transform relative = relative_pose(pose_a, pose_b);
    pair.kind = pair_kind({.record = &record,
                           .relative = &relative,
                           .margin = margin,
                           .extent_b = extents[ib],
                           .smaller_extent = std::min(extents[ia], extents[ib]),
                           .crowded = crowded(ia) && crowded(ib)},
                          settings_);
    if (pair.kind == PairKind::kReused) {
      kept_leaves(record, ia, ib, chunk);
    } else {
      // A crowd's pair descends to its roots alone (crowd.h), and their contact is not reused.
      const bool crowd = pair.kind == PairKind::kCrowded;
      const float looked = descent_gap(margin);
      chunk.node_pairs.clear();
      // The clock is read only for a time budget: a read per pair cost 1.7% of a step at 1,000
      // bunnies.
      const double spent = settings_.max_microseconds > 0.0 ? 1e3 * elapsed_ms(start) : 0.0;
      DescentSettings settings = descent_budget(spent, chunk.counters.sphere_tests, looked);
      settings.depth_a = crowd ? kCrowdTreeDepth : settings_.tree_depth;
      settings.depth_b = settings.depth_a;
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
      record.descent_margin = crowd ? -1.0f : looked;
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
// pair, as its kind says: a reused pair's contacts take their own depth offsets and normals, a
// crowd's its capped depth, the others are reduced (or not, the paper's) and their shapes noted.
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
      chunk.run.push_back(contact);
    }
    const Quat rotation_a = plane ? Quat::Identity() : pose_of(first.body_a).rotation;
    const std::size_t reduced_begin = chunk.contacts.size();
    switch (pair.kind) {
      case PairKind::kReused:
        reused_contacts(*pair.record, rotation_a, chunk);
        continue;  // its shapes are the record's
      case PairKind::kCrowded:
        for (std::size_t i = 0; i < chunk.run.size(); ++i) {
          const LeafSpheres& roots = chunk.leaves[pair.leaves_begin + i];
          chunk.run[i].depth =
              crowd_contact_depth(chunk.run[i].depth, roots.sphere_a, roots.sphere_b);
        }
        [[fallthrough]];  // its one contact, capped, goes as the paper's do
      case PairKind::kPaper:
        chunk.contacts.insert(chunk.contacts.end(), chunk.run.begin(), chunk.run.end());
        break;
      case PairKind::kFastByParts: {
        const SphereTree& tree_a = *bodies_[first.body_a].tree;
        const SphereTree& tree_b = *bodies_[first.body_b].tree;
        chunk.parts.clear();
        for (const Contact& contact : chunk.run) {
          chunk.parts.push_back(std::uint64_t{part_of(tree_a, contact.leaf_a)} << 32 |
                                part_of(tree_b, contact.leaf_b));
        }
        chunk.reducer.reduce_by_parts(chunk.run, chunk.parts, cache_.last_contacts(*pair.record),
                                      chunk.contacts);
        break;
      }
      case PairKind::kManifold:
        chunk.reducer.reduce(chunk.run, settings_.manifold_points,
                             cache_.last_contacts(*pair.record), chunk.contacts);
        break;
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

// A reused pair's contacts, each with its own depth offset and normal (in body a's frame) as the
// record kept them.
void CollisionDetector::reused_contacts(const PairRecord& record, const Quat& rotation_a,
                                        NarrowChunk& chunk) const {
  for (std::size_t i = 0; i < chunk.run.size(); ++i) {
    const ContactShape& shape = cache_.previous_shapes()[record.first + i];
    Contact contact = chunk.run[i];
    contact.depth += shape.depth_offset;
    contact.normal = rotation_a * shape.normal_in_a;
    chunk.contacts.push_back(contact);
    chunk.shapes.push_back(shape);
  }
}

}  // namespace sphys
