#include <filesystem>

#include <benchmark/benchmark.h>

#include "sphys/tools/check_mesh.h"
#include "sphys/tools/decimate.h"
#include "sphys/tools/load_mesh.h"
#include "sphys/tools/model.h"

namespace {

using namespace sphys::tools;

void BM_LoadBunny(benchmark::State& state) {
  if (!std::filesystem::exists(bunny_path())) {
    state.SkipWithError("the default model is not installed");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(load_mesh(bunny_path()));
}
BENCHMARK(BM_LoadBunny)->Unit(benchmark::kMillisecond);

void BM_DecimateBunny(benchmark::State& state) {
  if (!std::filesystem::exists(bunny_path())) {
    state.SkipWithError("the default model is not installed");
    return;
  }
  const TriangleMesh full = load_mesh(bunny_path());
  for (auto _ : state) {
    benchmark::DoNotOptimize(decimate(full, static_cast<std::size_t>(state.range(0))));
  }
}
BENCHMARK(BM_DecimateBunny)->Arg(2000)->Arg(500)->Unit(benchmark::kMillisecond);

void BM_CheckBunny(benchmark::State& state) {
  if (!std::filesystem::exists(bunny_path())) {
    state.SkipWithError("the default model is not installed");
    return;
  }
  const TriangleMesh full = load_mesh(bunny_path());
  for (auto _ : state) benchmark::DoNotOptimize(check_mesh(full));
}
BENCHMARK(BM_CheckBunny)->Unit(benchmark::kMillisecond);

}  // namespace
