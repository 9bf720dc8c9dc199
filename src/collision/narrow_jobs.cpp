// A detection's jobs: the candidate pairs and the bodies against the ground plane that have a
// moving body, listed in order on the threads; the records of the others keep their contacts
// asleep.

#include <atomic>

#include "collision/collision_detector.h"
#include "core/place_in_runs.h"

namespace sphys {
namespace {

// Records or bodies per item of the threaded loops. unit: items
constexpr std::size_t kItemsPerRun = 256;

}  // namespace

void CollisionDetector::list_jobs() {
  const Parallel& parallel = threads_or_caller(parallel_);
  const std::span<PairRecord> records = cache_.records();
  // An unpaired record (bodies a joint holds together) neither moves nor rests: it has no
  // contacts.
  const auto pair_moves = [&](std::size_t p) {
    return (moves(body_of_proxy_[records[p].proxies.a]) ||
            moves(body_of_proxy_[records[p].proxies.b])) &&
           !unpaired(records[p]);
  };
  const bool plane = settings_.ground_plane_height.has_value();
  const auto plane_rests = [&](std::size_t i) {
    return plane && !moves(static_cast<std::uint32_t>(i)) &&
           store_->alive(static_cast<std::uint32_t>(i));
  };
  // Each record and body starts undone; a resting one's record keeps its contacts asleep.
  std::atomic<std::size_t> live_asleep{0};
  parallel.for_each_run(records.size(), kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    std::size_t live = 0;
    for (std::size_t p = begin; p < end; ++p) {
      records[p].done = false;
      if (unpaired(records[p])) {
        drop_contacts(records[p]);
      } else if (!pair_moves(p)) {
        live += PairCache::rest(records[p]);
      }
    }
    live_asleep.fetch_add(live, std::memory_order_relaxed);
  });
  parallel.for_each_run(bodies_.size(), kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    std::size_t live = 0;
    for (std::size_t i = begin; i < end; ++i) {
      bodies_[i].ground_done = false;
      if (plane_rests(i))
        live += PairCache::rest(cache_.ground_record(static_cast<std::uint32_t>(i)));
    }
    live_asleep.fetch_add(live, std::memory_order_relaxed);
  });
  cache_.count_live_asleep(live_asleep.load());

  // The jobs: the moving pairs in the records' order, then the moving bodies against the plane.
  pair_jobs_ = compact_in_runs(
      parallel, records.size(), kItemsPerRun, pair_moves,
      [&](std::size_t count) { resize_buffer(jobs_, count); },
      [&](std::size_t position, std::size_t p) {
        jobs_[position] = {static_cast<std::uint32_t>(p), false};
      },
      run_first_);
  compact_in_runs(
      parallel, plane ? bodies_.size() : 0, kItemsPerRun,
      [&](std::size_t i) { return moves(static_cast<std::uint32_t>(i)); },
      [&](std::size_t count) { resize_buffer(jobs_, pair_jobs_ + count); },
      [&](std::size_t position, std::size_t i) {
        jobs_[pair_jobs_ + position] = {static_cast<std::uint32_t>(i), true};
      },
      run_first_);

  // The records that only now rest, kept in the sleeping pairs' store in order: the pairs', then
  // the plane's.
  compact_in_runs(
      parallel, records.size(), kItemsPerRun,
      [&](std::size_t p) {
        return !pair_moves(p) && !records[p].kept_asleep && !unpaired(records[p]);
      },
      [&](std::size_t count) { resize_buffer(newly_resting_, count); },
      [&](std::size_t position, std::size_t p) {
        newly_resting_[position] = static_cast<std::uint32_t>(p);
      },
      run_first_);
  for (const std::uint32_t p : newly_resting_) cache_.keep_asleep(records[p]);
  compact_in_runs(
      parallel, bodies_.size(), kItemsPerRun,
      [&](std::size_t i) {
        return plane_rests(i) && !cache_.ground_record(static_cast<std::uint32_t>(i)).kept_asleep;
      },
      [&](std::size_t count) { resize_buffer(newly_resting_, count); },
      [&](std::size_t position, std::size_t i) {
        newly_resting_[position] = static_cast<std::uint32_t>(i);
      },
      run_first_);
  for (const std::uint32_t i : newly_resting_) cache_.keep_asleep(cache_.ground_record(i));
}

}  // namespace sphys
