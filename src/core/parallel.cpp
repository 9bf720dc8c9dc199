#include "sphys/parallel.h"

#include <algorithm>
#include <atomic>
#include <thread>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

namespace sphys {

struct Parallel::Arena {
  tbb::task_arena arena;
};

Parallel::Parallel(std::uint32_t threads)
    : threads_(threads == 0 ? static_cast<std::uint32_t>(tbb::info::default_concurrency())
                            : threads) {
  if (threads_ > 1)
    arena_ = std::make_unique<Arena>(Arena{tbb::task_arena(static_cast<int>(threads_))});
}

Parallel::~Parallel() = default;

const Parallel& threads_or_caller(const Parallel* parallel) {
  static const Parallel kCallersThread(1);
  return parallel != nullptr ? *parallel : kCallersThread;
}

void Parallel::run(std::size_t count, void (*item)(const void*, std::size_t),
                   const void* fn) const {
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) item(fn, i);
                      });
  });
}

namespace {

// Spins this many times (each a PAUSE) before yielding the processor: with more threads than
// cores a waiting thread must let the one it waits for run, but a yield is a system call that
// costs more than most stages of a solver pass take.
constexpr int kSpinsBeforeYield = 4096;

// A stage's items are claimed in runs of about 1 / (this many x the threads) of those left: few
// claims, yet a thread that comes late or runs slow still finds some left.
constexpr std::uint32_t kRunsPerThread = 2;

void wait_a_little(int& spins) {
  if (++spins < kSpinsBeforeYield) {
#if defined(__SSE2__)
    _mm_pause();  // tells the core this is a wait, which spares the other thread's resources
#endif
    return;
  }
  spins = 0;
  std::this_thread::yield();
}

// The shared state of a staged run. A thread claims item i of stage s by raising `claim` from
// (s, i) to (s, i + 1), so a thread still in an earlier stage can never take a later stage's
// item; `done` counts the current stage's finished items.
struct Stages {
  std::span<const std::uint32_t> counts;
  std::uint32_t threads = 1;
  void (*item)(const void*, std::size_t, std::uint32_t);
  const void* fn;
  // Each on a cache line of its own, so that claiming, finishing and watching do not slow each
  // other. unit: bytes
  alignas(64) std::atomic<std::uint64_t> claim{0};
  alignas(64) std::atomic<std::uint32_t> done{0};
  alignas(64) std::atomic<std::uint64_t> published{
      0};  // the current stage + 1; kFinished at the end

  static constexpr std::uint64_t kFinished = ~std::uint64_t{0};

  // Claims and runs the stage's items until none is left, a run of consecutive items at a time:
  // threads on neighbouring items write neighbouring memory, and a cache line written from two
  // threads by turns costs more than the items.
  void work(std::size_t stage) {
    const std::uint32_t count = counts[stage];
    std::uint64_t claimed = claim.load();
    while ((claimed >> 32) == stage && (claimed & 0xffffffffu) < count) {
      const auto first = static_cast<std::uint32_t>(claimed & 0xffffffffu);
      // Guided: a share of what is left, so that the runs shrink towards the stage's end and
      // the threads finish it together.
      const std::uint32_t run = std::max(1u, (count - first) / (kRunsPerThread * threads));
      const std::uint32_t end = std::min(count, first + run);
      if (!claim.compare_exchange_weak(claimed, claimed + (end - first))) continue;
      for (std::uint32_t i = first; i < end; ++i) item(fn, stage, i);
      done.fetch_add(end - first);
      claimed = claim.load();
    }
  }

  // Another thread: the items of each stage as it is published, until the run is finished.
  void help() {
    std::uint64_t seen = 0;
    int spins = 0;
    for (;;) {
      const std::uint64_t stage = published.load();
      if (stage == kFinished) return;
      if (stage == seen) {
        wait_a_little(spins);
        continue;
      }
      seen = stage;
      work(stage - 1);
    }
  }

  // The calling thread: publishes each stage, works on it and waits until every item is done.
  void drive() {
    for (std::size_t stage = 0; stage < counts.size(); ++stage) {
      if (counts[stage] == 0) continue;
      done.store(0);
      claim.store(std::uint64_t{stage} << 32);
      published.store(stage + 1);
      work(stage);
      int spins = 0;
      while (done.load() < counts[stage]) wait_a_little(spins);
    }
    published.store(kFinished);
  }
};

}  // namespace

// The helpers are tasks of the arena: one that never starts before the end is run by the calling
// thread's wait, finds the run finished and returns, so nothing waits on a thread that is not
// there.
void Parallel::run_stages(std::span<const std::uint32_t> counts,
                          void (*item)(const void*, std::size_t, std::uint32_t),
                          const void* fn) const {
  Stages stages{.counts = counts, .threads = threads_, .item = item, .fn = fn};
  arena_->arena.execute([&] {
    tbb::task_group helpers;
    for (std::uint32_t t = 1; t < threads_; ++t) helpers.run([&] { stages.help(); });
    stages.drive();
    helpers.wait();
  });
}

}  // namespace sphys
