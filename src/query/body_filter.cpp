#include "query/body_filter.h"

#include <string>

#include "sphys/error.h"

namespace sphys::query_detail {

std::uint32_t checked_slot(const World& world, const Snapshot& snapshot, BodyId body,
                           std::string_view argument) {
  std::uint32_t slot = 0;
  try {
    slot = world.slot_of(body);
  } catch (const Error& error) {
    throw Error(std::string(argument) + ": " + error.what());
  }
  if (slot >= snapshot.trees.size() || snapshot.trees[slot] == nullptr) {
    throw Error(std::string(argument) + ": body " + std::to_string(body.index) + "." +
                std::to_string(body.generation) +
                " was added after the query was made or refreshed");
  }
  return slot;
}

BodyFilter::BodyFilter(const World& world, const Snapshot& snapshot, const QueryFilter& filter)
    : snapshot_(snapshot), filter_(filter) {
  skip_.reserve(filter.skip.size());
  for (const BodyId body : filter.skip) {
    skip_.push_back(checked_slot(world, snapshot, body, "filter.skip"));
  }
}

}  // namespace sphys::query_detail
