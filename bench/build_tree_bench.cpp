#include <string>

#include <benchmark/benchmark.h>

#include "sphys/tools/build_tree.h"
#include "sphys/tools/model.h"

namespace {

using namespace sphys::tools;

// Build time per method on the default bunny (2,000 triangles), branching 8; the argument is the
// depth (levels including the root).
void build_bunny_tree(benchmark::State& state, BuildMethod method) {
  const TriangleMesh bunny = load_model("bunny");
  BuildOptions options;
  options.method = method;
  options.depth = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(build_sphere_tree(bunny, options));
}

void register_all() {
  for (BuildMethod method : {BuildMethod::Octree, BuildMethod::Grid, BuildMethod::Spawn,
                             BuildMethod::Hubbard, BuildMethod::Merge, BuildMethod::Burst,
                             BuildMethod::Expand, BuildMethod::Combined, BuildMethod::Tight}) {
    benchmark::RegisterBenchmark(("build_bunny_tree/" + std::string(method_name(method))).c_str(),
                                 build_bunny_tree, method)
        ->Arg(2)
        ->Arg(3)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(3);
  }
}

const bool kRegistered = (register_all(), true);

}  // namespace
