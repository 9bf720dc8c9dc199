#pragma once

// Collision detection for a set of bodies (paper §3): Sweep & Prune over the bodies' bounds, the
// sphere-tree descent for every overlapping pair, one contact per overlapping leaf pair.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "sphys/contact.h"
#include "sphys/sphere_tree.h"
#include "sphys/sweep_and_prune.h"
#include "sphys/tree_descent.h"

namespace sphys {

// A body of the detector. A handle, never a pointer: storage may move.
struct BodyId {
  std::uint32_t index = 0;
  friend bool operator==(const BodyId&, const BodyId&) = default;
};

struct CollisionSettings {
  // Levels of every sphere-tree used, the root included; 0 uses them all (a depth-3 tree used as
  // depth 2: the nodes of the last used level are the leaves). unit: levels
  int tree_depth = 0;
  // Level whose spheres (with their subtree radii) bound a body for the broad phase: 0 is the
  // root's bound, cheapest to update; deeper levels give tighter boxes. unit: level
  int bounds_level = 0;
  // Time-critical narrow phase (paper §3.2): budgets for the narrow phase of a detect() call,
  // shared by the pairs in order; 0 turns a budget off. With both off, detection is exact.
  std::uint64_t max_sphere_tests = 0;  // unit: sphere tests per detect()
  double max_microseconds = 0.0;       // unit: µs of descent per detect()
  // The exact half-space ground y <= height (sphere against plane), instead of or besides a
  // static body carrying the paper's octree of a thin box. unit: m
  std::optional<float> ground_plane_height;
};

// Figures of one detect() call.
struct CollisionStats {
  std::uint32_t bodies = 0;
  std::uint32_t candidate_pairs = 0;  // overlapping bounds from the broad phase
  std::uint64_t sphere_tests = 0;     // in the narrow phase, ground plane included
  std::uint32_t leaf_pairs = 0;       // overlapping leaf pairs (ground plane: leaves under it)
  std::uint32_t contacts = 0;
  std::uint32_t pairs_cut_short = 0;     // node pairs left when a time-critical budget ran out
  std::uint32_t coincident_centres = 0;  // contacts whose normal came from the fallback
  double broad_phase_ms = 0.0;           // unit: ms
  double narrow_phase_ms = 0.0;          // sphere-tree descents. unit: ms
  double contacts_ms = 0.0;              // contact data from the leaf pairs (eq. 1-3). unit: ms
};

class CollisionDetector {
 public:
  explicit CollisionDetector(const CollisionSettings& settings = {});

  // Throws sphys::Error for a missing or empty tree or a non-finite pose. A pose places the
  // body frame: the tree's centres are given in it, and its origin is the centre of mass.
  BodyId add_body(std::shared_ptr<const SphereTree> tree, const Transform& pose, bool is_static);
  void remove_body(BodyId body);
  void set_pose(BodyId body, const Transform& pose);
  [[nodiscard]] const Transform& pose(BodyId body) const { return bodies_[body.index].pose; }
  [[nodiscard]] const CollisionSettings& settings() const { return settings_; }
  void set_settings(const CollisionSettings& settings) { settings_ = settings; }

  // Replaces `contacts` with this step's contacts, ordered by body pair (as the broad phase
  // lists them, then the ground plane's by body) and within a pair by the descent's order.
  const CollisionStats& detect(std::vector<Contact>& contacts);
  [[nodiscard]] const CollisionStats& stats() const { return stats_; }
  // The broad phase's current bound of a body (world frame).
  [[nodiscard]] Aabb bounds(BodyId body) const;

 private:
  struct Body {
    std::shared_ptr<const SphereTree> tree;
    Transform pose;
    ProxyId proxy = 0;
    bool is_static = false;
    bool alive = false;
  };

  // Two overlapping leaf spheres in the world frame, what the narrow phase hands to the contacts
  // phase. Against the ground plane, body_a is kGroundPlaneBody and sphere_a is unused.
  struct LeafSpheres {
    std::uint32_t body_a = 0;
    std::uint32_t body_b = 0;
    std::uint32_t leaf_a = 0;
    std::uint32_t leaf_b = 0;
    Sphere sphere_a;
    Sphere sphere_b;
  };

  void narrow_phase();
  void ground_plane_leaves(std::uint32_t body, float height);
  void make_contacts(std::vector<Contact>& contacts);
  [[nodiscard]] DescentSettings descent_budget(double spent_microseconds) const;

  CollisionSettings settings_;
  std::vector<Body> bodies_;
  std::vector<std::uint32_t> free_bodies_;
  std::vector<std::uint32_t> body_of_proxy_;
  SweepAndPrune broad_phase_;
  TreeDescent descent_;
  std::vector<NodePair> node_pairs_;
  std::vector<LeafSpheres> leaf_spheres_;
  std::vector<std::uint32_t> plane_stack_;
  CollisionStats stats_;
};

}  // namespace sphys
