#pragma once

// The threads a world steps with: loops over independent items on up to N threads of oneTBB.
// Each item writes only its own outputs, so what a loop computes does not depend on how many
// threads ran it, nor on which thread took which item.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

namespace sphys {

// Runs a world's loops on its threads (the top of this file says what a loop may do).
class Parallel {
 public:
  // `threads`: at most this many threads run a loop; 0 takes every hardware thread; 1 runs the
  // loops on the caller's thread without oneTBB.
  explicit Parallel(std::uint32_t threads = 1);
  ~Parallel();
  Parallel(const Parallel&) = delete;
  Parallel& operator=(const Parallel&) = delete;

  // How many threads run a loop: the number asked for, or the hardware's for 0.
  [[nodiscard]] std::uint32_t threads() const { return threads_; }

  // Wall-clock time spent in the loops that threads share, since this was made: every for_each
  // of two items or more and every for_each_in_stages that runs on the threads, timed on one
  // thread too (their items are what more threads would share). A loop inside another counts
  // once. What a step spends outside them is its serial time, which more threads do not
  // shorten (StepStats::serial_ms). unit: ms
  [[nodiscard]] double loop_ms() const {
    return 1e-6 * static_cast<double>(loop_ns_.load(std::memory_order_relaxed));
  }

  // Calls fn(i) for every i in [0, count), in any order and concurrently when there are threads;
  // in order on the caller's thread when there is one. fn must not touch what another item
  // writes.
  template <class Fn>
  void for_each(std::size_t count, const Fn& fn) const {
    if (count < 2) {
      if (count == 1) fn(0);
      return;
    }
    const LoopClock clock(*this);
    if (!arena_) {
      for (std::size_t i = 0; i < count; ++i) fn(i);
      return;
    }
    run(
        count, [](const void* f, std::size_t i) { (*static_cast<const Fn*>(f))(i); }, &fn);
  }

  // Calls fn(begin, end) for runs of at most `run` consecutive indices that together cover
  // [0, count), as for_each does its items: for loops whose items are too small to hand out one
  // by one.
  template <class Fn>
  void for_each_run(std::size_t count, std::size_t run, const Fn& fn) const {
    for_each((count + run - 1) / run,
             [&](std::size_t r) { fn(r * run, std::min(count, r * run + run)); });
  }

  // Runs fn() on the caller's thread: the one pass a loop makes where one thread runs it whole.
  // Timed as a loop (loop_ms()) where `shared`, work that more threads would share.
  template <class Fn>
  void as_one_run(const Fn& fn, bool shared) const {
    const LoopClock clock(*this, shared);
    fn();
  }

  // Runs first() and second() at once where there are threads, else one after the other: two
  // jobs that are not loops over items. Their time is serial time (loop_ms()): no more than two
  // threads share them.
  template <class First, class Second>
  void side_by_side(const First& first, const Second& second) const {
    const LoopClock clock(*this, false);
    if (!arena_) {
      first();
      second();
      return;
    }
    const auto job = [&](std::size_t i) {
      if (i == 0) {
        first();
      } else {
        second();
      }
    };
    run(
        2, [](const void* f, std::size_t i) { (*static_cast<const decltype(job)*>(f))(i); }, &job);
  }

  // Fewer items than this per stage on average, and for_each_in_stages runs on the caller's
  // thread alone. unit: items
  static constexpr std::size_t kItemsPerStageForThreads = 4;

  // Runs stages one after another: stage s calls fn(s, i) for every i in [0, counts[s]), in any
  // order and concurrently when there are threads, and starts once stage s - 1 has finished. For
  // many short stages (a solver's colours, pass after pass): the threads stay for the whole run
  // and wait for each other between stages, instead of being handed each stage's items anew. fn
  // must not touch what another item of its stage writes; it sees what earlier stages wrote.
  template <class Fn>
  void for_each_in_stages(std::span<const std::uint32_t> counts, const Fn& fn) const {
    std::size_t items = 0;
    for (const std::uint32_t count : counts) items += count;
    // Stages of a few items each run on this thread: the wait between stages costs more than
    // their items (a pile of 100 bunnies has some 200 stages a step of one to three blocks each).
    // (Serial time, then, whatever the thread count.)
    const bool shared = items >= kItemsPerStageForThreads * counts.size();
    if (!arena_ || !shared) {
      const LoopClock clock(*this, shared);
      for (std::size_t stage = 0; stage < counts.size(); ++stage) {
        for (std::uint32_t i = 0; i < counts[stage]; ++i) fn(stage, i);
      }
      return;
    }
    const LoopClock clock(*this);
    run_stages(
        counts,
        [](const void* f, std::size_t stage, std::uint32_t i) {
          (*static_cast<const Fn*>(f))(stage, i);
        },
        &fn);
  }

 private:
  // Times a loop into loop_ns_ unless it runs inside another.
  class LoopClock {
   public:
    // Not `timed`: a loop whose time is serial, yet which keeps any loop inside it untimed.
    explicit LoopClock(const Parallel& parallel, bool timed = true)
        : parallel_(parallel),
          outermost_(parallel.loops_running_.fetch_add(1, std::memory_order_relaxed) == 0 && timed),
          start_(outermost_ ? std::chrono::steady_clock::now()
                            : std::chrono::steady_clock::time_point{}) {}
    ~LoopClock() {
      if (outermost_) {
        const auto spent = std::chrono::steady_clock::now() - start_;
        parallel_.loop_ns_.fetch_add(
            std::chrono::duration_cast<std::chrono::nanoseconds>(spent).count(),
            std::memory_order_relaxed);
      }
      parallel_.loops_running_.fetch_sub(1, std::memory_order_relaxed);
    }
    LoopClock(const LoopClock&) = delete;
    LoopClock& operator=(const LoopClock&) = delete;

   private:
    const Parallel& parallel_;
    bool outermost_;
    std::chrono::steady_clock::time_point start_;
  };

  void run_stages(std::span<const std::uint32_t> counts,
                  void (*item)(const void*, std::size_t, std::uint32_t), const void* fn) const;

  // The threaded loop, behind a plain function pointer so that oneTBB's headers stay out of this
  // one.
  void run(std::size_t count, void (*item)(const void*, std::size_t), const void* fn) const;

  struct Arena;  // a oneTBB task arena of threads_ threads
  std::uint32_t threads_ = 1;
  std::unique_ptr<Arena> arena_;                         // none with one thread
  mutable std::atomic<std::int64_t> loop_ns_{0};         // loop_ms(). unit: ns
  mutable std::atomic<std::uint32_t> loops_running_{0};  // loops begun and not ended
};

// `parallel`, or where there is none the caller's thread alone (a detector or a sleep tracker
// used without a world).
[[nodiscard]] const Parallel& threads_or_caller(const Parallel* parallel);

// Parallel::for_each on `parallel`'s threads, or in order on the caller's thread where there is
// none (a detector or broad phase used without a world).
template <class Fn>
void for_each_on(const Parallel* parallel, std::size_t count, const Fn& fn) {
  if (parallel != nullptr) {
    parallel->for_each(count, fn);
    return;
  }
  for (std::size_t i = 0; i < count; ++i) fn(i);
}

}  // namespace sphys
