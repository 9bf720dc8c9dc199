#pragma once

#include <cstdint>
#include <vector>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools::build {

// Points spread over the whole surface: what the nodes of a sphere-tree must cover. Made by
// splitting every triangle evenly until its pieces have edges no longer than `spacing`; the
// points are the pieces' corners. Every surface point is within spacing/√3 of some sample.
// Long slivers are sampled in rows along their longest edge instead, so that a wire's sides cost
// samples in proportion to their area, not to the square of their length.
struct SurfaceSamples {
  std::vector<Vec3d> points;
  std::vector<std::uint32_t> triangle;  // the mesh triangle each point lies on
  double spacing = 0.0;                 // unit: m
};

// Surface samples the point-set builders cover: enough for the deepest level's regions to keep a
// few hundred each at branching 8, depth 3.
constexpr std::size_t kBuildSurfaceSamples = 20000;

// Chooses the spacing so that roughly `target_count` samples result (at least three per
// triangle).
[[nodiscard]] SurfaceSamples sample_surface(const TriangleMesh& mesh, std::size_t target_count);

}  // namespace sphys::tools::build
