#include "query/body_filter.h"

#include <string>

#include "sphys/error.h"

namespace sphys::query_detail {

std::uint32_t checked_slot(const World& world, const Snapshot& snapshot, BodyId body,
                           std::string_view argument) {
  if (!world.alive(body) || body.index >= snapshot.trees.size() ||
      snapshot.trees[body.index] == nullptr) {
    throw Error(std::string(argument) + ": no body with id " + std::to_string(body.index) + "." +
                std::to_string(body.generation) +
                " in the world (removed, never added, or added after the query was refreshed)");
  }
  return body.index;
}

BodyFilter::BodyFilter(const World& world, const Snapshot& snapshot, const QueryFilter& filter)
    : snapshot_(snapshot), filter_(filter) {
  skip_.reserve(filter.skip.size());
  for (const BodyId body : filter.skip) {
    skip_.push_back(checked_slot(world, snapshot, body, "filter.skip"));
  }
}

}  // namespace sphys::query_detail
