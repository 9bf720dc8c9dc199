// Mass properties of a 20 480-triangle icosphere (5 subdivisions) by both methods, and the cost
// of one generalized winding number query against it.
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "sphys/tools/mass_properties.h"
#include "sphys/tools/primitives.h"
#include "sphys/tools/winding_number.h"

namespace {

using sphys::tools::MassPropertiesOptions;
using sphys::tools::TriangleMesh;
using sphys::tools::Vec3d;

const TriangleMesh& icosphere() {
  static const TriangleMesh mesh = sphys::tools::make_icosphere(1.0, 5);
  return mesh;
}

// The same sphere with three adjacent triangles missing: the winding-number method then has
// caps to evaluate, which is its general case.
const TriangleMesh& holed_icosphere() {
  static const TriangleMesh mesh = [] {
    TriangleMesh holed = icosphere();
    for (const std::size_t t : {3, 1, 0}) {
      holed.triangles.erase(holed.triangles.begin() + static_cast<std::ptrdiff_t>(t));
    }
    return holed;
  }();
  return mesh;
}

void mass_polyhedral(benchmark::State& state) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(sphys::tools::compute_mass_properties(icosphere()));
  }
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(icosphere().triangles.size()));
}
BENCHMARK(mass_polyhedral)->Unit(benchmark::kMillisecond);

void mass_winding_number(benchmark::State& state, const TriangleMesh& mesh) {
  MassPropertiesOptions options;
  options.force_winding_number = true;
  options.columns = static_cast<int>(state.range(0));
  for (auto _ : state) {
    benchmark::DoNotOptimize(sphys::tools::compute_mass_properties(mesh, options));
  }
}
BENCHMARK_CAPTURE(mass_winding_number, closed, icosphere())
    ->Arg(80)
    ->Arg(160)
    ->Arg(320)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(mass_winding_number, holed, holed_icosphere())
    ->Arg(80)
    ->Arg(160)
    ->Arg(320)
    ->Unit(benchmark::kMillisecond);

// Items are queries: items_per_second is winding-number queries per second.
void winding_number_query(benchmark::State& state) {
  std::mt19937 engine(7);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  std::vector<Vec3d> points(64);
  for (Vec3d& p : points) p = Vec3d(coordinate(engine), coordinate(engine), coordinate(engine));
  std::size_t next = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(sphys::tools::winding_number(icosphere(), points[next]));
    next = (next + 1) % points.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(winding_number_query)->Unit(benchmark::kMicrosecond);

}  // namespace
