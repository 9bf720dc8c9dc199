#include "collision/cell_sweep_and_prune.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "sphys/error.h"

namespace sphys {
namespace {

// Cell coordinates are kept within 21 bits each, so that a cell's key packs all three into 64
// bits; boxes beyond share the outermost cells (correct, only slower there).
constexpr std::int32_t kCoordLimit = 1 << 20;
constexpr std::uint64_t kCoordMask = (std::uint64_t{1} << 21) - 1;

std::uint64_t cell_key(const std::array<std::int32_t, 3>& cell) {
  std::uint64_t key = 0;
  for (const std::int32_t c : cell)
    key = key << 21 | (static_cast<std::uint64_t>(c + kCoordLimit) & kCoordMask);
  return key;
}

bool contains(const std::array<std::int32_t, 3>& min, const std::array<std::int32_t, 3>& max,
              const std::array<std::int32_t, 3>& cell) {
  for (int axis = 0; axis < 3; ++axis) {
    if (cell[axis] < min[axis] || cell[axis] > max[axis]) return false;
  }
  return true;
}

}  // namespace

CellSweepAndPrune::CellSweepAndPrune(float cell_size) : cell_size_(cell_size) {
  if (!std::isfinite(cell_size) || cell_size < 0.0f) {
    throw Error("broad phase: the cell size must be finite and >= 0 (0: chosen from the boxes)");
  }
}

ProxyId CellSweepAndPrune::add(const Aabb& box, ProxyKind kind) {
  check_proxy_box(box);
  const ProxyId id = take_proxy_id(free_ids_, proxies_.size());
  if (id == proxies_.size()) {
    proxies_.emplace_back();
    boxes_.emplace_back();
  }
  Proxy& proxy = proxies_[id];
  proxy = Proxy{};
  boxes_[id] = box;
  proxy.kind = kind;
  proxy.alive = true;
  proxy.queued = true;
  changed_.push_back(id);
  ++live_count_;
  return id;
}

void CellSweepAndPrune::remove(ProxyId id) {
  assert(id < proxies_.size() && proxies_[id].alive);
  proxies_[id].alive = false;
  retired_.push_back(id);
  --live_count_;
}

void CellSweepAndPrune::set_box(ProxyId id, const Aabb& box) {
  assert(id < proxies_.size() && proxies_[id].alive);
  Proxy& proxy = proxies_[id];
  assert(box.min.allFinite() && box.max.allFinite() && !box.empty());
  boxes_[id] = box;
  if (!proxy.queued) {
    proxy.queued = true;
    changed_.push_back(id);
  }
}

void CellSweepAndPrune::update(const Parallel* parallel) {
  swaps_last_update_ = 0;
  touched_.clear();
  entered_.clear();
  left_.clear();
  if (cell_size_ == 0.0f) choose_cell_size();
  for (const ProxyId id : retired_) leave_cells(id);
  for (const ProxyId id : changed_) {
    proxies_[id].queued = false;
    if (proxies_[id].alive) place(id);
  }
  changed_.clear();
  update_cells(parallel);
  mark_crowded();
  update_wide();
  release_empty_cells();
  merge_changes(parallel);
  // Every cell has dropped the removed proxies' pairs now, so their ids may be given out again.
  free_ids_.insert(free_ids_.end(), retired_.begin(), retired_.end());
  retired_.clear();
}

// kCellsPerBox times the median of the boxes' largest extents: a cell then holds a few boxes
// across, and most boxes reach one or two cells per axis. Zero-sized boxes give way to the
// largest one, and all of them zero-sized to 1 m.
void CellSweepAndPrune::choose_cell_size() {
  std::vector<float> extents;
  for (ProxyId id = 0; id < proxies_.size(); ++id) {
    if (proxies_[id].alive) extents.push_back((boxes_[id].max - boxes_[id].min).maxCoeff());
  }
  if (extents.empty()) return;
  const auto middle = extents.begin() + static_cast<std::ptrdiff_t>(extents.size() / 2);
  std::nth_element(extents.begin(), middle, extents.end());
  float extent = *middle;
  if (extent == 0.0f) extent = *std::max_element(extents.begin(), extents.end());
  if (extent == 0.0f) extent = 1.0f;
  cell_size_ = std::min(kCellsPerBox * extent, std::numeric_limits<float>::max());
}

// Cell coordinates from one float product per bound (the same rounding wherever a box is placed),
// clamped before the conversion so that any finite box, however far, has a cell.
CellSweepAndPrune::CellRange CellSweepAndPrune::range_of(const Aabb& box) const {
  const float per_metre = 1.0f / cell_size_;
  const auto coord = [&](float x) {
    constexpr auto kLimit = static_cast<float>(kCoordLimit);
    return static_cast<std::int32_t>(std::clamp(std::floor(x * per_metre), -kLimit, kLimit - 1.0f));
  };
  CellRange range;
  for (int axis = 0; axis < 3; ++axis) {
    range.min[axis] = coord(box.min[axis]);
    range.max[axis] = coord(box.max[axis]);
  }
  return range;
}

std::size_t CellSweepAndPrune::cells_in(const CellRange& range) {
  std::size_t count = 1;
  for (int axis = 0; axis < 3; ++axis) {
    count *= static_cast<std::size_t>(range.max[axis] - range.min[axis] + 1);
  }
  return count;
}

// A removed proxy leaves its cells (whose next update lists its pairs as left) or stops being
// tested as a wide box.
void CellSweepAndPrune::leave_cells(ProxyId id) {
  Proxy& proxy = proxies_[id];
  for (std::uint8_t m = 0; m < proxy.membership_count; ++m) leave_cell(proxy.memberships[m]);
  proxy.membership_count = 0;
  if (proxy.wide) {
    for (const ProxyId partner : wide_partners_[id]) count_pair(id, partner, false);
    wide_partners_.erase(id);
    wide_.erase(std::find(wide_.begin(), wide_.end(), id));
    proxy.wide = false;
  }
  proxy.placed = false;
}

// Puts a new or moved box into the cells it reaches now: it stays in those it still reaches
// (which read its new box when they update), leaves the others and enters the new ones.
void CellSweepAndPrune::place(ProxyId id) {
  Proxy& proxy = proxies_[id];
  const CellRange range = range_of(boxes_[id]);
  const bool wide = cells_in(range) > kMaxCellsPerBox;
  if (proxy.placed && proxy.wide == wide && (wide || range == proxy.range)) {
    for (std::uint8_t m = 0; m < proxy.membership_count; ++m) {
      mark_changed(proxy.memberships[m].cell);
    }
    return;
  }
  if (proxy.placed && (proxy.wide || wide)) {
    leave_cells(id);  // a box turning wide or narrow starts afresh
  }
  const bool was_placed = proxy.placed;
  const CellRange old_range = proxy.range;
  proxy.range = range;
  proxy.placed = true;
  if (wide) {
    proxy.wide = true;
    wide_.push_back(id);
    wide_partners_[id];  // no partners yet: update_wide() finds them
    return;
  }
  // Keep the memberships of cells still reached, leave the rest.
  std::uint8_t kept = 0;
  for (std::uint8_t m = 0; m < proxy.membership_count; ++m) {
    const Membership membership = proxy.memberships[m];
    if (contains(range.min, range.max, cells_[membership.cell].coords)) {
      mark_changed(membership.cell);
      proxy.memberships[kept++] = membership;
    } else {
      leave_cell(membership);
    }
  }
  proxy.membership_count = kept;
  std::array<std::int32_t, 3> c{};
  for (c[0] = range.min[0]; c[0] <= range.max[0]; ++c[0]) {
    for (c[1] = range.min[1]; c[1] <= range.max[1]; ++c[1]) {
      for (c[2] = range.min[2]; c[2] <= range.max[2]; ++c[2]) {
        if (!was_placed || !contains(old_range.min, old_range.max, c)) enter_cell(id, c);
      }
    }
  }
}

void CellSweepAndPrune::leave_cell(const Membership& membership) {
  Cell& cell = cells_[membership.cell];
  cell.sweep.remove(membership.local);
  cell.proxy_of_local[membership.local] |= kLeftBit;
  mark_changed(membership.cell);
}

void CellSweepAndPrune::mark_changed(std::uint32_t cell) {
  if (cell_changed_[cell] != 0) return;
  cell_changed_[cell] = 1;
  changed_cells_.push_back(cell);
}

void CellSweepAndPrune::enter_cell(ProxyId id, const std::array<std::int32_t, 3>& coords) {
  Proxy& proxy = proxies_[id];
  const std::uint32_t index = cell_at(coords);
  Cell& cell = cells_[index];
  const ProxyId local = cell.sweep.add(boxes_[id], proxy.kind);
  if (cell.proxy_of_local.size() <= local) cell.proxy_of_local.resize(local + 1);
  cell.proxy_of_local[local] = id;
  mark_changed(index);
  proxy.memberships[proxy.membership_count++] = {index, local};
}

// The cell at these coordinates, made (or an emptied one reused) if no box reached it.
std::uint32_t CellSweepAndPrune::cell_at(const std::array<std::int32_t, 3>& coords) {
  const auto [it, made] = cell_of_key_.try_emplace(cell_key(coords), 0);
  if (!made) {
    Cell& cell = cells_[it->second];
    if (cell.empty) {
      cell.empty = false;
      --empty_cells_;
    }
    return it->second;
  }
  if (free_cells_.empty()) {
    it->second = static_cast<std::uint32_t>(cells_.size());
    cells_.emplace_back();
    cells_.back().sweep.set_crowd_limit(crowd_limit_);
    cell_changed_.push_back(0);
  } else {
    it->second = free_cells_.back();
    free_cells_.pop_back();
  }
  cells_[it->second].coords = coords;
  return it->second;
}

// Each cell with changes reads its boxes' current bounds and re-sorts, the cells on the threads
// (each its own Sweep & Prune); then, cell by cell in order, the pairs it gained or lost count up
// or down.
void CellSweepAndPrune::update_cells(const Parallel* parallel) {
  const auto sort_cell = [&](std::size_t i) {
    Cell& cell = cells_[changed_cells_[i]];
    for (ProxyId local = 0; local < cell.proxy_of_local.size(); ++local) {
      const ProxyId id = cell.proxy_of_local[local];
      if ((id & kLeftBit) == 0) cell.sweep.set_box(local, boxes_[id]);
    }
    cell.sweep.update();
  };
  for_each_on(parallel, changed_cells_.size(), sort_cell);
  for (const std::uint32_t index : changed_cells_) {
    Cell& cell = cells_[index];
    cell_changed_[index] = 0;
    swaps_last_update_ += cell.sweep.swaps_last_update();
    const auto proxy_of = [&](ProxyId local) { return cell.proxy_of_local[local] & ~kLeftBit; };
    for (const ProxyPair& pair : cell.sweep.pairs_entered()) {
      count_pair(proxy_of(pair.a), proxy_of(pair.b), true);
    }
    for (const ProxyPair& pair : cell.sweep.pairs_left()) {
      count_pair(proxy_of(pair.a), proxy_of(pair.b), false);
    }
  }
}

void CellSweepAndPrune::set_crowd_limit(std::uint32_t pairs_per_box) {
  crowd_limit_ = pairs_per_box;
  for (Cell& cell : cells_) cell.sweep.set_crowd_limit(pairs_per_box);
}

// The boxes crowded in some cell, and the pairs the cells left out.
void CellSweepAndPrune::mark_crowded() {
  crowds_.clear();
  if (crowd_limit_ == 0) return;
  for (const Cell& cell : cells_) {
    crowds_.add_cell(cell.sweep.crowd(), proxies_.size(), cell.proxy_of_local.size(),
                     [&](ProxyId local) {
                       const ProxyId id = cell.proxy_of_local[local];
                       return (id & kLeftBit) == 0 ? id : CellCrowds::kNoProxy;
                     });
  }
}

// Each wide box against every other box, its partners then compared with the last update's.
void CellSweepAndPrune::update_wide() {
  std::vector<ProxyId>& now = wide_now_;
  for (const ProxyId id : wide_) {
    const Proxy& proxy = proxies_[id];
    now.clear();
    for (ProxyId other = 0; other < proxies_.size(); ++other) {
      const Proxy& p = proxies_[other];
      if (other == id || !p.alive || !p.placed) continue;
      if (proxy.kind == ProxyKind::kStatic && p.kind == ProxyKind::kStatic) continue;
      if (boxes_[id].overlaps(boxes_[other])) now.push_back(other);
    }
    std::vector<ProxyId>& before = wide_partners_[id];
    std::size_t i = 0;
    std::size_t j = 0;
    while (i < before.size() || j < now.size()) {
      if (j == now.size() || (i < before.size() && before[i] < now[j])) {
        count_pair(id, before[i++], false);
      } else if (i == before.size() || now[j] < before[i]) {
        count_pair(id, now[j++], true);
      } else {
        ++i;
        ++j;
      }
    }
    before.swap(now);
  }
}

// Cells that emptied in this update are counted; once the empty ones outnumber the others (and
// 64), all empty cells are freed for reuse, in index order.
void CellSweepAndPrune::release_empty_cells() {
  for (const std::uint32_t index : changed_cells_) {
    Cell& cell = cells_[index];
    if (cell.sweep.size() == 0 && !cell.empty) {
      cell.empty = true;
      ++empty_cells_;
    }
  }
  changed_cells_.clear();
  if (empty_cells_ <= std::max<std::size_t>(64, cell_of_key_.size() - empty_cells_)) return;
  for (std::uint32_t index = 0; index < cells_.size(); ++index) {
    Cell& cell = cells_[index];
    if (!cell.empty) continue;
    cell.empty = false;
    cell_of_key_.erase(cell_key(cell.coords));
    free_cells_.push_back(index);
  }
  empty_cells_ = 0;
}

void CellSweepAndPrune::count_pair(ProxyId a, ProxyId b, bool entered) {
  const std::uint64_t key = pair_key(a, b);
  if (entered ? counts_.add(key) : counts_.drop(key)) touched_.push_back(key);
}

// pairs_ becomes the pairs counted in some cell.
void CellSweepAndPrune::merge_changes(const Parallel* parallel) {
  std::sort(touched_.begin(), touched_.end());
  touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
  merge_touched_pairs(pairs_, touched_, counts_, merge_, entered_, left_, parallel);
}

}  // namespace sphys
