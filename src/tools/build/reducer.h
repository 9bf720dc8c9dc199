#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "ball.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/mesh_query.h"
#include "surface_samples.h"

namespace sphys::tools::build {

// What every reducer may look at: the mesh, fast queries against it, and the surface samples.
struct BuildContext {
  const TriangleMesh& mesh;
  const MeshQuery& query;
  const SurfaceSamples& samples;
  std::uint64_t seed = 1;
};

// A node's children: up to B balls, and for each the samples it answers for (a partition of the
// samples the parent answered for; each ball contains its samples).
struct Cover {
  std::vector<Ball> balls;
  std::vector<std::vector<std::uint32_t>> samples;
};

// One of the toolkit's reduction algorithms: covers a set of surface samples with at most
// `max_balls` balls, as tightly as it can. Top-down construction calls it once per node, with
// the samples the node answers for. Implementations must be deterministic for a given context.
class Reducer {
 public:
  virtual ~Reducer() = default;
  [[nodiscard]] virtual Cover cover(std::span<const std::uint32_t> samples, int max_balls) = 0;
};

// The reducer of a point-set method (every method but Octree, which subdivides space instead).
[[nodiscard]] std::unique_ptr<Reducer> make_reducer(BuildMethod method,
                                                    const BuildContext& context);

}  // namespace sphys::tools::build
