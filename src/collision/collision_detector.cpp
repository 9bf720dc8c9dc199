#include "collision/collision_detector.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <type_traits>

#include "collision/narrow_chunk.h"
#include "core/buffers.h"
#include "core/stopwatch.h"
#include "sphys/error.h"

namespace sphys {
namespace {

bool finite(const Transform& pose) {
  return pose.translation.allFinite() && pose.rotation.coeffs().allFinite();
}

// World bound of a body from one level's spheres, each grown to its subtree radius so that every
// deeper sphere is inside too.
Aabb world_bounds(const SphereTree& tree, const Transform& pose, int level) {
  const int used = std::min(level, tree.depth() - 1);
  Aabb box;
  for (std::uint32_t node = tree.level_begin(used); node < tree.level_end(used); ++node) {
    box.extend(
        Aabb::around_sphere(pose.apply(tree.sphere(node).center), tree.subtree_radius(node)));
  }
  // Leaves above the level (trees need not be complete) bound parts of the body too.
  for (std::uint32_t node = 0; node < tree.level_begin(used); ++node) {
    if (tree.is_leaf(node)) {
      box.extend(
          Aabb::around_sphere(pose.apply(tree.sphere(node).center), tree.sphere(node).radius));
    }
  }
  return box;
}

// Jobs per run of the narrow phase: enough work per run to outweigh handing it to a thread, and
// runs enough to share among threads.
constexpr std::size_t kPairsPerChunk = 64;
constexpr std::size_t kBodiesPerChunk = 256;

}  // namespace

CollisionDetector::CollisionDetector(const DetectorSettings& settings) : settings_(settings) {
  if (settings.broad_phase == BroadPhaseKind::kCells) broad_phase_.emplace<CellSweepAndPrune>();
  set_settings(settings);
}

void CollisionDetector::set_settings(const DetectorSettings& settings) {
  const BroadPhaseKind kept = settings_.broad_phase;
  settings_ = settings;
  settings_.broad_phase = kept;
  // The bounds level may have changed: every body's bound at its pose again.
  for (std::uint32_t slot = 0; slot < bodies_.size(); ++slot) {
    if (bodies_[slot].tree) bound_at_pose(slot);
  }
  std::visit(
      [&](auto& broad_phase) { broad_phase.set_crowd_limit(settings_.crowd_pairs_per_body); },
      broad_phase_);
}

bool CollisionDetector::crowded(std::uint32_t slot) const {
  return crowd_ &&
         std::visit(
             [&](const auto& broad_phase) { return broad_phase.crowded(bodies_[slot].proxy); },
             broad_phase_);
}
CollisionDetector::~CollisionDetector() = default;

void CollisionDetector::set_bodies(BodyStore& bodies) {
  store_ = &bodies;
  bodies.attach(*this);
}

void CollisionDetector::grow_slots(std::uint32_t slots) {
  bodies_.resize(slots);
  cache_.resize_ground(slots);
}

void CollisionDetector::add_body(std::uint32_t slot, std::shared_ptr<const SphereTree> tree) {
  if (!tree || tree->empty()) throw Error("a body needs a non-empty sphere-tree");
  if (!finite(pose_of(slot))) throw Error("a body's pose must be finite");
  Body& body = bodies_[slot];
  body = Body{};
  body.tree = std::move(tree);
  bound_at_pose(slot);
  const ProxyKind kind = store_->is_static(slot) ? ProxyKind::kStatic : ProxyKind::kDynamic;
  const Aabb box = broad_phase_box(slot);
  body.proxy =
      std::visit([&](auto& broad_phase) { return broad_phase.add(box, kind); }, broad_phase_);
  if (body_of_proxy_.size() <= body.proxy) body_of_proxy_.resize(body.proxy + 1);
  body_of_proxy_[body.proxy] = slot;
  cache_.ground_record(slot) = PairRecord{};
}

void CollisionDetector::remove_body(std::uint32_t slot) {
  Body& body = bodies_[slot];
  std::visit([&](auto& broad_phase) { broad_phase.remove(body.proxy); }, broad_phase_);
  cache_.forget_proxy(body.proxy);
  body = Body{};
  cache_.ground_record(slot) = PairRecord{};
}

void CollisionDetector::paired_bodies(std::uint32_t slot, std::vector<std::uint32_t>& out) const {
  const std::uint32_t proxy = bodies_[slot].proxy;
  for (const PairRecord& record : cache_.records()) {
    if (record.proxies.a == proxy) out.push_back(body_of_proxy_[record.proxies.b]);
    if (record.proxies.b == proxy) out.push_back(body_of_proxy_[record.proxies.a]);
  }
}

void CollisionDetector::bound_at_pose(std::uint32_t slot) {
  Body& body = bodies_[slot];
  body.pose_box = world_bounds(*body.tree, pose_of(slot), settings_.bounds_level);
}

void CollisionDetector::set_motion(std::uint32_t slot, const Vec3& displacement, float turn_reach) {
  Body& body = bodies_[slot];
  body.displacement = displacement;
  body.turn_reach = turn_reach;
}

// The body's bound, grown by half the contact margin (two grown boxes meet when the bodies are
// within the margin) and, with speculative contacts, by how far the body can move this step.
Aabb CollisionDetector::broad_phase_box(std::uint32_t slot) const {
  const Body& body = bodies_[slot];
  float grow = 0.5f * settings_.contact_margin;
  if (settings_.speculative) grow += body.displacement.norm() + body.turn_reach;
  Aabb box = body.pose_box;
  box.min.array() -= grow;
  box.max.array() += grow;
  return box;
}

Aabb CollisionDetector::bounds(std::uint32_t slot) const {
  return std::visit([&](const auto& broad_phase) { return broad_phase.box(bodies_[slot].proxy); },
                    broad_phase_);
}

void CollisionDetector::set_unpaired(
    std::span<const std::pair<std::uint32_t, std::uint32_t>> body_pairs) {
  unpaired_.clear();
  for (const auto& [a, b] : body_pairs) {
    unpaired_.push_back(pair_key(bodies_[a].proxy, bodies_[b].proxy));
  }
  std::sort(unpaired_.begin(), unpaired_.end());
}

bool CollisionDetector::unpaired(const PairRecord& record) const {
  return !unpaired_.empty() && std::binary_search(unpaired_.begin(), unpaired_.end(),
                                                  pair_key(record.proxies.a, record.proxies.b));
}

void CollisionDetector::drop_contacts(PairRecord& record) {
  record.count = 0;
  record.kept_asleep = false;
  record.descent_margin = -1.0f;
  record.done = true;
}

bool CollisionDetector::links_dynamic_bodies(const PairRecord& record) const {
  return record.count > 0 && store_->dynamic()[body_of_proxy_[record.proxies.a]] != 0 &&
         store_->dynamic()[body_of_proxy_[record.proxies.b]] != 0;
}

const CollisionStats& CollisionDetector::detect() {
  stats_ = {};
  stats_.bodies = static_cast<std::uint32_t>(
      std::visit([](const auto& broad_phase) { return broad_phase.size(); }, broad_phase_));

  const PhaseClock broad_clock(parallel_);
  std::visit(
      [&](auto& broad_phase) {
        for (const std::uint32_t slot : store_->awake()) {
          broad_phase.set_box(bodies_[slot].proxy, broad_phase_box(slot));
        }
        if constexpr (std::is_same_v<std::decay_t<decltype(broad_phase)>, CellSweepAndPrune>) {
          broad_phase.update(parallel_);
        } else {
          broad_phase.update();
        }
      },
      broad_phase_);
  const std::span<const ProxyPair> pairs =
      std::visit([](const auto& broad_phase) { return broad_phase.pairs(); }, broad_phase_);
  stats_.pairs_deferred = std::visit(
      [](const auto& broad_phase) { return broad_phase.pairs_deferred(); }, broad_phase_);
  crowd_ =
      std::visit([](const auto& broad_phase) { return broad_phase.has_crowd(); }, broad_phase_);
  if (crowd_) {
    for (const std::uint32_t slot : store_->awake()) stats_.crowded_bodies += crowded(slot) ? 1 : 0;
  }
  stats_.parted_pairs += cache_.follow(
      pairs, [&](const PairRecord& record) { return links_dynamic_bodies(record); }, parallel_);
  stats_.candidate_pairs = static_cast<std::uint32_t>(pairs.size());
  broad_clock.add_to(stats_.broad_phase_ms, stats_.broad_phase_serial_ms);

  cache_.begin_narrow_phase();

  // Pairs with no moving body make no contacts; their records keep the last ones asleep.
  list_jobs();
  cache_.compact_asleep();
  run_jobs(0);
  return stats_;
}

const CollisionStats& CollisionDetector::detect_woken() {
  stats_ = {};
  jobs_.clear();
  const std::span<const PairRecord> records = cache_.records();
  for (std::size_t p = 0; p < records.size(); ++p) {
    const PairRecord& record = records[p];
    if (!record.done &&
        (moves(body_of_proxy_[record.proxies.a]) || moves(body_of_proxy_[record.proxies.b]))) {
      jobs_.push_back({static_cast<std::uint32_t>(p), false});
    }
  }
  pair_jobs_ = jobs_.size();
  if (settings_.ground_plane_height) {
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
      if (!bodies_[i].ground_done && moves(i)) jobs_.push_back({i, true});
    }
  }
  run_jobs(cache_.contacts().size());
  return stats_;
}

// Splits the jobs into runs of fixed length (the same whatever the thread count). A budget is
// shared by the pairs in order: then all pairs are one run.
void CollisionDetector::plan_chunks() {
  chunks_.clear();
  std::size_t pair_used = 0;
  std::size_t plane_used = 0;
  const bool one_run = settings_.has_budget();
  for (std::size_t begin = 0; begin < jobs_.size();) {
    // The pairs' jobs come first, then the plane's.
    const bool plane = begin >= pair_jobs_;
    const std::size_t length = plane ? kBodiesPerChunk : (one_run ? jobs_.size() : kPairsPerChunk);
    const std::size_t end = std::min(begin + length, plane ? jobs_.size() : pair_jobs_);
    // Pair runs and plane runs each keep their own chunks, whose buffers then grow to one kind
    // of work.
    std::vector<std::unique_ptr<NarrowChunk>>& pool = plane ? plane_chunks_ : pair_chunks_;
    std::size_t& used = plane ? plane_used : pair_used;
    if (pool.size() <= used) pool.push_back(std::make_unique<NarrowChunk>());
    NarrowChunk& chunk = *pool[used++];
    chunks_.push_back(&chunk);
    chunk.begin = begin;
    chunk.end = end;
    chunk.leaves.clear();
    chunk.pairs.clear();
    chunk.contacts.clear();
    chunk.shapes.clear();
    chunk.parted_pairs = 0;
    chunk.counters = {};
    chunk.deepest_penetration = 0.0f;
    chunk.penetration_sum = 0.0;
    chunk.penetrating_contacts = 0;
    begin = end;
  }
}

// The narrow phase and the contacts of jobs_, placed in the cache in the jobs' order.
void CollisionDetector::run_jobs(std::size_t base) {
  plan_chunks();
  const auto for_each_chunk = [&](auto&& fn) {
    for_each_on(parallel_, chunks_.size(), [&](std::size_t c) { fn(*chunks_[c]); });
  };

  const PhaseClock narrow_clock(parallel_);
  const StepClock::time_point narrow_start = StepClock::now();  // for the narrow phase's budget
  if (settings_.has_budget()) {
    for (std::size_t c = 0; c < chunks_.size(); ++c) narrow_phase(*chunks_[c], narrow_start);
  } else {
    for_each_chunk([&](NarrowChunk& chunk) { narrow_phase(chunk, narrow_start); });
  }
  narrow_clock.add_to(stats_.narrow_phase_ms, stats_.narrow_phase_serial_ms);

  const PhaseClock contacts_clock(parallel_);
  for_each_chunk([&](NarrowChunk& chunk) { make_contacts(chunk); });
  // Each chunk's contacts follow those of the chunks before it, in the jobs' order.
  std::size_t total = base;
  for (NarrowChunk* chunk : chunks_) {
    chunk->base = total;
    total += chunk->contacts.size();
  }
  cache_.resize(total);
  for_each_chunk([&](NarrowChunk& chunk) { place_contacts(chunk); });
  for (const NarrowChunk* chunk : chunks_) {
    stats_.parted_pairs += chunk->parted_pairs;
    stats_ += chunk->counters;
    stats_.deepest_penetration = std::max(stats_.deepest_penetration, chunk->deepest_penetration);
    stats_.penetration_sum += chunk->penetration_sum;
    stats_.penetrating_contacts += chunk->penetrating_contacts;
  }
  stats_.contacts = static_cast<std::uint32_t>(total);
  contacts_clock.add_to(stats_.contacts_ms, stats_.contacts_serial_ms);
}

// A chunk's contacts and shapes into their place in the detector's, their warm-start memory
// carried there from each record's last contacts, and the records then pointed at them (each
// record is one chunk's, and the last contacts read are the previous narrow phase's or the
// sleeping pairs', never those placed now).
void CollisionDetector::place_contacts(NarrowChunk& chunk) {
  const auto base = static_cast<std::ptrdiff_t>(chunk.base);
  std::copy(chunk.contacts.begin(), chunk.contacts.end(), cache_.contacts().begin() + base);
  std::copy(chunk.shapes.begin(), chunk.shapes.end(), cache_.shapes().begin() + base);
  for (std::size_t k = 0; k < chunk.pairs.size(); ++k) {
    const PairLeaves& pair = chunk.pairs[k];
    const std::size_t end =
        k + 1 < chunk.pairs.size() ? chunk.pairs[k + 1].contacts_begin : chunk.contacts.size();
    const std::size_t count = end - pair.contacts_begin;
    const std::size_t first = chunk.base + pair.contacts_begin;
    cache_.carry_memory(*pair.record, cache_.contacts().subspan(first, count),
                        cache_.memory().subspan(first, count));
    if (!pair.plane && count == 0 && links_dynamic_bodies(*pair.record)) ++chunk.parted_pairs;
    pair.record->first = static_cast<std::uint32_t>(first);
    pair.record->count = static_cast<std::uint32_t>(count);
    pair.record->kept_asleep = false;
  }
}

}  // namespace sphys
