#include "collision/broad_phase.h"

#include <algorithm>
#include <bit>

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

void merge_touched_pairs(std::vector<ProxyPair>& pairs, std::span<const std::uint64_t> touched,
                         const PairCounts& table, std::vector<ProxyPair>& scratch,
                         std::vector<ProxyPair>& entered, std::vector<ProxyPair>& left) {
  if (touched.empty()) return;
  scratch.clear();
  std::size_t old_i = 0;
  std::size_t touched_i = 0;
  while (old_i < pairs.size() || touched_i < touched.size()) {
    const std::uint64_t from_old = old_i < pairs.size() ? pair_key(pairs[old_i]) : kEmpty;
    const std::uint64_t from_touched = touched_i < touched.size() ? touched[touched_i] : kEmpty;
    const std::uint64_t key = std::min(from_old, from_touched);
    if (from_old == key) ++old_i;
    if (from_touched == key) ++touched_i;
    const bool was_in = from_old == key;
    const bool is_in = from_touched != key || table.contains(key);
    if (is_in) scratch.push_back(pair_of(key));
    if (is_in && !was_in) entered.push_back(pair_of(key));
    if (was_in && !is_in) left.push_back(pair_of(key));
  }
  pairs.swap(scratch);
}

}  // namespace sphys
