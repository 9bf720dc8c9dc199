// Broad phase: one step of Sweep & Prune against brute force, on boxes filling a cube and on boxes
// spread over a floor.
// Run: sphys-bench --benchmark_filter=BroadPhase

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "collision/cell_sweep_and_prune.h"
#include "collision/sweep_and_prune.h"
#include "sphys/math.h"

namespace {

using sphys::Aabb;
using sphys::Vec3;

// Boxes about 1 m wide placed at random, each drifting at a constant velocity and bouncing off
// the walls: the regime drifting boxes settle into, so that every size is timed in the same one.
// Cube: one box per cubic metre filling a cube, moving in 3D. Floor: one box per 1.15 m square,
// every box standing on y = 0 and moving in x and z only, as bodies spread over the ground. Each
// box overlaps about 3 others on the floor and 7 in the cube.
enum class Layout { kCube, kFloor };
constexpr float kCubeSpacing = 1.0f;    // the cube's volume per box is its cube. unit: m
constexpr float kFloorSpacing = 1.15f;  // the floor's area per box is its square. unit: m
constexpr float kMinHalf = 0.4f;        // unit: m
constexpr float kMaxHalf = 0.6f;        // unit: m
constexpr float kStepLength = 0.02f;    // distance moved per step: 1.2 m/s at 60 Hz. unit: m

struct Scene {
  std::vector<Vec3> centers;
  std::vector<Vec3> halves;
  std::vector<Vec3> steps;
  float side = 0.0f;  // unit: m

  Scene(Layout layout, int count) {
    const bool floor = layout == Layout::kFloor;
    const auto n = static_cast<double>(count);
    side = floor ? static_cast<float>(std::sqrt(n)) * kFloorSpacing
                 : static_cast<float>(std::cbrt(n)) * kCubeSpacing;
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> place(0.0f, side);
    std::uniform_real_distribution<float> half(kMinHalf, kMaxHalf);
    std::normal_distribution<float> direction(0.0f, 1.0f);
    for (int i = 0; i < count; ++i) {
      const Vec3 half_size(half(rng), half(rng), half(rng));
      halves.push_back(half_size);
      if (floor) {
        centers.emplace_back(place(rng), half_size.y(), place(rng));
        steps.push_back(Vec3(direction(rng), 0.0f, direction(rng)).normalized() * kStepLength);
      } else {
        centers.emplace_back(place(rng), place(rng), place(rng));
        steps.push_back(Vec3(direction(rng), direction(rng), direction(rng)).normalized() *
                        kStepLength);
      }
    }
  }

  [[nodiscard]] std::size_t size() const { return centers.size(); }
  [[nodiscard]] Aabb box(std::size_t i) const {
    return {centers[i] - halves[i], centers[i] + halves[i]};
  }
  void advance() {
    for (std::size_t i = 0; i < size(); ++i) {
      centers[i] += steps[i];
      for (int axis = 0; axis < 3; ++axis) {
        if (centers[i][axis] < 0.0f || centers[i][axis] > side) steps[i][axis] = -steps[i][axis];
      }
    }
  }
};

void set_counters(benchmark::State& state, std::size_t boxes) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(boxes));
  // Seconds per box and step; shown with an SI prefix (n = ns).
  state.counters["time_per_box"] =
      benchmark::Counter(static_cast<double>(boxes), benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}

// One step: every box moves (set_box) and update() re-sorts and updates the pairs.
template <class BroadPhase, Layout kLayout>
void BM_BroadPhase(benchmark::State& state) {
  Scene scene(kLayout, static_cast<int>(state.range(0)));
  BroadPhase sap;
  for (std::size_t i = 0; i < scene.size(); ++i) sap.add(scene.box(i), sphys::ProxyKind::kDynamic);
  sap.update();
  // Warm up to steady state: the buffers at their size, the scene in its bouncing regime.
  for (int step = 0; step < 10; ++step) {
    scene.advance();
    for (std::size_t i = 0; i < scene.size(); ++i) {
      sap.set_box(static_cast<sphys::ProxyId>(i), scene.box(i));
    }
    sap.update();
  }

  std::uint64_t swaps = 0;
  std::uint64_t pairs = 0;
  for (auto _ : state) {
    scene.advance();
    for (std::size_t i = 0; i < scene.size(); ++i) {
      sap.set_box(static_cast<sphys::ProxyId>(i), scene.box(i));
    }
    sap.update();
    swaps += sap.swaps_last_update();
    pairs += sap.pairs().size();
  }
  set_counters(state, scene.size());
  const double box_steps =
      static_cast<double>(state.iterations()) * static_cast<double>(scene.size());
  state.counters["swaps_per_box"] = static_cast<double>(swaps) / box_steps;
  state.counters["pairs_per_box"] = static_cast<double>(pairs) / box_steps;
}
// Each broad phase on each layout at 1,000, 10,000 and 100,000 boxes.
#define SPHYS_BROAD_PHASE_BENCHMARK(name, type, layout) \
  BENCHMARK(BM_BroadPhase<type, layout>)                \
      ->Name(name)                                      \
      ->Arg(1000)                                       \
      ->Arg(10000)                                      \
      ->Arg(100000)                                     \
      ->Unit(benchmark::kMicrosecond)
SPHYS_BROAD_PHASE_BENCHMARK("BM_BroadPhaseSweepAndPrune/cube", sphys::SweepAndPrune, Layout::kCube);
SPHYS_BROAD_PHASE_BENCHMARK("BM_BroadPhaseSweepAndPrune/floor", sphys::SweepAndPrune,
                            Layout::kFloor);
SPHYS_BROAD_PHASE_BENCHMARK("BM_BroadPhaseCellSweepAndPrune/cube", sphys::CellSweepAndPrune,
                            Layout::kCube);
SPHYS_BROAD_PHASE_BENCHMARK("BM_BroadPhaseCellSweepAndPrune/floor", sphys::CellSweepAndPrune,
                            Layout::kFloor);

// The same step by testing every pair of boxes. 100k boxes (5e9 tests, seconds a step) is left
// out.
void BM_BroadPhaseBruteForce(benchmark::State& state) {
  Scene scene(Layout::kCube, static_cast<int>(state.range(0)));
  std::vector<Aabb> boxes(scene.size());
  std::vector<sphys::ProxyPair> pairs;
  for (auto _ : state) {
    scene.advance();
    for (std::size_t i = 0; i < scene.size(); ++i) boxes[i] = scene.box(i);
    pairs.clear();
    for (std::size_t a = 0; a < boxes.size(); ++a) {
      for (std::size_t b = a + 1; b < boxes.size(); ++b) {
        if (boxes[a].overlaps(boxes[b])) {
          pairs.push_back({static_cast<sphys::ProxyId>(a), static_cast<sphys::ProxyId>(b)});
        }
      }
    }
    benchmark::DoNotOptimize(pairs.data());
  }
  set_counters(state, scene.size());
}
BENCHMARK(BM_BroadPhaseBruteForce)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

}  // namespace
