// Parallel's staged loops: every item of every stage runs exactly once, and each stage sees all
// that the stages before it wrote, on one thread and on several (more threads than cores too);
// and the time its loops take, which the step's serial time leaves out.

#include "sphys/parallel.h"

#include <chrono>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace sphys {
namespace {

// Stage s writes item i of row s as one more than the sum of row s - 1, which every item of
// stage s reads whole: any item run before the stage before it had finished sees a short sum.
TEST(Parallel, StagesRunInOrderAndEachItemOnce) {
  // Stages of varied sizes, empty ones among them.
  const std::vector<std::uint32_t> counts = {5, 0, 1, 37, 200, 0, 3, 64, 1, 129};
  for (const std::uint32_t threads : {1u, 2u, 4u}) {
    SCOPED_TRACE(threads);
    const Parallel parallel(threads);
    for (int repeat = 0; repeat < 200; ++repeat) {
      std::vector<std::vector<std::uint64_t>> rows(counts.size());
      std::vector<std::vector<int>> runs(counts.size());
      for (std::size_t s = 0; s < counts.size(); ++s) {
        rows[s].assign(counts[s], 0);
        runs[s].assign(counts[s], 0);
      }
      parallel.for_each_in_stages(counts, [&](std::size_t stage, std::uint32_t i) {
        // The nearest earlier stage with items, summed a few times over: items long enough that
        // the threads overlap.
        std::uint64_t below = 0;
        for (std::size_t s = stage; s-- > 0;) {
          if (counts[s] == 0) continue;
          for (int again = 0; again < 8; ++again) {
            below = 0;
            for (const std::uint64_t v : rows[s])
              below += *static_cast<const volatile std::uint64_t*>(&v);
          }
          break;
        }
        rows[stage][i] = below + 1;
        ++runs[stage][i];
      });
      std::uint64_t below = 0;
      for (std::size_t s = 0; s < counts.size(); ++s) {
        if (counts[s] == 0) continue;
        std::uint64_t sum = 0;
        for (std::uint32_t i = 0; i < counts[s]; ++i) {
          EXPECT_EQ(rows[s][i], below + 1) << "stage " << s << " item " << i;
          EXPECT_EQ(runs[s][i], 1) << "stage " << s << " item " << i;
          sum += rows[s][i];
        }
        below = sum;
      }
    }
  }
}

// Spins for about `ms` of wall-clock time, so that a loop's time is known to be at least that.
void spend(double ms) {
  const auto until =
      std::chrono::steady_clock::now() + std::chrono::duration<double, std::milli>(ms);
  while (std::chrono::steady_clock::now() < until) {
  }
}

// loop_ms() times the loops threads share, on one thread as on several: a loop of two items or
// more, once even when another runs inside it, and a loop's one pass where more threads would
// share it; not one item alone, nor two jobs side by side.
TEST(Parallel, LoopTimeCountsTheSharedLoopsOnce) {
  for (const std::uint32_t threads : {1u, 2u}) {
    SCOPED_TRACE(threads);
    const Parallel parallel(threads);
    EXPECT_EQ(parallel.loop_ms(), 0.0);
    parallel.for_each(1, [](std::size_t) { spend(2.0); });
    parallel.side_by_side([] { spend(2.0); }, [] { spend(2.0); });
    parallel.as_one_run([] { spend(2.0); }, false);
    EXPECT_EQ(parallel.loop_ms(), 0.0);
    parallel.as_one_run([] { spend(2.0); }, true);
    EXPECT_GE(parallel.loop_ms(), 2.0);

    const double before_nested = parallel.loop_ms();
    const auto start = std::chrono::steady_clock::now();
    parallel.for_each(4,
                      [&](std::size_t) { parallel.for_each(2, [](std::size_t) { spend(1.0); }); });
    const double outer_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    // Eight spins of 1 ms: at least 8 ms on one thread, 4 on two; the nested loops are not added.
    EXPECT_GE(parallel.loop_ms() - before_nested, 8.0 / threads);
    EXPECT_LE(parallel.loop_ms() - before_nested, outer_ms);

    const double before = parallel.loop_ms();
    const std::vector<std::uint32_t> counts(3, 8);
    parallel.for_each_in_stages(counts, [](std::size_t, std::uint32_t) { spend(0.1); });
    EXPECT_GE(parallel.loop_ms() - before, 2.4 / threads);
  }
}

}  // namespace
}  // namespace sphys
