#pragma once

// What the broad phases (Sweep & Prune, and per cell) share: proxies, pairs, their keys and the
// table of pairs.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sphys/math.h"
#include "sphys/parallel.h"

namespace sphys {

// A handle to a box of the broad phase. Ids of removed proxies are given out again.
using ProxyId = std::uint32_t;

// Two proxies whose boxes overlap, a < b.
struct ProxyPair {
  ProxyId a = 0;
  ProxyId b = 0;

  friend bool operator==(const ProxyPair&, const ProxyPair&) = default;
  friend auto operator<=>(const ProxyPair&, const ProxyPair&) = default;
};

// Static proxies (the ground, walls) are never paired with each other, only with dynamic ones.
enum class ProxyKind : std::uint8_t { kDynamic, kStatic };

// A pair as one 64-bit key, a in the high half: keys sort as pairs do.
inline std::uint64_t pair_key(ProxyId a, ProxyId b) {
  return a < b ? std::uint64_t{a} << 32 | b : std::uint64_t{b} << 32 | a;
}
inline std::uint64_t pair_key(const ProxyPair& pair) {
  return std::uint64_t{pair.a} << 32 | pair.b;
}
inline ProxyPair pair_of(std::uint64_t key) {
  return {static_cast<ProxyId>(key >> 32), static_cast<ProxyId>(key & 0xffffffffu)};
}

// Throws sphys::Error unless the box is finite with min <= max on every axis, as a broad phase's
// add() requires.
void check_proxy_box(const Aabb& box);
// The id for a new proxy: the last freed one, or `count` (the ids in use so far) when none is
// free, in which case the caller makes room for it. Throws sphys::Error past 2^31 proxies.
ProxyId take_proxy_id(std::vector<ProxyId>& free_ids, std::size_t count);

// Open-addressing hash table of pair keys with a count each (linear probing, backward-shift
// deletion: no tombstones). Sweep & Prune keeps each overlapping pair once (insert, erase);
// Sweep & Prune per cell counts the cells in which a pair overlaps (add, drop). Grows when half
// full; never shrinks, so a steady state allocates nothing. The key ~0 is reserved.
class PairCounts {
 public:
  // Set use: true when the key was absent, which it then holds with the count 1.
  bool insert(std::uint64_t key);
  // Set use: true when the key was present (whatever its count); it is gone after.
  bool erase(std::uint64_t key);
  // Count use: one more for the key; true when it was absent before.
  bool add(std::uint64_t key);
  // Count use: one less for a key that is present; true when that was its last, and it is gone.
  bool drop(std::uint64_t key);
  [[nodiscard]] bool contains(std::uint64_t key) const;
  [[nodiscard]] std::size_t size() const { return size_; }
  void clear();

 private:
  // The slot holding the key, or the empty slot where it would go.
  [[nodiscard]] std::size_t find(std::uint64_t key) const;
  [[nodiscard]] std::size_t home(std::uint64_t key) const;
  void remove_at(std::size_t hole);
  void grow();

  std::vector<std::uint64_t> keys_;    // kEmpty or a key; size a power of two
  std::vector<std::uint32_t> counts_;  // per slot
  std::size_t size_ = 0;
  int shift_ = 64;  // 64 - log2(keys_.size())
};

// merge_touched_pairs()'s working memory, kept from update to update.
struct PairMerge {
  // What a run of old pairs lists, came in and went out, then where its lists begin.
  struct Run {
    std::uint32_t listed = 0;
    std::uint32_t entered = 0;
    std::uint32_t left = 0;
  };
  std::vector<ProxyPair> merged;  // the next pair list
  std::vector<Run> runs;
};

// Brings a sorted pair list up to date after an update touched some keys (`touched`: sorted,
// unique): an untouched pair stays, a touched key is listed if `table` holds it. Only the touched
// keys are looked up, the rest are copied: O(pairs + touched), in runs of old pairs on
// `parallel`'s threads (none: the caller's), with the same result. The pairs that came in and
// went out are appended, sorted, to `entered` and `left`.
void merge_touched_pairs(std::vector<ProxyPair>& pairs, std::span<const std::uint64_t> touched,
                         const PairCounts& table, PairMerge& work, std::vector<ProxyPair>& entered,
                         std::vector<ProxyPair>& left, const Parallel* parallel);

}  // namespace sphys
