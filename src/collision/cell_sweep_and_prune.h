#pragma once

// Broad phase for many bodies: Sweep & Prune per cell of a coarse grid. docs/collision.md
// explains why one Sweep & Prune slows down as bodies spread over a floor, and what this costs.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "collision/broad_phase.h"
#include "collision/crowd.h"
#include "collision/sweep_and_prune.h"
#include "sphys/math.h"
#include "sphys/parallel.h"

namespace sphys {

// The same contract as SweepAndPrune (add, remove and set_box record, update() applies them, the
// overlapping pairs sorted by (a, b), static proxies never paired with each other, deterministic),
// over space cut into cubes of one edge length: each cell that some box reaches runs its own
// SweepAndPrune over the boxes reaching it, and a pair is listed while its boxes overlap in at
// least one cell (counted per pair). A box reaching more than kMaxCellsPerBox cells is tested
// against every other box at each update() instead.
//
// One Sweep & Prune's cost per box grows with how many boxes share each axis's projection (as
// n^(1/2) for boxes spread over a floor, n^(2/3) filling a cube); per cell it stays with the
// number of boxes in a cell.
class CellSweepAndPrune {
 public:
  // Boxes reaching more cells than this are tested against all others.
  static constexpr std::size_t kMaxCellsPerBox = 8;

  // `cell_size`: the edge of a cell (unit: m), finite and > 0; or 0 for a size chosen at the
  // first update() that has boxes: kCellsPerBox times the median of the boxes' largest extents.
  // Throws sphys::Error for anything else.
  explicit CellSweepAndPrune(float cell_size = 0.0f);
  static constexpr float kCellsPerBox = 6.0f;

  // As SweepAndPrune::add (unit: m); throws sphys::Error for a non-finite or inverted box.
  ProxyId add(const Aabb& box, ProxyKind kind);
  // As SweepAndPrune::remove.
  void remove(ProxyId id);
  // As SweepAndPrune::set_box (unit: m).
  void set_box(ProxyId id, const Aabb& box);
  [[nodiscard]] Aabb box(ProxyId id) const { return boxes_[id]; }

  // As SweepAndPrune::update; the cells re-sort on `parallel`'s threads where given, with the
  // same pairs in the same order.
  void update(const Parallel* parallel = nullptr);

  [[nodiscard]] std::span<const ProxyPair> pairs() const { return pairs_; }
  [[nodiscard]] std::span<const ProxyPair> pairs_entered() const { return entered_; }
  [[nodiscard]] std::span<const ProxyPair> pairs_left() const { return left_; }
  [[nodiscard]] std::size_t size() const { return live_count_; }
  // Endpoint swaps of the cells' sorts in the last update().
  [[nodiscard]] std::uint64_t swaps_last_update() const { return swaps_last_update_; }
  // The edge of a cell in use (unit: m); 0 until chosen.
  [[nodiscard]] float cell_size() const { return cell_size_; }
  // Crowds, as SweepAndPrune's, judged in each cell by its own boxes (collision/crowd.h,
  // CellCrowds).
  void set_crowd_limit(std::uint32_t pairs_per_box);
  [[nodiscard]] bool crowded(ProxyId id) const { return crowds_.crowded(id); }
  [[nodiscard]] bool has_crowd() const { return crowds_.found(); }
  [[nodiscard]] std::uint64_t pairs_deferred() const { return crowds_.pairs_deferred(); }
  // Cells holding boxes after the last update().
  [[nodiscard]] std::size_t cell_count() const { return cell_of_key_.size() - empty_cells_; }

 private:
  // The cells a box reaches: integer cell coordinates, inclusive, per axis.
  struct CellRange {
    std::array<std::int32_t, 3> min{};
    std::array<std::int32_t, 3> max{};
    friend bool operator==(const CellRange&, const CellRange&) = default;
  };
  struct Membership {
    std::uint32_t cell = 0;  // index into cells_
    ProxyId local = 0;       // the box's id in that cell's SweepAndPrune
  };
  struct Proxy {
    CellRange range;
    ProxyKind kind = ProxyKind::kDynamic;
    bool alive = false;
    bool placed = false;  // in its cells (or the wide list) since an update()
    bool queued = false;  // in changed_
    bool wide = false;    // reaches more than kMaxCellsPerBox cells
    std::uint8_t membership_count = 0;
    std::array<Membership, kMaxCellsPerBox> memberships{};
  };
  struct Cell {
    std::array<std::int32_t, 3> coords{};
    SweepAndPrune sweep;
    // By the cell's own ids: the proxy, with kLeftBit set once it left the cell (the id stays
    // readable until the cell's next update has listed the pairs it left).
    std::vector<ProxyId> proxy_of_local;
    // No box reached it after an update(), yet it stays in cell_of_key_ a while: counted in
    // empty_cells_.
    bool empty = false;
  };
  static constexpr ProxyId kLeftBit = ProxyId{1} << 31;

  [[nodiscard]] CellRange range_of(const Aabb& box) const;
  [[nodiscard]] static std::size_t cells_in(const CellRange& range);
  void choose_cell_size();
  void leave_cells(ProxyId id);
  void leave_cell(const Membership& membership);
  void place(ProxyId id);
  void enter_cell(ProxyId id, const std::array<std::int32_t, 3>& cell);
  std::uint32_t cell_at(const std::array<std::int32_t, 3>& cell);
  void mark_changed(std::uint32_t cell);
  void update_cells(const Parallel* parallel);
  void update_wide();
  void release_empty_cells();
  void count_pair(ProxyId a, ProxyId b, bool entered);
  void mark_crowded();
  void merge_changes(const Parallel* parallel);

  float cell_size_ = 0.0f;  // unit: m
  // Per proxy id. The boxes apart, as the cells read them at random.
  std::vector<Aabb> boxes_;
  std::vector<Proxy> proxies_;
  std::vector<ProxyId> free_ids_;
  std::vector<ProxyId> changed_;  // added or moved since the last update(), alive or not
  std::vector<ProxyId> retired_;  // removed since the last update()
  std::size_t live_count_ = 0;

  std::vector<Cell> cells_;
  std::vector<std::uint8_t> cell_changed_;    // per cell: boxes entered, left or moved
  std::vector<std::uint32_t> changed_cells_;  // in the order first marked
  std::vector<std::uint32_t> free_cells_;
  // Cells by key. A cell left empty stays listed until the empty ones outnumber the rest, so that
  // boxes moving back and forth across a cell's border do not make and free it at every step.
  std::unordered_map<std::uint64_t, std::uint32_t> cell_of_key_;
  std::size_t empty_cells_ = 0;

  // Wide boxes, and for each the others it overlapped at the last update(), sorted.
  std::vector<ProxyId> wide_;
  std::unordered_map<ProxyId, std::vector<ProxyId>> wide_partners_;
  std::vector<ProxyId> wide_now_;  // update_wide()'s working list

  std::uint32_t crowd_limit_ = 0;       // unit: overlapping boxes per box; 0: no limit
  CellCrowds crowds_;                   // as of the last update()
  PairCounts counts_;                   // per pair: the cells (and wide tests) in which it overlaps
  std::vector<std::uint64_t> touched_;  // pair keys whose count changed in this update()
  std::vector<ProxyPair> pairs_;
  PairMerge merge_;  // merge_changes()'s working memory
  std::vector<ProxyPair> entered_;
  std::vector<ProxyPair> left_;
  std::uint64_t swaps_last_update_ = 0;
};

}  // namespace sphys
