#pragma once

// The collision detector's memory between steps, in the manner of Jolt's ManifoldCache: one
// record per body pair the broad phase lists (and per body against the ground plane), each
// pointing at its contacts of the last narrow phase; those contacts with their warm-start memory
// and shapes; and the contacts of pairs that went to sleep, kept until they wake. The detector
// (collision_detector.h) drives it; it knows nothing of trees or descents.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "collision/broad_phase.h"
#include "sphys/contact.h"
#include "sphys/math.h"
#include "sphys/parallel.h"

namespace sphys {

// What a contact carries from one narrow phase to the next for warm starting, matched by its leaf
// pair within its body pair's record. The response writes it; the detector carries it over.
struct ContactMemory {
  float normal_impulse = 0.0f;  // to start the next solve from. unit: N·s
  // Friction is solved per manifold, at its centre: each of its contacts keeps an equal share of
  // the manifold's tangential impulse (world frame) and of its twist about the normal, and the
  // next solve sums the shares of the contacts it still has.
  Vec3 friction_impulse = Vec3::Zero();  // unit: N·s
  float twist_impulse = 0.0f;            // unit: N·m·s
  // Static friction's anchor, shared by a manifold's contacts like its friction: whether the
  // manifold's bodies stuck at the end of the last solve (its friction within the bound), and
  // how far its centre had crept along the surface since they stuck (world frame). unit: m
  Vec3 creep = Vec3::Zero();
  bool stuck = false;
  bool solved = false;  // false for a contact the last solve did not have
};

class PairCache {
 public:
  // The persistent record of a body pair (or of a body and the ground plane): created when the
  // broad phase pairs the bodies, dropped when it unpairs them.
  struct Record {
    ProxyPair proxies;  // the key; the ground plane's records are per body instead
    // Body b's pose in body a's frame (the world's for the ground) at the last descent.
    Transform relative;
    // The gap the last descent looked up to; negative when the contacts below are not valid.
    // unit: m
    float descent_margin = -1.0f;
    // Its contacts of the last narrow phase: [first, first + count) of contacts() (of
    // previous_contacts() once the next narrow phase begins), or of the sleeping pairs' store
    // while neither body moves (`kept_asleep`).
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    bool kept_asleep = false;
    bool done = false;  // had its narrow phase in this step
  };

  // Per contact, what reusing it needs: its depth beyond its own leaf pair's (a reduced contact
  // carries its cluster's deepest overlap) and its normal in body a's frame. unit: m
  struct Shape {
    float depth_offset = 0.0f;
    Vec3 normal_in_a = Vec3::UnitY();
  };

  // Whether a record joined two dynamic bodies by contacts in its last narrow phase.
  using LinksDynamic = std::function<bool(const Record&)>;

  // The records follow the broad phase's pairs, both sorted by proxies: a pair still listed keeps
  // its record, a new pair gets an empty one, and the records of pairs gone are dropped. Merged in
  // runs on `parallel`'s threads (none: the caller's). Returns how many records dropped had
  // `links_dynamic`.
  std::uint32_t follow(std::span<const ProxyPair> pairs, const LinksDynamic& links_dynamic,
                       const Parallel* parallel);
  [[nodiscard]] std::span<Record> records() { return records_; }
  [[nodiscard]] std::span<const Record> records() const { return records_; }
  // The ground plane's record of a body slot; slots up to `slots` exist after resize_ground.
  [[nodiscard]] Record& ground_record(std::uint32_t slot) { return ground_records_[slot]; }
  void resize_ground(std::size_t slots) { ground_records_.resize(slots); }
  // A removed body's pairs are kept by the broad phase until its next update: until then their
  // contacts must not be reused or carried.
  void forget_proxy(ProxyId proxy);

  // A narrow phase begins: this one's contacts, memory and shapes become the last ones.
  void begin_narrow_phase();
  // A record whose bodies both stopped moving (asleep, or asleep and static) keeps its contacts
  // and their memory in the sleeping pairs' store, so that the pair warm starts when it wakes.
  // In parts, so that the records may be gone through on the threads: rest() for every such
  // record, on any thread (it writes the record alone), which returns its contacts;
  // count_live_asleep() with their sum; and keep_asleep(), in the records' order, for those not
  // yet kept (Record::kept_asleep), which copies their contacts into the store.
  static std::uint32_t rest(Record& record);
  void count_live_asleep(std::size_t contacts) { live_asleep_ = contacts; }
  void keep_asleep(Record& record);
  // Once less than half of the sleeping pairs' store is live, it is rebuilt from the live records.
  void compact_asleep();

  // The record's contacts and memory of its last narrow phase (a record that had none, none).
  [[nodiscard]] std::span<const Contact> last_contacts(const Record& record) const;
  [[nodiscard]] std::span<const ContactMemory> last_memory(const Record& record) const;
  [[nodiscard]] std::span<const Contact> previous_contacts() const { return previous_contacts_; }
  [[nodiscard]] std::span<const Shape> previous_shapes() const { return previous_shapes_; }
  // Each new contact of a record takes the memory of the contact of the same leaf pair among the
  // record's last contacts (a new one starts empty).
  void carry_memory(const Record& record, std::span<const Contact> contacts,
                    std::span<ContactMemory> memory) const;

  // This narrow phase's contacts, their memory and shapes: sized by resize (what they held is not
  // zeroed first) and written in place.
  void resize(std::size_t contacts);
  [[nodiscard]] std::span<Contact> contacts() { return contacts_; }
  [[nodiscard]] std::span<const Contact> contacts() const { return contacts_; }
  [[nodiscard]] std::span<ContactMemory> memory() { return memory_; }
  [[nodiscard]] std::span<Shape> shapes() { return shapes_; }

 private:
  static std::uint32_t append_range(const std::vector<Contact>& contacts,
                                    const std::vector<ContactMemory>& memory, const Record& record,
                                    std::vector<Contact>& to_contacts,
                                    std::vector<ContactMemory>& to_memory);

  // Records of the candidate pairs, in the order of the broad phase's pairs, and of the last
  // update's (swapped, to carry them over); the ground plane's per body.
  std::vector<Record> records_;
  std::vector<Record> old_records_;
  std::vector<std::uint32_t> parted_in_run_;  // follow()'s records dropped, per run
  std::vector<Record> ground_records_;
  // This narrow phase's contacts, memory and shapes, and the last one's, to carry them over.
  std::vector<Contact> contacts_;
  std::vector<ContactMemory> memory_;
  std::vector<Shape> shapes_;
  std::vector<Contact> previous_contacts_;
  std::vector<ContactMemory> previous_memory_;
  std::vector<Shape> previous_shapes_;
  // The contacts and memory of the records kept asleep, and how many of them are a live record's
  // (records gone or woken leave theirs behind until the store is compacted).
  std::vector<Contact> asleep_contacts_;
  std::vector<ContactMemory> asleep_memory_;
  std::vector<Contact> compacted_contacts_;  // compact_asleep's scratch
  std::vector<ContactMemory> compacted_memory_;
  std::size_t live_asleep_ = 0;
};

}  // namespace sphys
