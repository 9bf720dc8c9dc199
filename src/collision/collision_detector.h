#pragma once

// Collision detection for a set of bodies (paper §3): Sweep & Prune over the bodies' bounds, the
// sphere-tree descent for every overlapping pair, one contact per overlapping leaf pair.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <variant>
#include <vector>

#include "collision/cell_sweep_and_prune.h"
#include "collision/detector_settings.h"
#include "collision/pair_cache.h"
#include "collision/pair_kind.h"
#include "collision/sweep_and_prune.h"
#include "collision/tree_descent.h"
#include "sphys/body_store.h"
#include "sphys/collision_settings.h"
#include "sphys/contact.h"
#include "sphys/parallel.h"
#include "sphys/sphere_tree.h"
#include "sphys/step_stats.h"

namespace sphys {

// Figures of one detect() call.
struct CollisionStats : DetectionCounters {
  std::uint32_t bodies = 0;
  std::uint32_t contacts = 0;  // in the pair cache after this detection (reduced, when reduced)
  // Pairs of two dynamic bodies that had contacts in their last narrow phase and have none now
  // (or that the broad phase dropped): the islands they joined may have split.
  std::uint32_t parted_pairs = 0;
  // Crowds (CollisionSettings::crowd_pairs_per_body): the moving bodies in a crowd.
  std::uint32_t crowded_bodies = 0;
  // With DetectorSettings::measure_penetration, over the leaf pairs that overlap.
  float deepest_penetration = 0.0f;  // unit: m
  double penetration_sum = 0.0;      // unit: m
  std::uint32_t penetrating_contacts = 0;
  double broad_phase_ms = 0.0;   // unit: ms
  double narrow_phase_ms = 0.0;  // sphere-tree descents. unit: ms
  // Contact data from the leaf pairs (eq. 1-3), the reduction to manifolds and the carrying over
  // of each contact's memory. unit: ms
  double contacts_ms = 0.0;
  // Of each, the time outside the threads' loops (StepStats::serial_ms). unit: ms
  double broad_phase_serial_ms = 0.0;
  double narrow_phase_serial_ms = 0.0;
  double contacts_serial_ms = 0.0;
};

class ContactReducer;

class CollisionDetector final : public SlotArrays {
 public:
  explicit CollisionDetector(const DetectorSettings& settings = {});
  ~CollisionDetector();

  // The bodies: their poses, whether they are static, asleep or alive, and their extents are
  // read from the store, never copied (a static body must stay where it was added); the
  // detector's own per-body arrays grow with the store's. `bodies` must outlive the detector's
  // use or be replaced first.
  void set_bodies(BodyStore& bodies);
  void grow_slots(std::uint32_t slots) override;
  // The body in a slot of the store joins the broad phase with its sphere-tree, whose centres
  // are given in the body frame. Throws sphys::Error for a missing or empty tree or a
  // non-finite pose.
  void add_body(std::uint32_t slot, std::shared_ptr<const SphereTree> tree);
  // Before the store frees the slot: the body's pairs and their contacts' memory go with it.
  void remove_body(std::uint32_t slot);
  // Appends the bodies paired with a body in the last broad phase (within the contact margin of
  // it, or about to be), asleep ones included.
  void paired_bodies(std::uint32_t slot, std::vector<std::uint32_t>& out) const;
  // The body's bound at its pose in the store (the tree's spheres at CollisionSettings::
  // bounds_level) for the next detections, which grow it by the motion: whoever moves a body
  // bounds it again, once (the world's finalize pass). Touches the body's own entry alone, so
  // bodies may be bounded on several threads.
  void bound_at_pose(std::uint32_t slot);
  // How far a body may move in the coming step, for speculative contacts: its centre of mass by
  // `displacement` and any of its points by up to `turn_reach` more from turning. unit: m
  void set_motion(std::uint32_t slot, const Vec3& displacement, float turn_reach);
  [[nodiscard]] const DetectorSettings& settings() const { return settings_; }
  // The broad phase stays the one the detector was made with.
  void set_settings(const DetectorSettings& settings);
  // Whether the broad phase found the body's box in a crowd at the last detect()
  // (CollisionSettings::crowd_pairs_per_body).
  [[nodiscard]] bool crowded(std::uint32_t slot) const;
  // Body pairs (store slots, alive) whose contacts with each other do not count, such as the
  // bodies a joint holds together: their pairs make no contacts from the next detection on.
  // Replaces the last list.
  void set_unpaired(std::span<const std::pair<std::uint32_t, std::uint32_t>> body_pairs);

  // The threads the narrow phase and the contacts run on (none: the caller's thread). The
  // contacts and figures do not depend on them. A time-critical budget is spent pair after pair
  // in order, so with one the narrow phase runs on the caller's thread. `parallel` must outlive
  // the detector or be replaced first.
  void set_parallel(const Parallel* parallel) { parallel_ = parallel; }

  // The broad phase, then the narrow phase of every candidate pair with a moving body (the
  // store's awake bodies; a sleeping body is checked only against them) and of every moving body
  // against the ground plane: contacts() becomes this step's contacts, ordered by body pair (as the
  // broad phase lists them, then the ground plane's by body) and within a pair by the descent's
  // order (or the reduction's). The contacts of one body pair are consecutive. With a contact
  // margin or speculative contacts, pairs of leaves that are apart by less than their pair's gap
  // come too (negative depth). Each contact's memory() is carried over from the contact of the same
  // leaf pair in the same body pair's last narrow phase (a new one starts empty). Figures of this
  // call.
  const CollisionStats& detect();
  // The narrow phase of the pairs detect() passed over because neither body moved, for those of
  // them with a body that moves now (woken since), and of the woken bodies against the ground
  // plane: their contacts are appended to contacts(), each pair's together. Figures of this call
  // alone, so that a step adds each pair's work once.
  const CollisionStats& detect_woken();
  [[nodiscard]] std::span<const Contact> contacts() const { return cache_.contacts(); }
  [[nodiscard]] std::span<ContactMemory> memory() { return cache_.memory(); }
  [[nodiscard]] const CollisionStats& stats() const { return stats_; }
  // The broad phase's current bound of a body (world frame).
  [[nodiscard]] Aabb bounds(std::uint32_t slot) const;
  // The sphere-tree a body joined with (body frame).
  [[nodiscard]] const SphereTree& tree(std::uint32_t slot) const { return *bodies_[slot].tree; }
  [[nodiscard]] const std::shared_ptr<const SphereTree>& shared_tree(std::uint32_t slot) const {
    return bodies_[slot].tree;
  }

 private:
  using PairRecord = PairCache::Record;
  using ContactShape = PairCache::Shape;

  // What the detector keeps of a body beside the store's state.
  struct Body {
    std::shared_ptr<const SphereTree> tree;
    ProxyId proxy = 0;
    Vec3 displacement = Vec3::Zero();
    float turn_reach = 0.0f;
    Aabb pose_box;             // the tree's bound at the body's pose (bound_at_pose)
    bool ground_done = false;  // its ground plane pair had its narrow phase in this step
  };

  // Two leaf spheres within their pair's gap in the world frame, what the narrow phase hands to
  // the contacts phase. Against the ground plane, body_a is kGroundPlaneBody and sphere_a is
  // unused.
  struct LeafSpheres {
    std::uint32_t body_a = 0;
    std::uint32_t body_b = 0;
    std::uint32_t leaf_a = 0;
    std::uint32_t leaf_b = 0;
    Sphere sphere_a;
    Sphere sphere_b;
  };

  // One pair the narrow phase found leaf spheres for: its record and its leaves in the chunk.
  struct PairLeaves {
    PairRecord* record = nullptr;
    bool plane = false;  // the record is a body's against the ground plane
    std::uint32_t leaves_begin = 0;
    std::uint32_t leaves_end = 0;
    PairKind kind = PairKind::kManifold;  // decided by pair_kind() in the narrow phase
    std::uint32_t contacts_begin = 0;     // its contacts in the chunk's output
  };

  // The narrow phase's work on a run of jobs (collision/narrow_chunk.h).
  struct NarrowChunk;

  // A job of the narrow phase: a candidate pair's index, or a body's against the ground plane.
  struct Job {
    std::uint32_t index = 0;
    bool plane = false;
  };

  [[nodiscard]] const Transform& pose_of(std::uint32_t slot) const { return store_->poses()[slot]; }
  [[nodiscard]] bool moves(std::uint32_t slot) const { return store_->moving()[slot] != 0; }

  // Whether a record joined two dynamic bodies by contacts in its last narrow phase.
  [[nodiscard]] bool links_dynamic_bodies(const PairRecord& record) const;
  // Whether a record's body pair is unpaired (set_unpaired): it makes no contacts.
  [[nodiscard]] bool unpaired(const PairRecord& record) const;
  // An unpaired record is left with no contacts, and done for the step.
  static void drop_contacts(PairRecord& record);
  [[nodiscard]] Aabb broad_phase_box(std::uint32_t slot) const;
  [[nodiscard]] float pair_margin(const Body& a, const Body& b) const;
  [[nodiscard]] float plane_margin(const Body& body) const;
  [[nodiscard]] float descent_gap(float margin) const;
  // This detection's jobs_ (narrow_jobs.cpp): the candidate pairs with a moving body, then the
  // moving bodies against the ground plane, each in order; every record and body marked undone,
  // and the records of the others kept asleep.
  void list_jobs();
  // Where a run's items go in jobs_ and newly_resting_, or how many it lists (list_in_runs()).
  struct RunLists {
    std::uint32_t jobs = 0;
    std::uint32_t newly_resting = 0;
  };
  template <class Moving, class Resting, class RecordOf>
  std::size_t list_in_runs(const Parallel& parallel, std::size_t count, bool plane, RunLists first,
                           const Moving& moving, const Resting& resting, const RecordOf& record);
  // The narrow phase and contacts of jobs_, placed in the cache's contacts from `base` on.
  void run_jobs(std::size_t base);
  void plan_chunks();
  void narrow_phase(NarrowChunk& chunk, std::chrono::steady_clock::time_point start);
  void pair_leaves(const Job& job, NarrowChunk& chunk, std::chrono::steady_clock::time_point start);
  void kept_leaves(const PairRecord& record, std::uint32_t body_a, std::uint32_t body_b,
                   NarrowChunk& chunk) const;
  void ground_plane_leaves(std::uint32_t body, float reach_down, NarrowChunk& chunk) const;
  void make_contacts(NarrowChunk& chunk) const;
  void reused_contacts(const PairRecord& record, const Quat& rotation_a, NarrowChunk& chunk) const;
  void place_contacts(NarrowChunk& chunk);
  [[nodiscard]] DescentSettings descent_budget(double spent_microseconds, std::uint64_t spent_tests,
                                               float margin) const;

  DetectorSettings settings_;
  BodyStore* store_ = nullptr;  // read only, but for attaching the detector's arrays
  std::vector<Body> bodies_;    // per slot of the store
  std::vector<std::uint32_t> body_of_proxy_;
  std::variant<SweepAndPrune, CellSweepAndPrune> broad_phase_;
  bool crowd_ = false;  // the broad phase's last update found a crowd
  PairCache cache_;
  std::vector<Job> jobs_;
  std::size_t pair_jobs_ = 0;                 // jobs_'s pairs, which come before its bodies
  std::vector<std::uint32_t> newly_resting_;  // list_jobs()'s records that only now rest
  std::vector<RunLists> run_lists_;           // list_in_runs()'s scratch, per run
  std::vector<std::unique_ptr<NarrowChunk>> pair_chunks_;
  std::vector<std::unique_ptr<NarrowChunk>> plane_chunks_;
  std::vector<NarrowChunk*> chunks_;  // the planned runs, in order
  const Parallel* parallel_ = nullptr;
  CollisionStats stats_;
  std::vector<std::uint64_t> unpaired_;  // set_unpaired's pairs as sorted keys of their proxies
};

}  // namespace sphys
