#include "sphys/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

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

void Parallel::run(std::size_t count, void (*item)(const void*, std::size_t),
                   const void* fn) const {
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) item(fn, i);
                      });
  });
}

}  // namespace sphys
