#pragma once

// Items of one kind kept by slot, each slot with a generation (sphys/slot_id.h): the joints and
// the robots of a world. The body store keeps its bodies' slots itself, in arrays per quantity
// (sphys/body_store.h).

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace sphys {

// `Item` has a `bool alive`, false by default, which the store keeps and the items' readers test
// (the joint solver passes over dead joints).
template <class Id, class Item>
class SlotStore {
 public:
  // Takes a free slot (the most recently freed first) for `item`, alive from now on.
  Id add(Item item) {
    std::uint32_t slot = 0;
    if (free_.empty()) {
      slot = static_cast<std::uint32_t>(items_.size());
      items_.emplace_back();
      generation_.push_back(0);
    } else {
      slot = free_.back();
      free_.pop_back();
    }
    items_[slot] = std::move(item);
    items_[slot].alive = true;
    ++generation_[slot];  // from 1: the null id's generation 0 names nothing
    return id_of(slot);
  }
  // Empties the slot (what its item held is freed) for a later add.
  void remove(std::uint32_t slot) {
    items_[slot] = Item{};
    free_.push_back(slot);
  }
  // True for an item in the store; false for a stale or unknown id, or the null one.
  [[nodiscard]] bool alive(Id id) const {
    return id.index < items_.size() && generation_[id.index] == id.generation &&
           items_[id.index].alive;
  }
  // The id of a slot's item, or of the last one removed from it when the slot is free.
  [[nodiscard]] Id id_of(std::uint32_t slot) const { return {slot, generation_[slot]}; }
  [[nodiscard]] Item& at(std::uint32_t slot) { return items_[slot]; }
  [[nodiscard]] const Item& at(std::uint32_t slot) const { return items_[slot]; }
  // Every slot's item, dead ones included (Item::alive).
  [[nodiscard]] std::span<Item> all() { return items_; }
  [[nodiscard]] std::span<const Item> all() const { return items_; }

 private:
  std::vector<Item> items_;
  std::vector<std::uint32_t> generation_;
  std::vector<std::uint32_t> free_;
};

}  // namespace sphys
