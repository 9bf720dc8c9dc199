#pragma once

// Collision detection for a set of bodies (paper §3): Sweep & Prune over the bodies' bounds, the
// sphere-tree descent for every overlapping pair, one contact per overlapping leaf pair.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "sphys/contact.h"
#include "sphys/parallel.h"
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
  // Leaf spheres apart by up to this gap make contacts too, with negative depth, so that a
  // response can stop bodies before they touch. unit: m
  float contact_margin = 0.0f;
  // Speculative contacts: the gap allowed for a pair grows by how far the two can close in the
  // coming step, from the motions given by set_motion() (swept sphere bounds).
  bool speculative = false;
};

// Figures of one detect() call.
struct CollisionStats {
  std::uint32_t bodies = 0;
  std::uint32_t candidate_pairs = 0;  // overlapping bounds from the broad phase
  std::uint64_t sphere_tests = 0;     // in the narrow phase, ground plane included
  // Overlapping leaf pairs (ground plane: leaves under it), and those within their pair's gap.
  std::uint32_t leaf_pairs = 0;
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
  // How far a body may move in the coming step, for speculative contacts: its centre of mass by
  // `displacement` and any of its points by up to `turn_reach` more from turning. unit: m
  void set_motion(BodyId body, const Vec3& displacement, float turn_reach);
  // A sleeping body is checked only against awake moving bodies (pairs of sleeping or static
  // bodies, and a sleeping body against the ground plane, make no contacts).
  void set_asleep(BodyId body, bool asleep);
  [[nodiscard]] const CollisionSettings& settings() const { return settings_; }
  void set_settings(const CollisionSettings& settings) { settings_ = settings; }
  // The threads the narrow phase and the contacts run on (none: the caller's thread). The
  // contacts and figures do not depend on them. A time-critical budget is spent pair after pair
  // in order, so with one the narrow phase runs on the caller's thread. `parallel` must outlive
  // the detector or be replaced first.
  void set_parallel(const Parallel* parallel) { parallel_ = parallel; }

  // Replaces `contacts` with this step's contacts, ordered by body pair (as the broad phase
  // lists them, then the ground plane's by body) and within a pair by the descent's order. The
  // contacts of one body pair are consecutive. With a contact margin or speculative contacts,
  // pairs of leaves that are apart by less than their pair's gap come too (negative depth).
  const CollisionStats& detect(std::vector<Contact>& contacts);
  [[nodiscard]] const CollisionStats& stats() const { return stats_; }
  // The broad phase's current bound of a body (world frame).
  [[nodiscard]] Aabb bounds(BodyId body) const;

 private:
  struct Body {
    std::shared_ptr<const SphereTree> tree;
    Transform pose;
    ProxyId proxy = 0;
    Vec3 displacement = Vec3::Zero();
    float turn_reach = 0.0f;
    bool is_static = false;
    bool alive = false;
    bool asleep = false;
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

  // The narrow phase's work on a run of consecutive candidate pairs, or of bodies against the
  // ground plane, done on one thread into its own buffers; the runs' leaf pairs make contacts in
  // the runs' order, so the result is the same whatever thread did which run.
  struct NarrowChunk {
    std::size_t begin = 0;  // candidate pairs, or bodies when `plane`
    std::size_t end = 0;
    bool plane = false;
    TreeDescent descent;
    std::vector<NodePair> node_pairs;
    std::vector<std::uint32_t> plane_stack;
    std::vector<LeafSpheres> leaves;
    std::uint64_t sphere_tests = 0;
    std::uint32_t leaf_pairs = 0;
    std::uint32_t cut_short_pairs = 0;
    std::uint32_t coincident_centres = 0;
    std::size_t first_contact = 0;  // where its contacts go in detect()'s output
  };

  [[nodiscard]] Aabb broad_phase_box(const Body& body) const;
  [[nodiscard]] float pair_margin(const Body& a, const Body& b) const;
  [[nodiscard]] float plane_margin(const Body& body) const;
  void narrow_phase();
  void plan_chunks(bool budget);
  void descend_pairs(NarrowChunk& chunk, std::chrono::steady_clock::time_point start) const;
  void ground_plane_leaves(std::uint32_t body, float height, NarrowChunk& chunk) const;
  void make_contacts(NarrowChunk& chunk, std::vector<Contact>& contacts) const;
  [[nodiscard]] DescentSettings descent_budget(double spent_microseconds, std::uint64_t spent_tests,
                                               float margin) const;
  // Calls fn(chunk) for each planned chunk, on the detector's threads.
  template <class Fn>
  void run_chunks(const Fn& fn) {
    const auto each = [&](std::size_t c) { fn(chunks_[c]); };
    if (parallel_ != nullptr) {
      parallel_->for_each(chunks_used_, each);
    } else {
      for (std::size_t c = 0; c < chunks_used_; ++c) each(c);
    }
  }

  CollisionSettings settings_;
  std::vector<Body> bodies_;
  std::vector<std::uint32_t> free_bodies_;
  std::vector<std::uint32_t> body_of_proxy_;
  SweepAndPrune broad_phase_;
  std::vector<NarrowChunk> chunks_;
  std::size_t chunks_used_ = 0;
  const Parallel* parallel_ = nullptr;
  CollisionStats stats_;
};

}  // namespace sphys
