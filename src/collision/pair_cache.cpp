#include "collision/pair_cache.h"

#include <algorithm>

#include "core/buffers.h"

namespace sphys {
namespace {

// Broad-phase pairs per item of the threaded merge of the records. unit: pairs
constexpr std::size_t kRecordsPerRun = 1024;

}  // namespace

// The pairs are merged in runs, each run with the old records of its keys (the first run also
// those below, the last those above), so that the runs are independent.
std::uint32_t PairCache::follow(std::span<const ProxyPair> pairs, const LinksDynamic& links_dynamic,
                                const Parallel* parallel) {
  old_records_.swap(records_);
  resize_buffer(records_, pairs.size());
  // The first old record at or after pair p's key.
  const auto first_old = [&](std::size_t p) -> std::size_t {
    if (p == 0) return 0;
    if (p == pairs.size()) return old_records_.size();
    const std::uint64_t key = pair_key(pairs[p]);
    return static_cast<std::size_t>(
        std::partition_point(old_records_.begin(), old_records_.end(),
                             [&](const Record& r) { return pair_key(r.proxies) < key; }) -
        old_records_.begin());
  };
  const std::size_t runs =
      std::max<std::size_t>(1, (pairs.size() + kRecordsPerRun - 1) / kRecordsPerRun);
  fill_buffer(parted_in_run_, runs, 0u);
  const auto merge = [&](std::size_t run) {
    const std::size_t begin = run * kRecordsPerRun;
    const std::size_t end = std::min(pairs.size(), begin + kRecordsPerRun);
    std::size_t old = first_old(begin);
    const std::size_t old_end = first_old(end);
    const auto drop = [&](const Record& record) {
      if (links_dynamic(record)) ++parted_in_run_[run];
    };
    for (std::size_t p = begin; p < end; ++p) {
      const std::uint64_t key = pair_key(pairs[p]);
      while (old < old_end && pair_key(old_records_[old].proxies) < key) {
        drop(old_records_[old++]);
      }
      if (old < old_end && pair_key(old_records_[old].proxies) == key) {
        records_[p] = old_records_[old++];
      } else {
        records_[p] = Record{};
        records_[p].proxies = pairs[p];
      }
    }
    for (; old < old_end; ++old) drop(old_records_[old]);
  };
  for_each_on(parallel, runs, merge);
  std::uint32_t parted = 0;
  for (const std::uint32_t count : parted_in_run_) parted += count;
  return parted;
}

void PairCache::forget_proxy(ProxyId proxy) {
  for (Record& record : records_) {
    if (record.proxies.a == proxy || record.proxies.b == proxy) {
      record.descent_margin = -1.0f;
      record.count = 0;
    }
  }
}

void PairCache::begin_narrow_phase() {
  previous_contacts_.swap(contacts_);
  previous_memory_.swap(memory_);
  previous_shapes_.swap(shapes_);
  live_asleep_ = 0;
}

// Appends a record's contacts and their memory from one store to another; returns where they
// begin there.
std::uint32_t PairCache::append_range(const std::vector<Contact>& contacts,
                                      const std::vector<ContactMemory>& memory,
                                      const Record& record, std::vector<Contact>& to_contacts,
                                      std::vector<ContactMemory>& to_memory) {
  const auto first = static_cast<std::uint32_t>(to_contacts.size());
  const auto begin = static_cast<std::ptrdiff_t>(record.first);
  const auto end = begin + static_cast<std::ptrdiff_t>(record.count);
  to_contacts.insert(to_contacts.end(), contacts.begin() + begin, contacts.begin() + end);
  to_memory.insert(to_memory.end(), memory.begin() + begin, memory.begin() + end);
  return first;
}

std::uint32_t PairCache::rest(Record& record) {
  // Kept contacts are matched again by leaf pair only: the pair descends anew when it wakes.
  record.descent_margin = -1.0f;
  return record.count;
}

void PairCache::keep_asleep(Record& record) {
  record.first =
      append_range(previous_contacts_, previous_memory_, record, asleep_contacts_, asleep_memory_);
  record.kept_asleep = true;
}

void PairCache::compact_asleep() {
  if (2 * live_asleep_ >= asleep_contacts_.size()) return;
  compacted_contacts_.clear();
  compacted_memory_.clear();
  const auto move = [&](Record& record) {
    if (!record.kept_asleep) return;
    record.first = append_range(asleep_contacts_, asleep_memory_, record, compacted_contacts_,
                                compacted_memory_);
  };
  for (Record& record : records_) move(record);
  for (Record& record : ground_records_) move(record);
  asleep_contacts_.swap(compacted_contacts_);
  asleep_memory_.swap(compacted_memory_);
}

std::span<const Contact> PairCache::last_contacts(const Record& record) const {
  if (record.count == 0) return {};
  const std::vector<Contact>& from = record.kept_asleep ? asleep_contacts_ : previous_contacts_;
  return std::span<const Contact>(from).subspan(record.first, record.count);
}

std::span<const ContactMemory> PairCache::last_memory(const Record& record) const {
  if (record.count == 0) return {};
  const std::vector<ContactMemory>& from = record.kept_asleep ? asleep_memory_ : previous_memory_;
  return std::span<const ContactMemory>(from).subspan(record.first, record.count);
}

// Both lists come in the descent's order mostly, so the search starts after the last match.
void PairCache::carry_memory(const Record& record, std::span<const Contact> contacts,
                             std::span<ContactMemory> memory) const {
  const std::span<const Contact> old_contacts = last_contacts(record);
  const std::span<const ContactMemory> old_memory = last_memory(record);
  const std::size_t old_count = old_contacts.size();
  std::size_t hint = 0;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Contact& contact = contacts[c];
    std::size_t tried = 0;
    for (; tried < old_count; ++tried) {
      const std::size_t i = (hint + tried) % old_count;
      const Contact& old = old_contacts[i];
      if (old.leaf_a == contact.leaf_a && old.leaf_b == contact.leaf_b) {
        memory[c] = old_memory[i];
        hint = i + 1;
        break;
      }
    }
    if (tried == old_count) memory[c] = ContactMemory{};
  }
}

void PairCache::resize(std::size_t contacts) {
  resize_buffer(contacts_, contacts);
  resize_buffer(memory_, contacts);
  resize_buffer(shapes_, contacts);
}

}  // namespace sphys
