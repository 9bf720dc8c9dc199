// Grid reduction (Bradshaw & O'Sullivan 2004, §5): the points are binned into the cells of a
// regular grid over the node, each occupied cell gives a sphere, and the spheres are then
// reduced by merging (§4.2).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "reducers_impl.h"

namespace sphys::tools::build {
namespace {

// Occupied cells per sphere wanted: enough that merging has real choices to make.
constexpr int kCellsPerBall = 24;

std::vector<std::vector<std::uint32_t>> bin(const Region& region, double cell,
                                            const Vec3d& origin) {
  std::vector<std::pair<std::array<std::int64_t, 3>, std::uint32_t>> keyed;
  keyed.reserve(region.points.size());
  for (std::uint32_t i = 0; i < region.points.size(); ++i) {
    const Eigen::Array3d q = ((region.points[i] - origin) / cell).array().floor();
    keyed.push_back({{static_cast<std::int64_t>(q.x()), static_cast<std::int64_t>(q.y()),
                      static_cast<std::int64_t>(q.z())},
                     i});
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::vector<std::uint32_t>> cells;
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) cells.emplace_back();
    cells.back().push_back(keyed[i].second);
  }
  return cells;
}

}  // namespace

std::vector<Cluster> grid_clusters(const Region& region, const ErrorMeasure& measure,
                                   int max_balls) {
  Box3d box;
  for (const Vec3d& p : region.points) box.extend(p);
  const double wanted = static_cast<double>(std::min<std::size_t>(
      region.points.size(), static_cast<std::size_t>(kCellsPerBall * max_balls)));
  // On a surface the occupied cells grow as 1/side²: start from that and correct once.
  double cell = std::max(box.sizes().maxCoeff(), 1e-12) / std::sqrt(wanted);
  std::vector<std::vector<std::uint32_t>> cells = bin(region, cell, box.min());
  cell *= std::sqrt(static_cast<double>(cells.size()) / wanted);
  cells = bin(region, cell, box.min());
  std::vector<Cluster> clusters;
  clusters.reserve(cells.size());
  for (std::vector<std::uint32_t>& members : cells) {
    clusters.push_back(fit_cluster(region, measure, std::move(members)));
  }
  return merge_clusters(std::move(clusters), region, measure, max_balls);
}

}  // namespace sphys::tools::build
