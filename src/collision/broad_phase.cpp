#include "collision/broad_phase.h"

#include <algorithm>
#include <bit>

#include "core/buffers.h"
#include "sphys/error.h"

namespace sphys {
namespace {

constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // no pair key has both halves all ones:
                                                     // an empty slot, and past every key

}  // namespace

void check_proxy_box(const Aabb& box) {
  if (!box.min.allFinite() || !box.max.allFinite()) {
    throw Error("broad phase: a box must have finite coordinates");
  }
  if (box.empty()) throw Error("broad phase: a box must have min <= max on every axis");
}

ProxyId take_proxy_id(std::vector<ProxyId>& free_ids, std::size_t count) {
  if (!free_ids.empty()) {
    const ProxyId id = free_ids.back();
    free_ids.pop_back();
    return id;
  }
  // Ids stay below 2^31: the top bit of an endpoint's or a cell's id is a flag.
  if (count >= std::size_t{1} << 31) throw Error("broad phase: more than 2^31 proxies");
  return static_cast<ProxyId>(count);
}

bool PairCounts::insert(std::uint64_t key) {
  if ((size_ + 1) * 2 > keys_.size()) grow();
  const std::size_t slot = find(key);
  if (keys_[slot] == key) return false;
  keys_[slot] = key;
  counts_[slot] = 1;
  ++size_;
  return true;
}

bool PairCounts::add(std::uint64_t key) {
  if ((size_ + 1) * 2 > keys_.size()) grow();
  const std::size_t slot = find(key);
  if (keys_[slot] == key) {
    ++counts_[slot];
    return false;
  }
  keys_[slot] = key;
  counts_[slot] = 1;
  ++size_;
  return true;
}

bool PairCounts::erase(std::uint64_t key) {
  if (keys_.empty()) return false;
  const std::size_t slot = find(key);
  if (keys_[slot] != key) return false;
  remove_at(slot);
  return true;
}

bool PairCounts::drop(std::uint64_t key) {
  const std::size_t slot = find(key);
  if (--counts_[slot] > 0) return false;
  remove_at(slot);
  return true;
}

bool PairCounts::contains(std::uint64_t key) const {
  return !keys_.empty() && keys_[find(key)] == key;
}

void PairCounts::clear() {
  std::fill(keys_.begin(), keys_.end(), kEmpty);
  size_ = 0;
}

std::size_t PairCounts::find(std::uint64_t key) const {
  const std::size_t mask = keys_.size() - 1;
  std::size_t i = home(key);
  while (keys_[i] != key && keys_[i] != kEmpty) i = (i + 1) & mask;
  return i;
}

// Backward-shift deletion (Knuth, TAOCP vol. 3, §6.4, Algorithm R): the entries after the hole
// that could not be found past it move back into it, so no tombstones accumulate.
void PairCounts::remove_at(std::size_t hole) {
  const std::size_t mask = keys_.size() - 1;
  for (std::size_t j = (hole + 1) & mask; keys_[j] != kEmpty; j = (j + 1) & mask) {
    const std::size_t h = home(keys_[j]);
    // The entry at j was probed from h through j; it must move if the hole lies on that path.
    if (((hole - h) & mask) < ((j - h) & mask)) {
      keys_[hole] = keys_[j];
      counts_[hole] = counts_[j];
      hole = j;
    }
  }
  keys_[hole] = kEmpty;
  --size_;
}

// Fibonacci hashing (Knuth, TAOCP vol. 3, §6.4): the top bits of key * 2^64 / golden ratio spread
// the packed id pairs, whose low and high halves are small and correlated, over the table.
std::size_t PairCounts::home(std::uint64_t key) const {
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
}

void PairCounts::grow() {
  const std::size_t capacity = std::max<std::size_t>(64, keys_.size() * 2);
  std::vector<std::uint64_t> old_keys(capacity, kEmpty);
  std::vector<std::uint32_t> old_counts(capacity, 0);
  old_keys.swap(keys_);
  old_counts.swap(counts_);
  shift_ = 64 - std::countr_zero(capacity);
  for (std::size_t i = 0; i < old_keys.size(); ++i) {
    if (old_keys[i] == kEmpty) continue;
    const std::size_t slot = find(old_keys[i]);
    keys_[slot] = old_keys[i];
    counts_[slot] = old_counts[i];
  }
}

namespace {

// Old pairs per run of the merge. unit: pairs
constexpr std::size_t kPairsPerMergeRun = 2048;

// The merge of old pairs [old_i, old_end) with touched keys [touched_i, touched_end), in key
// order: emit(key, listed, entered, left) for each key of either.
template <class Emit>
void merge_run(std::span<const ProxyPair> pairs, std::size_t old_i, std::size_t old_end,
               std::span<const std::uint64_t> touched, std::size_t touched_i,
               std::size_t touched_end, const PairCounts& table, const Emit& emit) {
  while (old_i < old_end || touched_i < touched_end) {
    const std::uint64_t from_old = old_i < old_end ? pair_key(pairs[old_i]) : kEmpty;
    const std::uint64_t from_touched = touched_i < touched_end ? touched[touched_i] : kEmpty;
    const std::uint64_t key = std::min(from_old, from_touched);
    if (from_old == key) ++old_i;
    if (from_touched == key) ++touched_i;
    const bool was_in = from_old == key;
    const bool is_in = from_touched != key || table.contains(key);
    emit(key, is_in, is_in && !was_in, was_in && !is_in);
  }
}

}  // namespace

void merge_touched_pairs(std::vector<ProxyPair>& pairs, std::span<const std::uint64_t> touched,
                         const PairCounts& table, PairMerge& work, std::vector<ProxyPair>& entered,
                         std::vector<ProxyPair>& left, const Parallel* parallel) {
  if (touched.empty()) return;
  // Run r takes its old pairs and the touched keys from its first old pair's on (the first run
  // from the first), up to the next run's first old pair (the last run to the end). On one
  // thread, one run.
  const bool one_thread = parallel == nullptr || parallel->threads() == 1;
  const std::size_t runs =
      one_thread
          ? 1
          : std::max<std::size_t>(1, (pairs.size() + kPairsPerMergeRun - 1) / kPairsPerMergeRun);
  const std::size_t run_pairs = one_thread ? pairs.size() : kPairsPerMergeRun;
  const auto old_begin = [&](std::size_t r) { return std::min(pairs.size(), r * run_pairs); };
  const auto touched_begin = [&](std::size_t r) -> std::size_t {
    if (r == 0) return 0;
    if (r == runs) return touched.size();
    return static_cast<std::size_t>(
        std::lower_bound(touched.begin(), touched.end(), pair_key(pairs[old_begin(r)])) -
        touched.begin());
  };
  const auto merge = [&](std::size_t r, const auto& emit) {
    merge_run(pairs, old_begin(r), old_begin(r + 1), touched, touched_begin(r),
              touched_begin(r + 1), table, emit);
  };
  if (runs == 1) {
    work.merged.clear();
    const auto one_pass = [&] {
      merge(0, [&](std::uint64_t key, bool listed, bool came, bool went) {
        if (listed) work.merged.push_back(pair_of(key));
        if (came) entered.push_back(pair_of(key));
        if (went) left.push_back(pair_of(key));
      });
    };
    threads_or_caller(parallel).as_one_run(one_pass, pairs.size() > kPairsPerMergeRun);
    pairs.swap(work.merged);
    return;
  }
  resize_buffer(work.runs, runs + 1);
  work.runs[0] = {0, static_cast<std::uint32_t>(entered.size()),
                  static_cast<std::uint32_t>(left.size())};
  for_each_on(parallel, runs, [&](std::size_t r) {
    PairMerge::Run taken;
    merge(r, [&](std::uint64_t, bool listed, bool came, bool went) {
      taken.listed += listed ? 1 : 0;
      taken.entered += came ? 1 : 0;
      taken.left += went ? 1 : 0;
    });
    work.runs[r + 1] = taken;
  });
  for (std::size_t r = 0; r < runs; ++r) {
    work.runs[r + 1].listed += work.runs[r].listed;
    work.runs[r + 1].entered += work.runs[r].entered;
    work.runs[r + 1].left += work.runs[r].left;
  }
  resize_buffer(work.merged, work.runs[runs].listed);
  resize_buffer(entered, work.runs[runs].entered);
  resize_buffer(left, work.runs[runs].left);
  for_each_on(parallel, runs, [&](std::size_t r) {
    PairMerge::Run next = work.runs[r];
    merge(r, [&](std::uint64_t key, bool listed, bool came, bool went) {
      if (listed) work.merged[next.listed++] = pair_of(key);
      if (came) entered[next.entered++] = pair_of(key);
      if (went) left[next.left++] = pair_of(key);
    });
  });
  pairs.swap(work.merged);
}

}  // namespace sphys
