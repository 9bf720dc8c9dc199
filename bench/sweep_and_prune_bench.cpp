// Broad phase: one step of Sweep & Prune against brute force, on boxes filling a cube.
// Run: sphys-bench --benchmark_filter=BroadPhase

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "sphys/math.h"
#include "sphys/sweep_and_prune.h"

namespace {

using sphys::Aabb;
using sphys::Vec3;

// Boxes about 1 m wide on a jittered 1 m lattice filling a cube, so that each overlaps a few
// neighbours, each drifting at a constant velocity and bouncing off the cube's walls.
constexpr float kSpacing = 1.0f;      // unit: m
constexpr float kJitter = 0.2f;       // largest offset from the lattice point. unit: m
constexpr float kMinHalf = 0.4f;      // unit: m
constexpr float kMaxHalf = 0.6f;      // unit: m
constexpr float kStepLength = 0.02f;  // distance moved per step: 1.2 m/s at 60 Hz. unit: m

struct Scene {
  std::vector<Vec3> centers;
  std::vector<Vec3> halves;
  std::vector<Vec3> steps;
  float side = 0.0f;  // unit: m

  explicit Scene(int count) {
    const int per_axis = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(count))));
    side = static_cast<float>(per_axis) * kSpacing;
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> jitter(-kJitter, kJitter);
    std::uniform_real_distribution<float> half(kMinHalf, kMaxHalf);
    std::normal_distribution<float> direction(0.0f, 1.0f);
    for (int i = 0; i < count; ++i) {
      const Vec3 lattice(static_cast<float>(i % per_axis),
                         static_cast<float>(i / per_axis % per_axis),
                         static_cast<float>(i / per_axis / per_axis));
      centers.push_back((lattice.array() + 0.5f) * kSpacing +
                        Vec3(jitter(rng), jitter(rng), jitter(rng)).array());
      halves.emplace_back(half(rng), half(rng), half(rng));
      steps.push_back(Vec3(direction(rng), direction(rng), direction(rng)).normalized() *
                      kStepLength);
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
void BM_BroadPhaseSweepAndPrune(benchmark::State& state) {
  Scene scene(static_cast<int>(state.range(0)));
  sphys::SweepAndPrune sap;
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
BENCHMARK(BM_BroadPhaseSweepAndPrune)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMicrosecond);

// The same step by testing every pair of boxes. 100k boxes (5e9 tests, seconds a step) is left
// out.
void BM_BroadPhaseBruteForce(benchmark::State& state) {
  Scene scene(static_cast<int>(state.range(0)));
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
