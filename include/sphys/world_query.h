#pragma once

// Questions asked of a world without stepping it: ray casts, overlaps, distances, and the batched
// sphere checks of motion planners (sphys/configuration_check.h).
//
// Every answer comes from the bodies' leaf spheres (the nodes the narrow phase treats as leaves:
// CollisionSettings::tree_depth), exactly as a loop over all of them would give it. Since every
// level of a tree that sphys builds covers its mesh, "no hit", "no overlap" and a positive
// distance hold for the meshes too (docs/queries.md). The exact ground plane
// (CollisionSettings::ground_plane_height) is no body, and no query sees it.

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "sphys/math.h"
#include "sphys/parallel.h"
#include "sphys/sphere_tree.h"
#include "sphys/world.h"

namespace sphys {

// Which bodies a query sees: all of them but those the filter leaves out.
struct QueryFilter {
  // Bodies left out. Each must be in the world (else sphys::Error).
  std::vector<BodyId> skip;
  // A body is seen when its category bits share a bit with `mask`. `categories` holds the bits
  // per body slot (World::id_of); a body whose slot is past its end is in category 1.
  std::uint32_t mask = ~0u;
  std::vector<std::uint32_t> categories;  // category bits by body slot; missing slots: 1
  // Sleeping bodies are left out.
  bool skip_sleeping = false;
};

// A half-line from `origin` along `direction` (any length but zero), up to `max_distance` from
// the origin.
struct Ray {
  Vec3 origin = Vec3::Zero();                                   // unit: m
  Vec3 direction = Vec3::UnitX();                               // unit: any (normalised)
  float max_distance = std::numeric_limits<float>::infinity();  // unit: m, > 0
};

// Where a ray enters a body's leaf spheres. A ray that starts inside a leaf sphere hits it at
// distance 0, its normal against the ray.
struct RayHit {
  BodyId body;                  // the body hit
  std::uint32_t leaf = 0;       // the leaf sphere's node in the body's tree
  Vec3 point = Vec3::Zero();    // unit: m
  Vec3 normal = Vec3::UnitY();  // outward unit normal of the leaf sphere at `point`
  float distance = 0.0f;        // from the ray's origin along its unit direction. unit: m
};

// A box turned and placed by `pose`: the points pose.apply(p) with |p_i| <= half_extents_i.
struct OrientedBox {
  Transform pose;                            // the box's centre and axes in the world. unit: m
  Vec3 half_extents = Vec3::Constant(0.5f);  // unit: m, >= 0
};

// When a distance query may stop early (the paper's time-critical descent, §3.2); 0 turns a
// budget off, and with both off the answer is exact.
struct DistanceBudget {
  std::uint64_t max_sphere_tests = 0;  // unit: sphere tests
  double max_microseconds = 0.0;       // unit: µs of wall-clock time, >= 0
};

// The smallest gap between the leaf spheres of two bodies (or of a body and a point): the
// distance between the two closest spheres' surfaces, negative where they overlap (then minus
// the deepest overlap of a pair).
struct DistanceResult {
  float distance = std::numeric_limits<float>::infinity();  // unit: m
  // The closest pair: leaf nodes of body a's and body b's tree (leaf_b is 0 against a point) and
  // the nearest points of their spheres' surfaces (against a point, point_b is the point).
  std::uint32_t leaf_a = 0;
  std::uint32_t leaf_b = 0;     // 0 against a point
  Vec3 point_a = Vec3::Zero();  // unit: m
  Vec3 point_b = Vec3::Zero();  // unit: m
  // False when a budget stopped the descent: `distance` is then a lower bound of the leaf
  // spheres' gap (and of the meshes'), and the pair is the closest found so far.
  bool exact = true;
  std::uint64_t sphere_tests = 0;  // sphere tests the descent made. unit: sphere tests
};

namespace query_detail {
struct Snapshot;
}

// The world's bodies as they were when the query was made (or last refreshed): their ids, poses,
// trees and sleep. A query object made once answers many questions; after the world steps or
// changes, refresh() reads it again. Its const calls read that copy alone, never the world: they
// may run on many threads at once, and beside the world's steps and changes on other threads.
// Making or refreshing one reads the world, so it takes its turn (sphys/world.h): it throws
// sphys::Error while the world is being stepped or changed. The world must outlive it for
// refresh() alone.
class WorldQuery {
 public:
  // Reads the world's bodies now (see above for when that throws).
  explicit WorldQuery(const World& world);
  ~WorldQuery();
  // Takes the other's copy of the bodies; the moved-from query may only be destroyed or assigned
  // to.
  WorldQuery(WorldQuery&&) noexcept;
  // As the move constructor.
  WorldQuery& operator=(WorldQuery&&) noexcept;

  // Reads the world's bodies again; not beside this query's own calls on other threads.
  void refresh();
  // The world the query reads.
  [[nodiscard]] const World& world() const { return *world_; }

  // The nearest hit, if any. Throws sphys::Error naming `ray.origin`, `ray.direction` (zero or
  // not finite) or `ray.max_distance` (not positive, or NaN), or the filter's unknown body.
  [[nodiscard]] std::optional<RayHit> cast_ray(const Ray& ray,
                                               const QueryFilter& filter = {}) const;
  // Every body the ray hits, once each at its nearest hit, nearest first.
  [[nodiscard]] std::vector<RayHit> cast_ray_all(const Ray& ray,
                                                 const QueryFilter& filter = {}) const;
  // cast_ray for each ray, on `parallel`'s threads when given. `hits` has one entry per ray.
  void cast_rays(std::span<const Ray> rays, const QueryFilter& filter,
                 std::span<std::optional<RayHit>> hits, const Parallel* parallel = nullptr) const;

  // The bodies with a leaf sphere that overlaps the shape (touching counts), by increasing
  // slot. Throws sphys::Error for a negative or non-finite size or a non-finite place.
  [[nodiscard]] std::vector<BodyId> overlap_sphere(const Vec3& center, float radius,
                                                   const QueryFilter& filter = {}) const;
  // The same for a turned box.
  [[nodiscard]] std::vector<BodyId> overlap_box(const OrientedBox& box,
                                                const QueryFilter& filter = {}) const;
  // The same for an axis-aligned box.
  [[nodiscard]] std::vector<BodyId> overlap_aabb(const Aabb& box,
                                                 const QueryFilter& filter = {}) const;
  // Leaf spheres overlapping a leaf sphere of `tree` at `pose` (its leaves: the world's
  // tree_depth).
  [[nodiscard]] std::vector<BodyId> overlap_tree(const SphereTree& tree, const Transform& pose,
                                                 const QueryFilter& filter = {}) const;
  // A body's own tree at another pose; the body itself is left out.
  [[nodiscard]] std::vector<BodyId> overlap_body(BodyId body, const Transform& pose,
                                                 QueryFilter filter = {}) const;

  // The smallest gap between the leaf spheres of two bodies, or of a body and a point. Throws
  // sphys::Error naming an unknown body or a non-finite point.
  [[nodiscard]] DistanceResult distance(BodyId a, BodyId b,
                                        const DistanceBudget& budget = {}) const;
  // The same between a body and a world point (unit: m).
  [[nodiscard]] DistanceResult distance(BodyId body, const Vec3& point,
                                        const DistanceBudget& budget = {}) const;

  // What the queries read, private to the library (src/query/snapshot.h).
  [[nodiscard]] const query_detail::Snapshot& snapshot() const { return *snapshot_; }

 private:
  const World* world_;
  std::unique_ptr<query_detail::Snapshot> snapshot_;
};

}  // namespace sphys
