#include "sphys/world_query.h"

#include "query/snapshot.h"

namespace sphys {

WorldQuery::WorldQuery(const World& world)
    : world_(&world), snapshot_(std::make_unique<query_detail::Snapshot>()) {
  refresh();
}

WorldQuery::~WorldQuery() = default;
WorldQuery::WorldQuery(WorldQuery&&) noexcept = default;
WorldQuery& WorldQuery::operator=(WorldQuery&&) noexcept = default;

void WorldQuery::refresh() { snapshot_->read(*world_); }

}  // namespace sphys
