#pragma once

// Broad phase: incremental Sweep & Prune over axis-aligned boxes (paper §3.1; Cohen, Lin, Manocha
// & Ponamgi 1995, I-COLLIDE; Ericson, Real-Time Collision Detection §7.5). docs/collision.md
// explains the cost, the handling of ties and what is allocated when.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "collision/broad_phase.h"
#include "collision/crowd.h"
#include "sphys/math.h"

namespace sphys {

// The set of overlapping pairs of a changing set of boxes, kept up to date from one call of
// update() to the next. Boxes overlap as Aabb::overlaps says: closed intervals, so boxes that
// touch overlap.
//
// add(), remove() and set_box() only record; update() applies them all and refreshes pairs().
// It re-sorts the endpoints of the boxes on each axis with an insertion sort and updates the pairs
// from the swaps the sort makes, in O(n + m + swaps) for n boxes and m pairs; small motions between
// updates (temporal coherence) make few swaps. Once the pair count and the endpoint arrays have
// reached their largest size, update() allocates nothing and throws nothing.
//
// Deterministic: the same sequence of calls gives the same ids and the same pairs() in the same
// order. Not thread-safe; one thread at a time.
class SweepAndPrune {
 public:
  // Adds a box (unit: m) and returns its id. The box takes part from the next update() on.
  // Throws sphys::Error for a box with a non-finite coordinate or min > max on some axis, or when
  // 2^31 proxies exist at once.
  ProxyId add(const Aabb& box, ProxyKind kind);
  // Removes a proxy; it and its pairs leave pairs() at the next update(), after which its id may be
  // given out again. `id` must be a proxy that exists (checked by assert).
  void remove(ProxyId id);
  // Moves a proxy's box (unit: m); the sorting happens in update(). `box` must be finite with
  // min <= max on every axis and `id` a proxy that exists (checked by assert; the step never
  // throws).
  void set_box(ProxyId id, const Aabb& box);
  // The box last given to add() or set_box() (unit: m).
  [[nodiscard]] Aabb box(ProxyId id) const;

  // Applies the adds, removes and moves since the last call and refreshes pairs().
  void update();

  // The overlapping pairs as of the last update(), sorted by (a, b). Valid until the next update().
  [[nodiscard]] std::span<const ProxyPair> pairs() const { return pairs_; }
  // The pairs the last update() brought into pairs() and those it took out (pairs of removed
  // proxies included), each sorted by (a, b). Valid until the next update().
  [[nodiscard]] std::span<const ProxyPair> pairs_entered() const { return entered_; }
  [[nodiscard]] std::span<const ProxyPair> pairs_left() const { return left_; }
  // Proxies added and not removed (counting those waiting for the next update()).
  [[nodiscard]] std::size_t size() const { return live_count_; }
  // Endpoint swaps the insertion sort made in the last update(), over all three axes: the measure
  // of motion the cost follows. 0 after an update() that rebuilt everything (see docs).
  [[nodiscard]] std::uint64_t swaps_last_update() const { return swaps_last_update_; }

  // Crowds (collision/crowd.h, Crowd; docs/collision.md, "Crowds"): with a limit L (0: none) of
  // overlapping boxes per box, an update() in a crowd lists each crowded box's pairs with its L/2
  // nearest crowded partners only. Such an update() rebuilds everything without listing the
  // overlaps first: O(n log n + listed) time where boxes pile up, however many overlap, and memory
  // for the boxes and the listed pairs only. Deterministic, as without a limit.
  void set_crowd_limit(std::uint32_t pairs_per_box) { crowd_.set_limit(pairs_per_box); }
  // Whether the last update() paired the proxy only with its nearest (Crowd::crowded).
  [[nodiscard]] bool crowded(ProxyId id) const { return crowd_.crowded(id); }
  // Whether the last update() found a crowd, and how many overlapping pairs it left out.
  [[nodiscard]] bool has_crowd() const { return crowd_.found(); }
  [[nodiscard]] std::uint64_t pairs_deferred() const { return crowd_.pairs_deferred(); }
  [[nodiscard]] const Crowd& crowd() const { return crowd_; }

 private:
  // What the crowd's listing reads of the boxes (Crowd::list), with one sweep along an axis.
  struct CrowdBoxes;

  void store(ProxyId id, const Aabb& box);
  void rebuild();
  // rebuild()'s sweep along one axis of sorted endpoints: hands each overlapping pair's key to
  // `found` until it returns false.
  template <class Found>
  void sweep(int axis, const Found& found) const;
  // Back to the pairs before this update's incremental changes, for a rebuild that replaces them.
  void undo_changes();
  void sort_axis(int axis);
  void integrate_added();
  void drop_removed_pairs();
  void merge_changes();
  void on_min_passes_max(int axis, ProxyId a, ProxyId b);
  void on_max_passes_min(int axis, ProxyId a, ProxyId b);

  // A box as six floats, min x y z then max x y z, so that an endpoint finds its value without a
  // branch; the box now and as of the last update(), together in one cache line, since the swaps
  // of the sort read both at random.
  struct alignas(64) Bounds {
    BoxBounds now;
    BoxBounds before;
  };

  // Per id.
  std::vector<Bounds> bounds_;
  // Per axis and id: the box's interval {min, max} on that axis, a copy of bounds_[id].now that
  // packs what the sort of one axis reads into an eighth of the memory.
  std::array<std::vector<std::array<float, 2>>, 3> intervals_;
  std::vector<std::uint8_t> flags_;
  // Per axis: the endpoints of the boxes taking part, sorted (see the key layout in the source).
  std::array<std::vector<std::uint64_t>, 3> endpoints_;

  PairCounts pair_set_;               // the keys of pairs_ (and of changes during an update())
  std::vector<ProxyPair> pairs_;      // sorted; what pairs() shows
  std::vector<ProxyPair> entered_;    // sorted; what pairs_entered() shows
  std::vector<ProxyPair> left_;       // sorted; what pairs_left() shows
  PairMerge merge_;                   // merge_changes()'s working memory, its list the next pairs_
  std::vector<std::uint64_t> added_;  // keys that entered pair_set_ in this update()
  std::vector<std::uint64_t> removed_;  // keys that left pair_set_ in this update()

  std::vector<ProxyId> waiting_;  // added since the last update(), in the order of add()
  std::vector<ProxyId> retired_;  // removed since the last update()
  std::vector<ProxyId> free_ids_;
  std::size_t live_count_ = 0;
  std::uint64_t swaps_last_update_ = 0;

  Crowd crowd_;  // who is crowded, as of the last rebuild
};

}  // namespace sphys
