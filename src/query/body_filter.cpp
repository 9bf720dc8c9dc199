#include "query/body_filter.h"

#include <string>

#include "core/id_errors.h"
#include "sphys/error.h"

namespace sphys::query_detail {

std::uint32_t checked_slot(const Snapshot& snapshot, BodyId body, std::string_view argument) {
  if (body.is_null()) {
    throw Error(std::string(argument) + ": the null body id (BodyId{}) names no body");
  }
  if (body.index >= snapshot.ids.size() || snapshot.ids[body.index] != body) {
    throw Error(std::string(argument) + ": no body with id " + id_text(body) +
                " in the world as the query last read it (removed, added since the query was "
                "made or refreshed, or never added)");
  }
  return body.index;
}

BodyFilter::BodyFilter(const Snapshot& snapshot, const QueryFilter& filter)
    : snapshot_(snapshot), filter_(filter) {
  skip_.reserve(filter.skip.size());
  for (const BodyId body : filter.skip) {
    skip_.push_back(checked_slot(snapshot, body, "filter.skip"));
  }
}

}  // namespace sphys::query_detail
