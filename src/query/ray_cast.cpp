// Ray casts against the leaf spheres: the hierarchy's boxes nearest first, each group's spheres
// with the exact ray-sphere entry.

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "query/body_filter.h"
#include "query/bvh_walk.h"
#include "query/checked_input.h"
#include "query/snapshot.h"
#include "sphys/error.h"
#include "sphys/world_query.h"

namespace sphys {
namespace {

using query_detail::BodyFilter;
using query_detail::LeafGroup;
using query_detail::Snapshot;

// A ray with a unit direction.
struct UnitRay {
  Vec3 origin;
  Vec3 direction;
  float max_distance;
};

UnitRay checked(const Ray& ray) {
  query_detail::check_finite(ray.origin, "ray.origin");
  query_detail::check_finite(ray.direction, "ray.direction");
  const float length = ray.direction.norm();
  if (!(length > 0.0f) || !std::isfinite(length)) {
    throw Error("ray.direction: zero length (a ray needs a direction)");
  }
  if (!(ray.max_distance > 0.0f)) {
    throw Error("ray.max_distance: must be > 0 (m), not " + std::to_string(ray.max_distance));
  }
  return {ray.origin, ray.direction / length, ray.max_distance};
}

// How far along a unit ray it enters a sphere: 0 from inside, negative for a miss. The chord's
// half length comes from the centre's distance to the line (not from b² - c, which loses the
// digits of a sphere far along the ray). unit: m
float ray_entry(const UnitRay& ray, const Vec3& centre, float radius) {
  const Vec3 offset = ray.origin - centre;
  const float radius_squared = radius * radius;
  if (offset.squaredNorm() <= radius_squared) return 0.0f;
  const float along = offset.dot(ray.direction);
  if (along >= 0.0f) return -1.0f;  // outside and heading away
  const float chord_squared = radius_squared - (offset - along * ray.direction).squaredNorm();
  if (chord_squared < 0.0f) return -1.0f;
  return -along - std::sqrt(chord_squared);
}

// A hit before it is named: the body's slot and the sphere's index in the snapshot's lanes.
struct LaneHit {
  std::uint32_t body = 0;
  std::uint32_t sphere = 0;
  float distance = 0.0f;
};

// Calls hit(LaneHit) for every sphere of the group the ray enters within `limit`.
template <class Hit>
void cast_group(const Snapshot& snapshot, const LeafGroup& group, const UnitRay& ray, float limit,
                const Hit& hit) {
  for (std::uint32_t i = group.first; i < group.first + group.count; ++i) {
    const Vec3 centre(snapshot.x[i], snapshot.y[i], snapshot.z[i]);
    const float entry = ray_entry(ray, centre, snapshot.radius[i]);
    if (entry >= 0.0f && entry <= limit) hit(LaneHit{group.body, i, entry});
  }
}

std::optional<LaneHit> nearest(const Snapshot& snapshot, const BodyFilter& filter,
                               const UnitRay& ray) {
  std::optional<LaneHit> best;
  float limit = ray.max_distance;
  query_detail::walk_ray(snapshot, ray.origin, ray.direction, limit, [&](const LeafGroup& group) {
    if (!filter.sees(group.body)) return;
    cast_group(snapshot, group, ray, limit, [&](const LaneHit& hit) {
      // Equal distances go to the lower slot, then the lower sphere: the answer does not depend
      // on the hierarchy's order.
      if (!best || hit.distance < best->distance ||
          (hit.distance == best->distance &&
           std::tie(hit.body, hit.sphere) < std::tie(best->body, best->sphere))) {
        best = hit;
        limit = hit.distance;
      }
    });
  });
  return best;
}

RayHit named(const Snapshot& snapshot, const UnitRay& ray, const LaneHit& hit) {
  RayHit out;
  out.body = snapshot.ids[hit.body];
  out.leaf = snapshot.node[hit.sphere];
  out.distance = hit.distance;
  out.point = ray.origin + hit.distance * ray.direction;
  const Vec3 centre(snapshot.x[hit.sphere], snapshot.y[hit.sphere], snapshot.z[hit.sphere]);
  const Vec3 outward = out.point - centre;
  // From inside (distance 0) the surface is not where the ray is: the normal faces the ray.
  out.normal = hit.distance > 0.0f && outward.squaredNorm() > 0.0f ? Vec3(outward.normalized())
                                                                   : Vec3(-ray.direction);
  return out;
}

}  // namespace

std::optional<RayHit> WorldQuery::cast_ray(const Ray& ray, const QueryFilter& filter) const {
  const UnitRay unit = checked(ray);
  const BodyFilter seen(*snapshot_, filter);
  const std::optional<LaneHit> hit = nearest(*snapshot_, seen, unit);
  if (!hit) return std::nullopt;
  return named(*snapshot_, unit, *hit);
}

std::vector<RayHit> WorldQuery::cast_ray_all(const Ray& ray, const QueryFilter& filter) const {
  const UnitRay unit = checked(ray);
  const BodyFilter seen(*snapshot_, filter);
  std::vector<LaneHit> per_body;  // each body's nearest hit
  float limit = unit.max_distance;
  query_detail::walk_ray(
      *snapshot_, unit.origin, unit.direction, limit, [&](const LeafGroup& group) {
        if (!seen.sees(group.body)) return;
        cast_group(*snapshot_, group, unit, limit, [&](const LaneHit& hit) {
          const auto same = std::ranges::find(per_body, hit.body, &LaneHit::body);
          if (same == per_body.end()) {
            per_body.push_back(hit);
          } else if (std::tie(hit.distance, hit.sphere) < std::tie(same->distance, same->sphere)) {
            *same = hit;
          }
        });
      });
  std::ranges::sort(per_body, [](const LaneHit& a, const LaneHit& b) {
    return std::tie(a.distance, a.body) < std::tie(b.distance, b.body);
  });
  std::vector<RayHit> out;
  out.reserve(per_body.size());
  for (const LaneHit& hit : per_body) out.push_back(named(*snapshot_, unit, hit));
  return out;
}

void WorldQuery::cast_rays(std::span<const Ray> rays, const QueryFilter& filter,
                           std::span<std::optional<RayHit>> hits, const Parallel* parallel) const {
  if (hits.size() != rays.size()) {
    throw Error("hits: " + std::to_string(hits.size()) + " entries for " +
                std::to_string(rays.size()) + " rays");
  }
  std::vector<UnitRay> units;
  units.reserve(rays.size());
  for (const Ray& ray : rays) units.push_back(checked(ray));
  const BodyFilter seen(*snapshot_, filter);
  // Runs of rays per task: one ray is too little work to hand to a thread. unit: rays
  constexpr std::size_t kRaysPerRun = 64;
  for_each_on(parallel, (rays.size() + kRaysPerRun - 1) / kRaysPerRun, [&](std::size_t run) {
    const std::size_t end = std::min(rays.size(), (run + 1) * kRaysPerRun);
    for (std::size_t i = run * kRaysPerRun; i < end; ++i) {
      const std::optional<LaneHit> hit = nearest(*snapshot_, seen, units[i]);
      hits[i] = hit ? std::optional(named(*snapshot_, units[i], *hit)) : std::nullopt;
    }
  });
}

}  // namespace sphys
