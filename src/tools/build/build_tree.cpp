#include "sphys/tools/build_tree.h"

#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "coverage.h"
#include "octree.h"
#include "reducer.h"
#include "sphys/error.h"
#include "surface_samples.h"

namespace sphys::tools {
namespace {

using build::Ball;
using build::BallNode;

constexpr int kMaxDepth = 6;

void validate(const TriangleMesh& mesh, const BuildOptions& options) {
  if (mesh.triangles.empty()) throw Error::in_file(mesh.name, "the mesh has no triangles");
  if (options.branching < 2 || options.branching > 8) {
    throw Error("branching factor " + std::to_string(options.branching) + " is outside 2..8");
  }
  if (options.depth < 1 || options.depth > kMaxDepth) {
    throw Error("depth " + std::to_string(options.depth) + " is outside 1.." +
                std::to_string(kMaxDepth) + " (levels including the root)");
  }
  if (options.method == BuildMethod::Octree && options.branching != 8) {
    throw Error("the octree method splits every cell in 8: use --branching 8");
  }
}

// Top-down construction for the point-set methods: each node's children cover the samples the
// node answers for.
std::vector<BallNode> build_top_down(const build::BuildContext& context, BuildMethod method,
                                     const BuildOptions& options) {
  const std::unique_ptr<build::Reducer> reducer = build::make_reducer(method, context);
  std::vector<std::uint32_t> all(context.samples.points.size());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  build::Cover root = reducer->cover(all, 1);

  std::vector<BallNode> nodes{{root.balls.front(), -1}};
  std::vector<std::vector<std::uint32_t>> regions{std::move(root.samples.front())};
  for (int level = 1; level < options.depth; ++level) {
    const std::size_t level_start = nodes.size() - regions.size();
    std::vector<std::vector<std::uint32_t>> next;
    for (std::size_t i = 0; i < regions.size(); ++i) {
      if (regions[i].size() > 1) {
        build::Cover cover = reducer->cover(regions[i], options.branching);
        for (std::size_t c = 0; c < cover.balls.size(); ++c) {
          nodes.push_back({cover.balls[c], static_cast<std::int32_t>(level_start + i)});
          next.push_back(std::move(cover.samples[c]));
        }
      }
      if (options.progress) {
        options.progress(
            (level - 1 + static_cast<double>(i + 1) / static_cast<double>(regions.size())) /
            (options.depth - 1));
      }
    }
    regions = std::move(next);
  }
  return nodes;
}

}  // namespace

SphereTree build_sphere_tree(const TriangleMesh& mesh, const BuildOptions& options) {
  validate(mesh, options);
  const MeshQuery query(mesh);
  std::vector<BallNode> nodes;
  if (options.method == BuildMethod::Octree) {
    nodes = build::build_octree(query, options.depth, options.progress);
  } else {
    const build::SurfaceSamples samples = build::sample_surface(mesh, build::kBuildSurfaceSamples);
    const build::BuildContext context{mesh, query, samples, options.seed};
    nodes = build_top_down(context, options.method, options);
  }

  // Certify every level against the real surface. Nodes are breadth-first, so each level is a
  // contiguous range.
  std::vector<int> level(nodes.size(), 0);
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    level[i] = level[static_cast<std::size_t>(nodes[i].parent)] + 1;
  }
  std::vector<SphereTreeNode> packed(nodes.size());
  for (std::size_t begin = 0, end = 0; begin < nodes.size(); begin = end) {
    end = begin;
    std::vector<Ball> balls;
    for (; end < nodes.size() && level[end] == level[begin]; ++end)
      balls.push_back(nodes[end].ball);
    const std::vector<Sphere> spheres = build::certified_spheres(std::move(balls), mesh);
    for (std::size_t i = begin; i < end; ++i) packed[i] = {spheres[i - begin], nodes[i].parent};
  }
  return SphereTree::from_nodes(packed, options.branching);
}

}  // namespace sphys::tools
