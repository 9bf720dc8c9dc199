#pragma once

// Crowds (docs/collision.md, "Crowds"; CollisionSettings::crowd_pairs_per_body): who is crowded,
// which of a crowd's pairs the broad phases list, and how the narrow phase serves a pair of two
// crowded bodies. The broad phases (sweep_and_prune.cpp, cell_sweep_and_prune.cpp) and the
// narrow phase (narrow_phase.cpp, through PairKind::kCrowded) call it.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "collision/broad_phase.h"
#include "collision/crowd_tree.h"
#include "sphys/sphere_tree.h"

namespace sphys {

// The crowd rule of one Sweep & Prune. Boxes piled on each other make pairs by the square of
// their number. With a limit L (0: none), a listing at which the boxes overlap more than L others
// each on average (more than L/2 to stay so) lists, of the pairs of two crowded boxes (dynamic
// ones overlapping more than L others), only those of each crowded box with its L/2 nearest
// partners (by the boxes' centres; ties to the lower id). Nearest partners are the deepest
// overlaps, those that hold the crowd up, and they change little from one listing to the next.
// Pairs with a box that is not crowded (a static one among them: the ground) are all listed.
// Deterministic.
class Crowd {
 public:
  void set_limit(std::uint32_t pairs_per_box) { limit_ = pairs_per_box; }
  // Whether the last listing found a crowd, and how many overlapping pairs it left out.
  [[nodiscard]] bool found() const { return crowded_; }
  [[nodiscard]] std::uint64_t pairs_deferred() const { return pairs_deferred_; }
  // Whether the last listing paired the box only with its nearest: in a crowd, a box that was
  // crowded at the listing before (at this one, for the crowd's first).
  [[nodiscard]] bool crowded(ProxyId id) const {
    return crowded_ && id < choosing_.size() && choosing_[id] != 0;
  }
  // Whether `pairs` overlapping pairs of `boxes` boxes, listed whole, are past the limit: a crowd
  // formed since the last listing, which must then list again.
  [[nodiscard]] bool overflows(std::size_t pairs, std::size_t boxes) const {
    return limit_ > 0 && pairs > crowd_pairs(1.0, boxes);
  }

  // The keys of the pairs to list, into `listed` (empty before; unsorted, each once). Out of a
  // crowd, one sweep lists the pairs while they are few and stops at the first past the limit. In a
  // crowd, or one forming, no overlap is listed before the rule has cut them: a tree over the boxes
  // (CrowdTree) counts each box's overlaps, lists those of the boxes not crowded, and finds each
  // crowded box's nearest. O(n log n + listed) for n boxes where they pile up, whatever the
  // count of their overlaps; the sweep lists every pair once more only when the crowd has
  // thinned out below L/2. `boxes` shows the broad phase's boxes: ids() (ids in use, alive or
  // not), live() (boxes alive), alive(id), bounds(id) (a BoxBounds; unit: m), is_static(id) and
  // sweep(found) (hands each overlapping pair's key to `found`, which returns false to stop).
  template <class Boxes>
  void list(const Boxes& boxes, std::vector<std::uint64_t>& listed);

 private:
  // The pair count past which `boxes` boxes are a crowd: L n / 2, times `share`.
  [[nodiscard]] std::uint64_t crowd_pairs(double share, std::size_t boxes) const {
    return static_cast<std::uint64_t>(share * 0.5 * limit_ * static_cast<double>(boxes));
  }
  // The crowded boxes whose pairs a crowd's listing chooses among: dynamic boxes that overlapped
  // more than L others at the last count.
  template <class Boxes>
  void mark_choosing(const Boxes& boxes);
  [[nodiscard]] std::size_t nearest_kept() const;
  // Each box's overlaps counted by the tree, into overlaps_; returns the overlapping pairs.
  std::uint64_t count_overlaps(std::size_t ids);
  // The pairs of the boxes not choosing, and every choosing box's nearest choosing partners,
  // into `listed`, sorted and each once.
  void list_chosen(std::vector<std::uint64_t>& listed);

  std::uint32_t limit_ = 0;  // unit: overlapping boxes per box; 0: no limit
  bool crowded_ = false;
  std::uint64_t pairs_deferred_ = 0;     // overlapping pairs the last listing left out
  std::vector<std::uint32_t> overlaps_;  // per id: boxes it overlapped at the last count
  // Per id: 1 for the crowded boxes whose pairs a crowd's listing chooses among: what crowded()
  // reports.
  std::vector<std::uint8_t> choosing_;
  CrowdTree tree_;                     // the boxes of a crowd's listing
  std::vector<ProxyId> alive_;         // their ids, ascending
  std::vector<CrowdPartner> nearest_;  // one box's nearest, list_chosen()'s working list
};

// Crowds over the cells of a broad phase by cells (CellSweepAndPrune), each cell's Sweep & Prune
// judging its own boxes: a box is crowded if it is in some cell, and the pairs left out are
// summed over the cells (a pair left out in one cell may be listed through another).
class CellCrowds {
 public:
  // Forgets the last update's crowds.
  void clear() {
    pairs_deferred_ = 0;
    crowded_.clear();
  }
  // One cell's crowd, among `proxies` proxy ids: `proxy_of(local)` is the proxy of the cell's
  // id `local` (below `locals`), or kNoProxy for a box that left the cell.
  template <class ProxyOf>
  void add_cell(const Crowd& cell, std::size_t proxies, std::size_t locals,
                const ProxyOf& proxy_of);
  [[nodiscard]] bool crowded(ProxyId id) const { return id < crowded_.size() && crowded_[id] != 0; }
  [[nodiscard]] bool found() const { return !crowded_.empty(); }
  [[nodiscard]] std::uint64_t pairs_deferred() const { return pairs_deferred_; }

  static constexpr ProxyId kNoProxy = ~ProxyId{0};

 private:
  std::vector<std::uint8_t> crowded_;  // per proxy id; empty without a crowd
  std::uint64_t pairs_deferred_ = 0;
};

// How the narrow phase serves a pair of two crowded bodies (PairKind::kCrowded): one contact from
// their trees' roots, never reused (a crowd has pairs by the square of its bodies, each of whose
// descents would overlap at every level), its depth capped by crowd_contact_depth().
inline constexpr int kCrowdTreeDepth = 1;  // unit: levels, the root's alone

// The soft step pushes a pair apart the faster the deeper it overlaps, and a crowd's pushes add
// up from body to body: at the full depth of bodies spawned on each other, a crowd bursts at
// several m/s. Capped at kCrowdDepth of the smaller root's radius, it parts as a pile of bodies
// overlapping a little. unit: m
inline float crowd_contact_depth(float depth, const Sphere& root_a, const Sphere& root_b) {
  constexpr float kCrowdDepth = 0.5f;  // unit: dimensionless
  return std::min(depth, kCrowdDepth * std::min(root_a.radius, root_b.radius));
}

template <class Boxes>
void Crowd::list(const Boxes& boxes, std::vector<std::uint64_t>& listed) {
  pairs_deferred_ = 0;
  const auto list_all = [&] {
    boxes.sweep([&](std::uint64_t key) {
      listed.push_back(key);
      return true;
    });
  };
  if (limit_ == 0) {
    list_all();
    return;
  }
  const bool was_crowded = crowded_;
  const std::uint64_t limit = crowd_pairs(was_crowded ? 0.5 : 1.0, boxes.live());
  if (!was_crowded) {
    bool past_limit = false;
    boxes.sweep([&](std::uint64_t key) {
      past_limit = listed.size() == limit;
      if (!past_limit) listed.push_back(key);
      return !past_limit;
    });
    if (!past_limit) return;
  }
  tree_.clear();
  alive_.clear();
  for (ProxyId id = 0; id < boxes.ids(); ++id) {
    if (!boxes.alive(id)) continue;
    tree_.add(id, boxes.bounds(id), boxes.is_static(id));
    alive_.push_back(id);
  }
  tree_.build();
  if (was_crowded) mark_choosing(boxes);  // by the last listing's counts
  const std::uint64_t overlapping = count_overlaps(boxes.ids());
  crowded_ = overlapping > limit;
  listed.clear();
  if (!crowded_) {
    list_all();
    return;
  }
  if (!was_crowded) mark_choosing(boxes);
  list_chosen(listed);
  pairs_deferred_ = overlapping - listed.size();
}

template <class Boxes>
void Crowd::mark_choosing(const Boxes& boxes) {
  choosing_.assign(boxes.ids(), 0);
  for (ProxyId id = 0; id < overlaps_.size(); ++id) {
    choosing_[id] = overlaps_[id] > limit_ && !boxes.is_static(id) ? 1 : 0;
  }
}

template <class ProxyOf>
void CellCrowds::add_cell(const Crowd& cell, std::size_t proxies, std::size_t locals,
                          const ProxyOf& proxy_of) {
  if (!cell.found()) return;
  if (crowded_.empty()) crowded_.assign(proxies, 0);
  pairs_deferred_ += cell.pairs_deferred();
  for (ProxyId local = 0; local < locals; ++local) {
    const ProxyId id = proxy_of(local);
    if (id != kNoProxy && cell.crowded(local)) crowded_[id] = 1;
  }
}

}  // namespace sphys
