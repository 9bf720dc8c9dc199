// A detection's jobs: the candidate pairs and the bodies against the ground plane that have a
// moving body, listed in order on the threads; the records of the others keep their contacts
// asleep. Two passes over the records and two over the bodies, a scan as place_in_runs does it
// (core/place_in_runs.h) with two lists at once: each run marks its records and counts its jobs
// and its newly resting records, a sum over the runs places them, each run writes its own.

#include <algorithm>
#include <atomic>

#include "collision/collision_detector.h"
#include "core/buffers.h"

namespace sphys {
namespace {

// Records or bodies per item of the threaded loops. unit: items
constexpr std::size_t kItemsPerRun = 256;

}  // namespace

// `moving(k)`: item k is a job; `resting(k)`: its record rests, `record(k)` (a PairRecord&).
// Lists the jobs {k, plane} in jobs_ from `first.jobs` on and the newly resting items in
// newly_resting_ from `first.newly_resting` on, each in order, sizing each to its end; returns
// the resting records' live contacts. On one thread, one pass into room for every item.
template <class Moving, class Resting, class RecordOf>
std::size_t CollisionDetector::list_in_runs(const Parallel& parallel, std::size_t count, bool plane,
                                            RunLists first, const Moving& moving,
                                            const Resting& resting, const RecordOf& record) {
  // Items [begin, end) listed from `next` on, or counted into it where `write` is false; returns
  // the live contacts of the resting records.
  const auto list = [&](std::size_t begin, std::size_t end, RunLists& next, bool write) {
    std::size_t live = 0;
    for (std::size_t k = begin; k < end; ++k) {
      if (moving(k)) {
        if (write) jobs_[next.jobs] = {static_cast<std::uint32_t>(k), plane};
        ++next.jobs;
      } else if (resting(k)) {
        PairRecord& rests = record(k);
        live += PairCache::rest(rests);
        if (rests.kept_asleep) continue;
        if (write) newly_resting_[next.newly_resting] = static_cast<std::uint32_t>(k);
        ++next.newly_resting;
      }
    }
    return live;
  };
  const auto resize = [&](const RunLists& end) {
    resize_buffer(jobs_, end.jobs);
    resize_buffer(newly_resting_, end.newly_resting);
  };
  if (parallel.threads() == 1) {
    const auto room = static_cast<std::uint32_t>(count);
    resize({first.jobs + room, first.newly_resting + room});
    std::size_t live = 0;
    parallel.as_one_run([&] { live = list(0, count, first, true); }, count > kItemsPerRun);
    resize(first);
    return live;
  }
  const std::size_t runs = (count + kItemsPerRun - 1) / kItemsPerRun;
  resize_buffer(run_lists_, runs + 1);
  run_lists_[0] = first;
  std::atomic<std::size_t> live_asleep{0};
  parallel.for_each_run(count, kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    RunLists taken;
    live_asleep.fetch_add(list(begin, end, taken, false), std::memory_order_relaxed);
    run_lists_[begin / kItemsPerRun + 1] = taken;
  });
  for (std::size_t r = 0; r < runs; ++r) {
    run_lists_[r + 1].jobs += run_lists_[r].jobs;
    run_lists_[r + 1].newly_resting += run_lists_[r].newly_resting;
  }
  resize(run_lists_[runs]);
  parallel.for_each_run(count, kItemsPerRun, [&](std::size_t begin, std::size_t end) {
    RunLists next = run_lists_[begin / kItemsPerRun];
    list(begin, end, next, true);
  });
  return live_asleep.load();
}

void CollisionDetector::list_jobs() {
  const Parallel& parallel = threads_or_caller(parallel_);
  const std::span<PairRecord> records = cache_.records();
  // Every record and body starts undone (marked by `moving`, twice over). An unpaired record
  // (bodies a joint holds together) neither moves nor rests: it is left with no contacts.
  std::size_t live_asleep = list_in_runs(
      parallel, records.size(), false, {},
      [&](std::size_t p) {
        records[p].done = false;
        if (unpaired(records[p])) {
          drop_contacts(records[p]);
          return false;
        }
        return moves(body_of_proxy_[records[p].proxies.a]) ||
               moves(body_of_proxy_[records[p].proxies.b]);
      },
      [&](std::size_t p) { return !unpaired(records[p]); },
      [&](std::size_t p) -> PairRecord& { return records[p]; });
  pair_jobs_ = jobs_.size();
  const std::size_t resting_pairs = newly_resting_.size();
  const bool plane = settings_.ground_plane_height.has_value();
  live_asleep += list_in_runs(
      parallel, bodies_.size(), true,
      {static_cast<std::uint32_t>(pair_jobs_), static_cast<std::uint32_t>(resting_pairs)},
      [&](std::size_t i) {
        bodies_[i].ground_done = false;
        return plane && moves(static_cast<std::uint32_t>(i));
      },
      [&](std::size_t i) { return plane && store_->alive(static_cast<std::uint32_t>(i)); },
      [&](std::size_t i) -> PairRecord& {
        return cache_.ground_record(static_cast<std::uint32_t>(i));
      });
  cache_.count_live_asleep(live_asleep);
  // The records that only now rest, kept in the sleeping pairs' store in order: the pairs', then
  // the plane's.
  for (std::size_t k = 0; k < newly_resting_.size(); ++k) {
    const std::uint32_t item = newly_resting_[k];
    cache_.keep_asleep(k < resting_pairs ? records[item] : cache_.ground_record(item));
  }
}

}  // namespace sphys
