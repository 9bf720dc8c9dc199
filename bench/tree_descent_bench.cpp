#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <benchmark/benchmark.h>

#include "collision/tree_descent.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/model.h"

namespace {

using namespace sphys;

// The default bunny's Combined tree at depth 3, as in the paper; built once (about 2 s).
const SphereTree& bunny_tree() {
  static const SphereTree tree = [] {
    tools::BuildOptions options;
    options.method = tools::BuildMethod::Combined;
    options.depth = 3;
    return tools::build_sphere_tree(tools::load_model("bunny"), options);
  }();
  return tree;
}

// Body b relative to body a (at the identity): a shift along x, in root radii, and a turn about y.
struct RelativePose {
  float shift;    // unit: root radii
  float degrees;  // unit: degrees
};
constexpr RelativePose kPoses[] = {{0.25f, 30.0f}, {0.7f, 90.0f}, {1.2f, 180.0f}};

// Exact descent of two overlapping bunnies; arguments: the depth used (2 or 3) and the pose.
void descend_two_bunnies(benchmark::State& state) {
  const SphereTree& tree = bunny_tree();
  const RelativePose relative = kPoses[state.range(1)];
  Transform pose_b;
  pose_b.rotation =
      Quat(Eigen::AngleAxisf(relative.degrees * std::numbers::pi_v<float> / 180.0f, Vec3::UnitY()));
  pose_b.translation = Vec3(relative.shift * tree.root().radius, 0, 0);
  DescentSettings settings;
  settings.depth_a = static_cast<int>(state.range(0));
  settings.depth_b = settings.depth_a;

  TreeDescent descent;
  std::vector<NodePair> pairs;
  DescentStats stats;
  for (auto _ : state) {
    pairs.clear();
    stats = descent.descend(tree, Transform{}, tree, pose_b, settings, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["leaf_pairs"] = stats.leaf_pairs;
  state.counters["sphere_tests"] = static_cast<double>(stats.sphere_tests);
  // Seconds per leaf pair (shown with an SI prefix, "n" for ns).
  state.counters["time_per_leaf_pair"] =
      benchmark::Counter(stats.leaf_pairs, benchmark::Counter::kIsIterationInvariantRate |
                                               benchmark::Counter::kInvert);
}
BENCHMARK(descend_two_bunnies)->ArgNames({"depth", "pose"})->ArgsProduct({{2, 3}, {0, 1, 2}});

}  // namespace
