// Parallel's staged loops: every item of every stage runs exactly once, and each stage sees all
// that the stages before it wrote, on one thread and on several (more threads than cores too).

#include "sphys/parallel.h"

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

}  // namespace
}  // namespace sphys
