#pragma once

// Starting covers for the Tight method's search at the first level, unlike the reductions' in
// structure: which part of the surface each ball answers for comes from the points' positions
// alone, not from the medial axis, so the outside-volume descent starts in other basins.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "ball.h"
#include "exterior_lattice.h"

namespace sphys::tools::build {

// k-means of the points into `count` clusters (k-means++ seeding from `seed`, then Lloyd's
// rounds), each cluster's smallest enclosing ball.
[[nodiscard]] std::vector<Ball> clustered_start(std::span<const Vec3d> points, std::size_t count,
                                                std::uint64_t seed);

// k-means into `over` times `count` clusters, then merged pair by pair down to `count`: each
// time the pair whose merged ball adds the fewest outside lattice points among those whose
// merged ball stays within `limit` (unit: m, at `directions`), or when none does, the pair whose
// merged ball reaches out least. Small clusters merged under the limit keep thin parts (ears,
// legs) in balls of their own, which one round of k-means often joins to their neighbours.
[[nodiscard]] std::vector<Ball> merged_start(std::span<const Vec3d> points, std::size_t count,
                                             std::size_t over, const ExteriorLattice& lattice,
                                             std::span<const Vec3d> directions, double limit,
                                             std::uint64_t seed);

// The points cut into slabs of equal width along their principal axes, one start per way of
// writing `count` as a × b × c with the most cuts along the longest axis (a ≥ b, a ≥ c): 8 gives
// 8×1×1, 4×2×1, 4×1×2 and 2×2×2. What suits plates, boxes and rods, whose best covers are
// tilings. Empty slabs give no ball.
[[nodiscard]] std::vector<std::vector<Ball>> slab_starts(std::span<const Vec3d> points,
                                                         std::size_t count);

}  // namespace sphys::tools::build
