#pragma once

// Whether a group's leaf spheres touch a shape, kLaneWidth spheres at a time. Closed tests:
// touching counts. The padding spheres lie too far away to touch anything a query may hold.

#include <cstdint>

#include "query/snapshot.h"

namespace sphys::query_detail {

// A sphere of the group within `radius` of `centre`: |c - centre| <= r + radius.
[[nodiscard]] inline bool group_touches_sphere(const Snapshot& snapshot, const LeafGroup& group,
                                               const Vec3& centre, float radius) {
  const Lanes cx = Lanes::splat(centre.x());
  const Lanes cy = Lanes::splat(centre.y());
  const Lanes cz = Lanes::splat(centre.z());
  const Lanes r = Lanes::splat(radius);
  for (std::uint32_t i = group.first; i < group.first + group.padded(); i += kLaneWidth) {
    const Lanes dx = Lanes::load(&snapshot.x[i]) - cx;
    const Lanes dy = Lanes::load(&snapshot.y[i]) - cy;
    const Lanes dz = Lanes::load(&snapshot.z[i]) - cz;
    const Lanes reach = Lanes::load(&snapshot.radius[i]) + r;
    if (any(dx * dx + dy * dy + dz * dz <= reach * reach)) return true;
  }
  return false;
}

// The squared distance from each lane's point to the box [low, high] per axis.
[[nodiscard]] inline Lanes squared_distance_to_box(const Lanes& x, const Lanes& y, const Lanes& z,
                                                   const Vec3& low, const Vec3& high) {
  const Lanes zero = Lanes::splat(0.0f);
  const auto outside = [&](const Lanes& v, float lo, float hi) {
    return max(max(Lanes::splat(lo) - v, v - Lanes::splat(hi)), zero);
  };
  const Lanes ox = outside(x, low.x(), high.x());
  const Lanes oy = outside(y, low.y(), high.y());
  const Lanes oz = outside(z, low.z(), high.z());
  return ox * ox + oy * oy + oz * oz;
}

// A sphere of the group that touches the axis-aligned box.
[[nodiscard]] inline bool group_touches_aabb(const Snapshot& snapshot, const LeafGroup& group,
                                             const Aabb& box) {
  for (std::uint32_t i = group.first; i < group.first + group.padded(); i += kLaneWidth) {
    const Lanes r = Lanes::load(&snapshot.radius[i]);
    const Lanes d2 =
        squared_distance_to_box(Lanes::load(&snapshot.x[i]), Lanes::load(&snapshot.y[i]),
                                Lanes::load(&snapshot.z[i]), box.min, box.max);
    if (any(d2 <= r * r)) return true;
  }
  return false;
}

// A sphere of the group that touches the box of half extents `half` placed by rotation
// `rotation` (columns: the box's axes) and centre `centre`: each centre is taken into the box's
// frame, then against the axis-aligned box.
[[nodiscard]] inline bool group_touches_oriented_box(const Snapshot& snapshot,
                                                     const LeafGroup& group, const Mat3& rotation,
                                                     const Vec3& centre, const Vec3& half) {
  const auto splat = [](float v) { return Lanes::splat(v); };
  for (std::uint32_t i = group.first; i < group.first + group.padded(); i += kLaneWidth) {
    const Lanes dx = Lanes::load(&snapshot.x[i]) - splat(centre.x());
    const Lanes dy = Lanes::load(&snapshot.y[i]) - splat(centre.y());
    const Lanes dz = Lanes::load(&snapshot.z[i]) - splat(centre.z());
    // Rᵀ (c - centre): the offset along each of the box's axes.
    const auto along = [&](int axis) {
      return dx * splat(rotation(0, axis)) + dy * splat(rotation(1, axis)) +
             dz * splat(rotation(2, axis));
    };
    const Lanes r = Lanes::load(&snapshot.radius[i]);
    const Lanes d2 = squared_distance_to_box(along(0), along(1), along(2), -half, half);
    if (any(d2 <= r * r)) return true;
  }
  return false;
}

}  // namespace sphys::query_detail
