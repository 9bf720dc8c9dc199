#include "sphys/collision_detector.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <type_traits>

#include "collision/contact_reduction.h"
#include "core/buffers.h"
#include "core/stopwatch.h"
#include "sphys/error.h"

namespace sphys {
namespace {

bool finite(const Transform& pose) {
  return pose.translation.allFinite() && pose.rotation.coeffs().allFinite();
}

// The last level used of a tree: its nodes are the leaves.
int last_level(const SphereTree& tree, int tree_depth) {
  return (tree_depth <= 0 || tree_depth > tree.depth()) ? tree.depth() - 1 : tree_depth - 1;
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

// Body b's pose in body a's frame.
Transform relative_pose(const Transform& a, const Transform& b) {
  const Quat inverse = a.rotation.conjugate();
  return {inverse * b.rotation, inverse * (b.translation - a.translation)};
}

// How far any point of a body within `extent` of its origin can have moved between two of its
// poses (relative ones here): the origin's move plus the turn's reach. unit: m
float pose_change(const Transform& from, const Transform& to, float extent) {
  Quat turn = from.rotation.conjugate() * to.rotation;
  const float angle = 2.0f * std::atan2(turn.vec().norm(), std::abs(turn.w()));
  return (to.translation - from.translation).norm() + angle * extent;
}

// Jobs per run of the narrow phase: enough work per run to outweigh handing it to a thread, and
// runs enough to share among threads.
constexpr std::size_t kPairsPerChunk = 64;
constexpr std::size_t kBodiesPerChunk = 256;

}  // namespace

struct CollisionDetector::NarrowChunk {
  std::size_t begin = 0;  // jobs
  std::size_t end = 0;
  TreeDescent descent;
  ContactReducer reducer;
  std::vector<NodePair> node_pairs;
  std::vector<std::uint32_t> plane_stack;
  std::vector<LeafSpheres> leaves;
  std::vector<PairLeaves> pairs;
  std::vector<Contact> run;  // one pair's leaf contacts, before reduction
  std::vector<Contact> contacts;
  std::vector<ContactShape> shapes;
  std::size_t base = 0;  // where its contacts start in contacts_
  std::uint32_t parted_pairs = 0;
  std::uint64_t sphere_tests = 0;
  std::uint32_t leaf_pairs = 0;
  std::uint32_t cut_short_pairs = 0;
  std::uint32_t coincident_centres = 0;
  std::uint32_t descended_pairs = 0;
  std::uint32_t reused_pairs = 0;
  float deepest_penetration = 0.0f;
  double penetration_sum = 0.0;
  std::uint32_t penetrating_contacts = 0;
};

CollisionDetector::CollisionDetector(const CollisionSettings& settings) : settings_(settings) {
  if (settings.broad_phase == BroadPhaseKind::kCells) broad_phase_.emplace<CellSweepAndPrune>();
}
CollisionDetector::~CollisionDetector() = default;
CollisionDetector::CollisionDetector(CollisionDetector&&) noexcept = default;
CollisionDetector& CollisionDetector::operator=(CollisionDetector&&) noexcept = default;

void CollisionDetector::add_body(std::uint32_t slot, std::shared_ptr<const SphereTree> tree) {
  if (!tree || tree->empty()) throw Error("a body needs a non-empty sphere-tree");
  if (!finite(pose_of(slot))) throw Error("a body's pose must be finite");
  if (bodies_.size() <= slot) {
    bodies_.resize(slot + 1);
    ground_records_.resize(slot + 1);
  }
  Body& body = bodies_[slot];
  body = Body{};
  body.tree = std::move(tree);
  const ProxyKind kind = store_->is_static(slot) ? ProxyKind::kStatic : ProxyKind::kDynamic;
  const Aabb box = broad_phase_box(slot);
  body.proxy =
      std::visit([&](auto& broad_phase) { return broad_phase.add(box, kind); }, broad_phase_);
  if (body_of_proxy_.size() <= body.proxy) body_of_proxy_.resize(body.proxy + 1);
  body_of_proxy_[body.proxy] = slot;
  ground_records_[slot] = PairRecord{};
}

void CollisionDetector::remove_body(std::uint32_t slot) {
  Body& body = bodies_[slot];
  std::visit([&](auto& broad_phase) { broad_phase.remove(body.proxy); }, broad_phase_);
  // The broad phase drops its pairs at the next update; until then they must not be reused.
  for (PairRecord& record : records_) {
    if (record.proxies.a == body.proxy || record.proxies.b == body.proxy) {
      record.descent_margin = -1.0f;
      record.count = 0;
    }
  }
  body = Body{};
  ground_records_[slot] = PairRecord{};
}

void CollisionDetector::paired_bodies(std::uint32_t slot, std::vector<std::uint32_t>& out) const {
  const std::uint32_t proxy = bodies_[slot].proxy;
  for (const PairRecord& record : records_) {
    if (record.proxies.a == proxy) out.push_back(body_of_proxy_[record.proxies.b]);
    if (record.proxies.b == proxy) out.push_back(body_of_proxy_[record.proxies.a]);
  }
}

void CollisionDetector::set_motion(std::uint32_t slot, const Vec3& displacement, float turn_reach) {
  Body& body = bodies_[slot];
  body.displacement = displacement;
  body.turn_reach = turn_reach;
}

bool CollisionDetector::budget() const {
  return settings_.max_sphere_tests > 0 || settings_.max_microseconds > 0.0;
}

// The body's bound, grown by half the contact margin (two grown boxes meet when the bodies are
// within the margin) and, with speculative contacts, by how far the body can move this step.
Aabb CollisionDetector::broad_phase_box(std::uint32_t slot) const {
  const Body& body = bodies_[slot];
  float grow = 0.5f * settings_.contact_margin;
  if (settings_.speculative) grow += body.displacement.norm() + body.turn_reach;
  Aabb box = world_bounds(*body.tree, pose_of(slot), settings_.bounds_level);
  box.min.array() -= grow;
  box.max.array() += grow;
  return box;
}

// The gap up to which two bodies' spheres make contacts: the margin plus, with speculative
// contacts, a bound on how much closer any two of their points can come in the step.
float CollisionDetector::pair_margin(const Body& a, const Body& b) const {
  if (!settings_.speculative) return settings_.contact_margin;
  return settings_.contact_margin + (b.displacement - a.displacement).norm() + a.turn_reach +
         b.turn_reach;
}

float CollisionDetector::plane_margin(const Body& body) const {
  if (!settings_.speculative) return settings_.contact_margin;
  return settings_.contact_margin + std::max(-body.displacement.y(), 0.0f) + body.turn_reach;
}

Aabb CollisionDetector::bounds(std::uint32_t slot) const {
  return std::visit([&](const auto& broad_phase) { return broad_phase.box(bodies_[slot].proxy); },
                    broad_phase_);
}

// Broad-phase pairs per item of the threaded merge of the pair records. unit: pairs
constexpr std::size_t kRecordsPerRun = 1024;

// The records follow the broad phase's pairs, both sorted by proxies: a pair still listed keeps
// its record, a new pair gets an empty one, and the records of pairs gone are dropped. The pairs
// are merged in runs on the threads, each run with the old records of its keys (the first run also
// those below, the last those above).
void CollisionDetector::carry_records_over() {
  old_records_.swap(records_);
  const std::span<const ProxyPair> pairs =
      std::visit([](const auto& broad_phase) { return broad_phase.pairs(); }, broad_phase_);
  resize_buffer(records_, pairs.size());
  // The first old record at or after pair p's key.
  const auto first_old = [&](std::size_t p) -> std::size_t {
    if (p == 0) return 0;
    if (p == pairs.size()) return old_records_.size();
    const std::uint64_t key = pair_key(pairs[p]);
    return static_cast<std::size_t>(
        std::partition_point(old_records_.begin(), old_records_.end(),
                             [&](const PairRecord& r) { return pair_key(r.proxies) < key; }) -
        old_records_.begin());
  };
  const std::size_t runs =
      std::max<std::size_t>(1, (pairs.size() + kRecordsPerRun - 1) / kRecordsPerRun);
  fill_buffer(parted_in_run_, runs, 0u);
  for_each_item(runs, [&](std::size_t run) {
    const std::size_t begin = run * kRecordsPerRun;
    const std::size_t end = std::min(pairs.size(), begin + kRecordsPerRun);
    std::size_t old = first_old(begin);
    const std::size_t old_end = first_old(end);
    const auto drop = [&](const PairRecord& record) {
      if (links_dynamic_bodies(record)) ++parted_in_run_[run];
    };
    for (std::size_t p = begin; p < end; ++p) {
      const std::uint64_t key = pair_key(pairs[p]);
      while (old < old_end && pair_key(old_records_[old].proxies) < key) {
        drop(old_records_[old++]);
      }
      if (old < old_end && pair_key(old_records_[old].proxies) == key) {
        records_[p] = old_records_[old++];
      } else {
        records_[p] = PairRecord{};
        records_[p].proxies = pairs[p];
      }
    }
    for (; old < old_end; ++old) drop(old_records_[old]);
  });
  for (const std::uint32_t parted : parted_in_run_) stats_.parted_pairs += parted;
}

bool CollisionDetector::links_dynamic_bodies(const PairRecord& record) const {
  return record.count > 0 && store_->dynamic()[body_of_proxy_[record.proxies.a]] != 0 &&
         store_->dynamic()[body_of_proxy_[record.proxies.b]] != 0;
}

const CollisionStats& CollisionDetector::detect() {
  stats_ = {};
  stats_.bodies = static_cast<std::uint32_t>(
      std::visit([](const auto& broad_phase) { return broad_phase.size(); }, broad_phase_));

  const StepClock::time_point broad_start = StepClock::now();
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
  carry_records_over();
  stats_.candidate_pairs = static_cast<std::uint32_t>(records_.size());
  stats_.broad_phase_ms = elapsed_ms(broad_start);

  previous_contacts_.swap(contacts_);
  previous_memory_.swap(memory_);
  previous_shapes_.swap(shapes_);
  // run_jobs overwrites contacts_, memory_ and shapes_ from the start and sizes them: not cleared
  // here, what they held is not zeroed first.

  // Pairs with no moving body make no contacts; their records keep the last ones asleep.
  jobs_.clear();
  live_asleep_ = 0;
  for (std::size_t p = 0; p < records_.size(); ++p) {
    PairRecord& record = records_[p];
    record.done = false;
    if (moves(body_of_proxy_[record.proxies.a]) || moves(body_of_proxy_[record.proxies.b])) {
      jobs_.push_back({static_cast<std::uint32_t>(p), false});
    } else {
      keep_asleep(record);
    }
  }
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    bodies_[i].ground_done = false;
    if (!settings_.ground_plane_height) continue;
    if (moves(i)) {
      jobs_.push_back({i, true});
    } else if (store_->alive(i)) {
      keep_asleep(ground_records_[i]);
    }
  }
  compact_asleep();
  run_jobs(0);
  return stats_;
}

// Appends a record's contacts and their memory from one store to another; returns where they
// begin there.
std::uint32_t CollisionDetector::append_range(const std::vector<Contact>& contacts,
                                              const std::vector<ContactMemory>& memory,
                                              const PairRecord& record,
                                              std::vector<Contact>& to_contacts,
                                              std::vector<ContactMemory>& to_memory) {
  const auto first = static_cast<std::uint32_t>(to_contacts.size());
  const auto begin = static_cast<std::ptrdiff_t>(record.first);
  const auto end = begin + static_cast<std::ptrdiff_t>(record.count);
  to_contacts.insert(to_contacts.end(), contacts.begin() + begin, contacts.begin() + end);
  to_memory.insert(to_memory.end(), memory.begin() + begin, memory.begin() + end);
  return first;
}

void CollisionDetector::keep_asleep(PairRecord& record) {
  // Kept contacts are matched again by leaf pair only: the pair descends anew when it wakes.
  record.descent_margin = -1.0f;
  if (!record.kept_asleep) {
    record.first = append_range(previous_contacts_, previous_memory_, record, asleep_contacts_,
                                asleep_memory_);
    record.kept_asleep = true;
  }
  live_asleep_ += record.count;
}

// Once less than half of the store is live, it is rebuilt from the live records.
void CollisionDetector::compact_asleep() {
  if (2 * live_asleep_ >= asleep_contacts_.size()) return;
  compacted_contacts_.clear();
  compacted_memory_.clear();
  const auto move = [&](PairRecord& record) {
    if (!record.kept_asleep) return;
    record.first = append_range(asleep_contacts_, asleep_memory_, record, compacted_contacts_,
                                compacted_memory_);
  };
  for (PairRecord& record : records_) move(record);
  for (PairRecord& record : ground_records_) move(record);
  asleep_contacts_.swap(compacted_contacts_);
  asleep_memory_.swap(compacted_memory_);
}

// The record's contacts of its last narrow phase (a record that had none, none).
std::span<const Contact> CollisionDetector::last_contacts(const PairRecord& record) const {
  if (record.count == 0) return {};
  const std::vector<Contact>& from = record.kept_asleep ? asleep_contacts_ : previous_contacts_;
  return std::span<const Contact>(from).subspan(record.first, record.count);
}

std::span<const ContactMemory> CollisionDetector::last_memory(const PairRecord& record) const {
  if (record.count == 0) return {};
  const std::vector<ContactMemory>& from = record.kept_asleep ? asleep_memory_ : previous_memory_;
  return std::span<const ContactMemory>(from).subspan(record.first, record.count);
}

const CollisionStats& CollisionDetector::detect_woken() {
  stats_ = {};
  jobs_.clear();
  for (std::size_t p = 0; p < records_.size(); ++p) {
    const PairRecord& record = records_[p];
    if (!record.done &&
        (moves(body_of_proxy_[record.proxies.a]) || moves(body_of_proxy_[record.proxies.b]))) {
      jobs_.push_back({static_cast<std::uint32_t>(p), false});
    }
  }
  if (settings_.ground_plane_height) {
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
      if (!bodies_[i].ground_done && moves(i)) jobs_.push_back({i, true});
    }
  }
  run_jobs(contacts_.size());
  return stats_;
}

// Splits the jobs into runs of fixed length (the same whatever the thread count). A budget is
// shared by the pairs in order: then all pairs are one run.
void CollisionDetector::plan_chunks() {
  chunks_.clear();
  std::size_t pair_used = 0;
  std::size_t plane_used = 0;
  const bool one_run = budget();
  for (std::size_t begin = 0; begin < jobs_.size();) {
    const bool plane = jobs_[begin].plane;
    const std::size_t length = plane ? kBodiesPerChunk : (one_run ? jobs_.size() : kPairsPerChunk);
    std::size_t end = begin;
    while (end < jobs_.size() && end - begin < length && jobs_[end].plane == plane) ++end;
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
    chunk.sphere_tests = 0;
    chunk.leaf_pairs = 0;
    chunk.cut_short_pairs = 0;
    chunk.coincident_centres = 0;
    chunk.descended_pairs = 0;
    chunk.reused_pairs = 0;
    chunk.deepest_penetration = 0.0f;
    chunk.penetration_sum = 0.0;
    chunk.penetrating_contacts = 0;
    begin = end;
  }
}

// The narrow phase and the contacts of jobs_, appended to contacts_ in the jobs' order.
void CollisionDetector::run_jobs(std::size_t base) {
  plan_chunks();
  const auto for_each_chunk = [&](auto&& fn) {
    for_each_item(chunks_.size(), [&](std::size_t c) { fn(*chunks_[c]); });
  };

  const StepClock::time_point narrow_start = StepClock::now();
  if (budget()) {
    for (std::size_t c = 0; c < chunks_.size(); ++c) narrow_phase(*chunks_[c], narrow_start);
  } else {
    for_each_chunk([&](NarrowChunk& chunk) { narrow_phase(chunk, narrow_start); });
  }
  stats_.narrow_phase_ms = elapsed_ms(narrow_start);

  const StepClock::time_point contacts_start = StepClock::now();
  for_each_chunk([&](NarrowChunk& chunk) { make_contacts(chunk); });
  // Each chunk's contacts follow those of the chunks before it, in the jobs' order.
  std::size_t total = base;
  for (NarrowChunk* chunk : chunks_) {
    chunk->base = total;
    total += chunk->contacts.size();
  }
  resize_buffer(contacts_, total);
  resize_buffer(shapes_, total);
  resize_buffer(memory_, total);
  for_each_chunk([&](NarrowChunk& chunk) { place_contacts(chunk); });
  for (const NarrowChunk* chunk : chunks_) {
    stats_.parted_pairs += chunk->parted_pairs;
    stats_.sphere_tests += chunk->sphere_tests;
    stats_.leaf_pairs += chunk->leaf_pairs;
    stats_.pairs_cut_short += chunk->cut_short_pairs;
    stats_.coincident_centres += chunk->coincident_centres;
    stats_.descended_pairs += chunk->descended_pairs;
    stats_.reused_pairs += chunk->reused_pairs;
    stats_.deepest_penetration = std::max(stats_.deepest_penetration, chunk->deepest_penetration);
    stats_.penetration_sum += chunk->penetration_sum;
    stats_.penetrating_contacts += chunk->penetrating_contacts;
  }
  stats_.contacts = static_cast<std::uint32_t>(contacts_.size());
  stats_.contacts_ms = elapsed_ms(contacts_start);
}

// Each new contact takes the memory of the contact of the same leaf pair among the record's
// contacts of the last narrow phase. Both come in the descent's order mostly, so the search
// starts after the last match.
void CollisionDetector::carry_memory(const PairRecord& record, std::span<const Contact> contacts,
                                     std::span<ContactMemory> memory) const {
  const std::span<const Contact> old_contacts = last_contacts(record);
  const std::span<const ContactMemory> old_memory = last_memory(record);
  const std::size_t old_count = old_contacts.size();
  std::size_t hint = 0;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Contact& contact = contacts[c];
    memory[c] = ContactMemory{};
    for (std::size_t tried = 0; tried < old_count; ++tried) {
      const std::size_t i = (hint + tried) % old_count;
      const Contact& old = old_contacts[i];
      if (old.leaf_a == contact.leaf_a && old.leaf_b == contact.leaf_b) {
        memory[c] = old_memory[i];
        hint = i + 1;
        break;
      }
    }
  }
}

// A chunk's contacts and shapes into their place in the detector's, their warm-start memory
// carried there from each record's last contacts, and the records then pointed at them (each
// record is one chunk's, and the last contacts read are the previous narrow phase's or the
// sleeping pairs', never those placed now).
void CollisionDetector::place_contacts(NarrowChunk& chunk) {
  const auto base = static_cast<std::ptrdiff_t>(chunk.base);
  std::copy(chunk.contacts.begin(), chunk.contacts.end(), contacts_.begin() + base);
  std::copy(chunk.shapes.begin(), chunk.shapes.end(), shapes_.begin() + base);
  for (std::size_t k = 0; k < chunk.pairs.size(); ++k) {
    const PairLeaves& pair = chunk.pairs[k];
    const std::size_t end =
        k + 1 < chunk.pairs.size() ? chunk.pairs[k + 1].contacts_begin : chunk.contacts.size();
    const std::size_t count = end - pair.contacts_begin;
    const std::size_t first = chunk.base + pair.contacts_begin;
    carry_memory(*pair.record, std::span<const Contact>(contacts_).subspan(first, count),
                 std::span<ContactMemory>(memory_).subspan(first, count));
    if (!pair.plane && count == 0 && links_dynamic_bodies(*pair.record)) ++chunk.parted_pairs;
    pair.record->first = static_cast<std::uint32_t>(first);
    pair.record->count = static_cast<std::uint32_t>(count);
    pair.record->kept_asleep = false;
  }
}

// What is left of the time-critical budgets after `spent_microseconds` and `spent_tests` sphere
// tests in this call.
DescentSettings CollisionDetector::descent_budget(double spent_microseconds,
                                                  std::uint64_t spent_tests, float margin) const {
  DescentSettings descent;
  descent.margin = margin;
  descent.depth_a = settings_.tree_depth;
  descent.depth_b = settings_.tree_depth;
  // A budget that is on never reaches 0 (which would mean "off"): a pair met after the budget
  // is spent is resolved at its roots.
  if (settings_.max_sphere_tests > 0) {
    descent.max_sphere_tests =
        settings_.max_sphere_tests > spent_tests ? settings_.max_sphere_tests - spent_tests : 1;
  }
  if (settings_.max_microseconds > 0.0) {
    descent.max_microseconds = std::max(settings_.max_microseconds - spent_microseconds, 1e-3);
  }
  return descent;
}

void CollisionDetector::narrow_phase(NarrowChunk& chunk, StepClock::time_point start) {
  for (std::size_t j = chunk.begin; j < chunk.end; ++j) pair_leaves(jobs_[j], chunk, start);
}

// A pair whose bodies barely moved relative to each other since its last descent, within the gap
// that descent looked up to, keeps its leaf pairs: they are placed at the new poses.
bool CollisionDetector::reuse(PairRecord& record, const Transform& relative, float margin,
                              float extent_b, std::uint32_t body_a, std::uint32_t body_b,
                              NarrowChunk& chunk) {
  if (settings_.reuse_distance <= 0.0f || budget() || record.descent_margin < 0.0f) return false;
  const float moved = pose_change(record.relative, relative, extent_b);
  if (!(moved <= settings_.reuse_distance && margin + moved <= record.descent_margin)) {
    return false;
  }
  const Body& b = bodies_[body_b];
  for (std::uint32_t i = record.first; i < record.first + record.count; ++i) {
    const Contact& old = previous_contacts_[i];
    LeafSpheres leaves{body_a, body_b, old.leaf_a, old.leaf_b, Sphere{}, Sphere{}};
    const Sphere& leaf_b = b.tree->sphere(old.leaf_b);
    leaves.sphere_b = {pose_of(body_b).apply(leaf_b.center), leaf_b.radius};
    if (body_a != kGroundPlaneBody) {
      const Sphere& leaf_a = bodies_[body_a].tree->sphere(old.leaf_a);
      leaves.sphere_a = {pose_of(body_a).apply(leaf_a.center), leaf_a.radius};
    }
    chunk.leaves.push_back(leaves);
  }
  ++chunk.reused_pairs;
  return true;
}

// The leaf spheres of one job within its pair's gap: reused from its record, or from a descent.
void CollisionDetector::pair_leaves(const Job& job, NarrowChunk& chunk,
                                    StepClock::time_point start) {
  PairLeaves pair;
  pair.plane = job.plane;
  pair.leaves_begin = static_cast<std::uint32_t>(chunk.leaves.size());
  if (job.plane) {
    Body& body = bodies_[job.index];
    body.ground_done = true;
    const Transform& pose = pose_of(job.index);
    PairRecord& record = ground_records_[job.index];
    pair.record = &record;
    const float margin = plane_margin(body);
    pair.reused = reuse(record, pose, margin, store_->extents()[job.index], kGroundPlaneBody,
                        job.index, chunk);
    if (!pair.reused) {
      const float looked = margin + (budget() ? 0.0f : settings_.reuse_distance);
      ground_plane_leaves(job.index, *settings_.ground_plane_height + looked, chunk);
      record.relative = pose;
      record.descent_margin = looked;
      ++chunk.descended_pairs;
    }
  } else {
    PairRecord& record = records_[job.index];
    pair.record = &record;
    const std::uint32_t ia = body_of_proxy_[record.proxies.a];
    const std::uint32_t ib = body_of_proxy_[record.proxies.b];
    const Body& a = bodies_[ia];
    const Body& b = bodies_[ib];
    const float margin = pair_margin(a, b);
    const Transform& pose_a = pose_of(ia);
    const Transform& pose_b = pose_of(ib);
    const Transform relative = relative_pose(pose_a, pose_b);
    pair.reused = reuse(record, relative, margin, store_->extents()[ib], ia, ib, chunk);
    if (!pair.reused) {
      const float looked = margin + (budget() ? 0.0f : settings_.reuse_distance);
      chunk.node_pairs.clear();
      // The clock is read only for a time budget: a read per pair cost 1.7% of a step at 1,000
      // bunnies.
      const double spent = settings_.max_microseconds > 0.0 ? 1e3 * elapsed_ms(start) : 0.0;
      const DescentSettings settings = descent_budget(spent, chunk.sphere_tests, looked);
      const DescentStats descent =
          chunk.descent.descend(*a.tree, pose_a, *b.tree, pose_b, settings, chunk.node_pairs);
      chunk.sphere_tests += descent.sphere_tests;
      chunk.leaf_pairs += descent.leaf_pairs;
      chunk.cut_short_pairs += descent.cut_short_pairs;
      for (const NodePair& nodes : chunk.node_pairs) {
        chunk.leaves.push_back({ia, ib, nodes.node_a, nodes.node_b,
                                chunk.descent.world_sphere_a(*a.tree, nodes.node_a),
                                chunk.descent.world_sphere_b(*b.tree, nodes.node_b)});
      }
      record.relative = relative;
      record.descent_margin = looked;
      ++chunk.descended_pairs;
    }
    record.done = true;
  }
  pair.leaves_end = static_cast<std::uint32_t>(chunk.leaves.size());
  chunk.pairs.push_back(pair);
}

// Descends one body's tree against the half-space y <= height: a subtree is skipped when its
// bound is above `reach_down` (the plane's height plus the body's gap); each leaf sphere within it
// is kept.
void CollisionDetector::ground_plane_leaves(std::uint32_t index, float reach_down,
                                            NarrowChunk& chunk) const {
  const SphereTree& tree = *bodies_[index].tree;
  const Transform& pose = pose_of(index);
  const std::uint32_t leaves_begin = tree.level_begin(last_level(tree, settings_.tree_depth));
  std::vector<std::uint32_t>& stack = chunk.plane_stack;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const std::uint32_t node = stack.back();
    stack.pop_back();
    const Sphere& sphere = tree.sphere(node);
    const Vec3 center = pose.apply(sphere.center);
    ++chunk.sphere_tests;
    const bool leaf = tree.is_leaf(node) || node >= leaves_begin;
    if (center.y() - (leaf ? sphere.radius : tree.subtree_radius(node)) > reach_down) continue;
    if (!leaf) {
      for (std::uint32_t c = tree.first_child(node) + tree.child_count(node);
           c-- > tree.first_child(node);) {
        stack.push_back(c);
      }
      continue;
    }
    chunk.leaves.push_back({kGroundPlaneBody, index, 0, node, Sphere{}, {center, sphere.radius}});
    ++chunk.leaf_pairs;
  }
}

// One contact per pair of leaf spheres (paper eq. 1-3), in the narrow phase's order; then, pair by
// pair, the reduction to a manifold, or for a reused pair its contacts' own depth offsets and
// normals.
void CollisionDetector::make_contacts(NarrowChunk& chunk) const {
  const bool measure = settings_.measure_penetration;
  for (PairLeaves& pair : chunk.pairs) {
    pair.contacts_begin = static_cast<std::uint32_t>(chunk.contacts.size());
    if (pair.leaves_end == pair.leaves_begin) continue;
    const LeafSpheres& first = chunk.leaves[pair.leaves_begin];
    const bool plane = first.body_a == kGroundPlaneBody;
    // The pairs of one body pair share one fallback normal.
    const Vec3 fallback = plane ? Vec3::UnitY()
                                : fallback_normal(pose_of(first.body_a).translation,
                                                  pose_of(first.body_b).translation);
    chunk.run.clear();
    for (std::uint32_t l = pair.leaves_begin; l < pair.leaves_end; ++l) {
      const LeafSpheres& leaves = chunk.leaves[l];
      Contact contact;
      contact.body_a = leaves.body_a;
      contact.body_b = leaves.body_b;
      contact.leaf_a = leaves.leaf_a;
      contact.leaf_b = leaves.leaf_b;
      if (plane) {
        sphere_plane_contact(*settings_.ground_plane_height, leaves.sphere_b, contact);
      } else if (sphere_sphere_contact(leaves.sphere_a, leaves.sphere_b, fallback, contact)) {
        ++chunk.coincident_centres;
      }
      if (measure && contact.depth > 0.0f) {
        chunk.deepest_penetration = std::max(chunk.deepest_penetration, contact.depth);
        chunk.penetration_sum += contact.depth;
        ++chunk.penetrating_contacts;
      }
      chunk.run.push_back(contact);
    }
    const Quat rotation_a = plane ? Quat::Identity() : pose_of(first.body_a).rotation;
    if (pair.reused) {
      const std::uint32_t old_first = pair.record->first;
      for (std::size_t i = 0; i < chunk.run.size(); ++i) {
        const ContactShape& shape = previous_shapes_[old_first + i];
        Contact contact = chunk.run[i];
        contact.depth += shape.depth_offset;
        contact.normal = rotation_a * shape.normal_in_a;
        chunk.contacts.push_back(contact);
        chunk.shapes.push_back(shape);
      }
      continue;
    }
    const std::size_t reduced_begin = chunk.contacts.size();
    if (settings_.manifold_points == 0) {
      chunk.contacts.insert(chunk.contacts.end(), chunk.run.begin(), chunk.run.end());
    } else {
      chunk.reducer.reduce(chunk.run, settings_.manifold_points, last_contacts(*pair.record),
                           chunk.contacts);
    }
    for (std::size_t k = reduced_begin; k < chunk.contacts.size(); ++k) {
      const Contact& contact = chunk.contacts[k];
      float own_depth = contact.depth;
      for (const Contact& leaf : chunk.run) {
        if (leaf.leaf_a == contact.leaf_a && leaf.leaf_b == contact.leaf_b) {
          own_depth = leaf.depth;
          break;
        }
      }
      chunk.shapes.push_back({contact.depth - own_depth, rotation_a.conjugate() * contact.normal});
    }
  }
}

}  // namespace sphys
