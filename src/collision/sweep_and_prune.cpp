#include "collision/sweep_and_prune.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <iterator>
#include <limits>

namespace sphys {
namespace {

// An endpoint is one 64-bit key, so that the sort compares integers only:
//   bits 63..32  the coordinate, as a float mapped to an unsigned integer of the same order
//   bit  31      1 for a max endpoint, 0 for a min endpoint
//   bits 30..0   the proxy id
// At equal coordinates a min sorts before a max: intervals that touch overlap, as in
// Aabb::overlaps. Ties between two mins or two maxes fall to the id, so the sorted order is a
// function of the boxes alone, whatever the history.
constexpr std::uint64_t kMaxBit = std::uint64_t{1} << 31;
constexpr std::uint64_t kIdMask = kMaxBit - 1;

// Flags per id.
constexpr std::uint8_t kAlive = 1;    // added and not removed
constexpr std::uint8_t kWaiting = 2;  // added since the last update(): no endpoints yet
constexpr std::uint8_t kStatic = 4;

// Up to this many adds in one update() are inserted one by one (O(n) each: endpoint insertion
// and a brute-force search for the new pairs); more rebuild everything (O(n log n) sort and one
// sweep), which is what a scene's first update() does.
constexpr std::size_t kMaxIncrementalAdds = 64;

// The two axes other than `axis`.
constexpr int kOtherAxis[3][2] = {{1, 2}, {2, 0}, {0, 1}};

// IEEE-754 floats of one sign compare like their bit patterns read as integers (larger magnitude,
// larger pattern); flipping the sign bit of positives and every bit of negatives orders all
// finite floats as unsigned integers. Adding +0 first turns -0 into +0, which compare equal as
// floats and must give equal keys.
std::uint32_t ordered_bits(float value) {
  const auto bits = std::bit_cast<std::uint32_t>(value + 0.0f);
  return (bits & 0x80000000u) != 0 ? ~bits : bits | 0x80000000u;
}

std::uint64_t endpoint_key(float value, std::uint64_t kind_and_id) {
  return std::uint64_t{ordered_bits(value)} << 32 | kind_and_id;
}

ProxyId endpoint_id(std::uint64_t key) { return static_cast<ProxyId>(key & kIdMask); }
bool is_max(std::uint64_t key) { return (key & kMaxBit) != 0; }

// Closed-interval overlap of two boxes on two axes (the third is the one being swept).
bool overlap_on(const BoxBounds& p, const BoxBounds& q, int u, int v) {
  return p[u] <= q[u + 3] && q[u] <= p[u + 3] && p[v] <= q[v + 3] && q[v] <= p[v + 3];
}

BoxBounds to_bounds(const Aabb& box) {
  return {box.min.x(), box.min.y(), box.min.z(), box.max.x(), box.max.y(), box.max.z()};
}

}  // namespace

ProxyId SweepAndPrune::add(const Aabb& box, ProxyKind kind) {
  check_proxy_box(box);
  const ProxyId id = take_proxy_id(free_ids_, bounds_.size());
  if (id == bounds_.size()) {
    bounds_.emplace_back();
    for (auto& intervals : intervals_) intervals.emplace_back();
    flags_.push_back(0);
  }
  store(id, box);
  flags_[id] = kAlive | kWaiting | (kind == ProxyKind::kStatic ? kStatic : 0);
  waiting_.push_back(id);
  ++live_count_;
  return id;
}

void SweepAndPrune::remove(ProxyId id) {
  assert(id < flags_.size() && (flags_[id] & kAlive) != 0);
  flags_[id] = 0;
  retired_.push_back(id);
  --live_count_;
}

void SweepAndPrune::set_box(ProxyId id, const Aabb& box) {
  assert(id < flags_.size() && (flags_[id] & kAlive) != 0);
  assert(box.min.allFinite() && box.max.allFinite() && !box.empty());
  store(id, box);
}

void SweepAndPrune::store(ProxyId id, const Aabb& box) {
  bounds_[id].now = to_bounds(box);
  for (int axis = 0; axis < 3; ++axis) intervals_[axis][id] = {box.min[axis], box.max[axis]};
}

Aabb SweepAndPrune::box(ProxyId id) const {
  const BoxBounds& b = bounds_[id].now;
  return {Vec3(b[0], b[1], b[2]), Vec3(b[3], b[4], b[5])};
}

void SweepAndPrune::update() {
  swaps_last_update_ = 0;
  entered_.clear();
  left_.clear();
  if (crowd_.found() || waiting_.size() > kMaxIncrementalAdds) {
    rebuild();
  } else {
    drop_removed_pairs();
    for (int axis = 0; axis < 3; ++axis) sort_axis(axis);
    integrate_added();
    merge_changes();
    // Boxes moved or were added into a pile: listed whole, the pairs are past the limit.
    if (crowd_.overflows(pairs_.size(), live_count_)) {
      undo_changes();
      rebuild();
    }
  }
  for (Bounds& b : bounds_) b.before = b.now;
  waiting_.clear();
  // The endpoints of removed proxies are gone now, so their ids may be given out again.
  free_ids_.insert(free_ids_.end(), retired_.begin(), retired_.end());
  retired_.clear();
}

// Pairs of removed proxies leave the set before the sort, which skips their endpoints.
void SweepAndPrune::drop_removed_pairs() {
  if (retired_.empty()) return;
  for (const ProxyPair& pair : pairs_) {
    if ((flags_[pair.a] & kAlive) == 0 || (flags_[pair.b] & kAlive) == 0) {
      const std::uint64_t key = pair_key(pair);
      pair_set_.erase(key);
      removed_.push_back(key);
    }
  }
}

// Insertion sort of one axis with fresh coordinates (Cohen et al. 1995; Ericson §7.5):
// each endpoint takes its current value and moves left past every larger endpoint. Each swap is
// one inversion between the old and the new order, and only a swap of a min with a max changes
// whether two intervals overlap. Endpoints of removed proxies are dropped on the way.
void SweepAndPrune::sort_axis(int axis) {
  std::vector<std::uint64_t>& keys = endpoints_[axis];
  const std::vector<std::array<float, 2>>& intervals = intervals_[axis];
  const bool any_removed = !retired_.empty();
  std::size_t kept = 0;
  std::uint64_t swaps = 0;
  for (const std::uint64_t old_key : keys) {
    const ProxyId id = endpoint_id(old_key);
    if (any_removed && (flags_[id] & kAlive) == 0) continue;
    const bool moving_max = is_max(old_key);
    const std::uint64_t key =
        endpoint_key(intervals[id][moving_max ? 1 : 0], old_key & (kMaxBit | kIdMask));
    std::size_t j = kept;
    while (j > 0 && keys[j - 1] > key) {
      const std::uint64_t passed = keys[j - 1];
      if (is_max(passed) != moving_max) {
        if (moving_max) {
          on_max_passes_min(axis, id, endpoint_id(passed));
        } else {
          on_min_passes_max(axis, id, endpoint_id(passed));
        }
      }
      keys[j] = passed;
      --j;
    }
    keys[j] = key;
    swaps += kept - j;
    ++kept;
  }
  keys.resize(kept);
  swaps_last_update_ += swaps;
}

// A min moving left past another box's max: the intervals start to overlap on this axis, so the
// boxes overlap if they do on the other two (read from the stored boxes, which are already the
// new ones). If they do not overlap on this axis after all (a jump past the whole interval), the
// box's own max passes the other's min later in the same sort and removes the pair again.
void SweepAndPrune::on_min_passes_max(int axis, ProxyId a, ProxyId b) {
  if (a == b) return;  // only a box with min > max, which set_box() asserts against
  if ((flags_[a] & flags_[b] & kStatic) != 0) return;
  if (!overlap_on(bounds_[a].now, bounds_[b].now, kOtherAxis[axis][0], kOtherAxis[axis][1])) return;
  const std::uint64_t key = pair_key(a, b);
  if (pair_set_.insert(key)) added_.push_back(key);
}

// A max moving left past another box's min: the intervals no longer overlap on this axis, and the
// pair leaves the set if it is there. Most such swaps are of boxes far apart on another axis, so
// the set is probed only for a pair that can be in it: one that overlapped on the other two axes
// at the last update() (every pair then in the set did), or overlaps on them now (a pair added
// during this update() and not removed since does: its add checked the axes other than its own,
// and a pass that keeps a pair leaves it overlapping on that pass's axis).
void SweepAndPrune::on_max_passes_min(int axis, ProxyId a, ProxyId b) {
  if (a == b) return;
  const Bounds& p = bounds_[a];
  const Bounds& q = bounds_[b];
  const int u = kOtherAxis[axis][0];
  const int v = kOtherAxis[axis][1];
  if (!overlap_on(p.now, q.now, u, v) && !overlap_on(p.before, q.before, u, v)) return;
  const std::uint64_t key = pair_key(a, b);
  if (pair_set_.erase(key)) removed_.push_back(key);
}

// Few adds: each new proxy's endpoints go in at their sorted places and its pairs are found by
// testing it against every proxy already in (earlier new ones included, later ones will test it).
void SweepAndPrune::integrate_added() {
  for (const ProxyId id : waiting_) {
    if ((flags_[id] & kAlive) == 0) continue;
    const BoxBounds& b = bounds_[id].now;
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<std::uint64_t>& keys = endpoints_[axis];
      for (const std::uint64_t key :
           {endpoint_key(b[axis], id), endpoint_key(b[axis + 3], kMaxBit | id)}) {
        keys.insert(std::lower_bound(keys.begin(), keys.end(), key), key);
      }
    }
    flags_[id] &= static_cast<std::uint8_t>(~kWaiting);
    const bool is_static = (flags_[id] & kStatic) != 0;
    for (ProxyId other = 0; other < bounds_.size(); ++other) {
      const std::uint8_t f = flags_[other];
      if ((f & (kAlive | kWaiting)) != kAlive || other == id) continue;
      if (is_static && (f & kStatic) != 0) continue;
      if (!boxes_overlap(b, bounds_[other].now)) continue;
      const std::uint64_t key = pair_key(id, other);
      if (pair_set_.insert(key)) added_.push_back(key);
    }
  }
}

// pairs_ becomes (pairs_ + added_) without the keys that are no longer in the set. Only keys
// touched in this update() are looked up; the rest are copied, so the cost is O(m + k log k) for
// k changes, and nothing at all when nothing changed.
void SweepAndPrune::merge_changes() {
  added_.insert(added_.end(), removed_.begin(), removed_.end());
  std::sort(added_.begin(), added_.end());
  added_.erase(std::unique(added_.begin(), added_.end()), added_.end());
  merge_touched_pairs(pairs_, added_, pair_set_, merge_, entered_, left_, nullptr);
  added_.clear();
  removed_.clear();
}

void SweepAndPrune::undo_changes() {
  merge_.merged.clear();
  std::set_difference(pairs_.begin(), pairs_.end(), entered_.begin(), entered_.end(),
                      std::back_inserter(merge_.merged));
  pairs_.clear();
  std::merge(merge_.merged.begin(), merge_.merged.end(), left_.begin(), left_.end(),
             std::back_inserter(pairs_));
  entered_.clear();
  left_.clear();
}

// The boxes whose interval on `axis` is open as the sorted endpoints pass, each opening box
// tested against them: O(p) for p overlapping intervals on that axis, less when `found` stops it
// by returning false.
template <class Found>
void SweepAndPrune::sweep(int axis, const Found& found) const {
  // The open boxes, with their bounds on the other two axes copied so that the inner loop reads
  // one array.
  struct Open {
    float min_u, max_u, min_v, max_v;
    ProxyId id;
    bool is_static;
  };
  const int u = kOtherAxis[axis][0];
  const int v = kOtherAxis[axis][1];
  std::vector<Open> open;
  std::vector<std::uint32_t> open_slot(bounds_.size());
  for (const std::uint64_t key : endpoints_[axis]) {
    const ProxyId id = endpoint_id(key);
    if (is_max(key)) {
      const std::uint32_t slot = open_slot[id];
      open[slot] = open.back();
      open_slot[open[slot].id] = slot;
      open.pop_back();
      continue;
    }
    const BoxBounds& b = bounds_[id].now;
    const Open box{b[u], b[u + 3], b[v], b[v + 3], id, (flags_[id] & kStatic) != 0};
    for (const Open& other : open) {
      if (box.min_u <= other.max_u && other.min_u <= box.max_u && box.min_v <= other.max_v &&
          other.min_v <= box.max_v && !(box.is_static && other.is_static) &&
          !found(pair_key(id, other.id))) {
        return;
      }
    }
    open_slot[id] = static_cast<std::uint32_t>(open.size());
    open.push_back(box);
  }
}

struct SweepAndPrune::CrowdBoxes {
  const SweepAndPrune& boxes;
  int axis = 0;

  [[nodiscard]] std::size_t ids() const { return boxes.bounds_.size(); }
  [[nodiscard]] std::size_t live() const { return boxes.live_count_; }
  [[nodiscard]] bool alive(ProxyId id) const { return (boxes.flags_[id] & kAlive) != 0; }
  [[nodiscard]] bool is_static(ProxyId id) const { return (boxes.flags_[id] & kStatic) != 0; }
  [[nodiscard]] const BoxBounds& bounds(ProxyId id) const { return boxes.bounds_[id].now; }
  template <class Found>
  void sweep(const Found& found) const {
    boxes.sweep(axis, found);
  }
};

// Many adds: sort every axis from scratch and find all pairs with one sweep along the axis on
// which the fewest intervals overlap (counted in O(n) from the sorted endpoints). The sweep keeps
// the boxes whose interval is open and tests each opening box against them: O(n log n + p) for p
// overlapping intervals on that axis.
void SweepAndPrune::rebuild() {
  for (std::vector<std::uint64_t>& keys : endpoints_) keys.clear();
  for (ProxyId id = 0; id < bounds_.size(); ++id) {
    if ((flags_[id] & kAlive) == 0) continue;
    flags_[id] &= static_cast<std::uint8_t>(~kWaiting);
    for (int axis = 0; axis < 3; ++axis) {
      endpoints_[axis].push_back(endpoint_key(bounds_[id].now[axis], id));
      endpoints_[axis].push_back(endpoint_key(bounds_[id].now[axis + 3], kMaxBit | id));
    }
  }
  int sweep_axis = 0;
  std::uint64_t fewest = std::numeric_limits<std::uint64_t>::max();
  for (int axis = 0; axis < 3; ++axis) {
    std::sort(endpoints_[axis].begin(), endpoints_[axis].end());
    std::uint64_t open = 0;
    std::uint64_t overlapping = 0;
    for (const std::uint64_t key : endpoints_[axis]) {
      if (is_max(key)) {
        --open;
      } else {
        overlapping += open;
        ++open;
      }
    }
    if (overlapping < fewest) {
      fewest = overlapping;
      sweep_axis = axis;
    }
  }

  added_.clear();
  crowd_.list(CrowdBoxes{*this, sweep_axis}, added_);

  std::sort(added_.begin(), added_.end());
  pair_set_.clear();
  merge_.merged.clear();
  for (const std::uint64_t key : added_) {
    pair_set_.insert(key);
    merge_.merged.push_back(pair_of(key));
  }
  std::set_difference(merge_.merged.begin(), merge_.merged.end(), pairs_.begin(), pairs_.end(),
                      std::back_inserter(entered_));
  std::set_difference(pairs_.begin(), pairs_.end(), merge_.merged.begin(), merge_.merged.end(),
                      std::back_inserter(left_));
  pairs_.swap(merge_.merged);
  added_.clear();
  removed_.clear();
}

}  // namespace sphys
