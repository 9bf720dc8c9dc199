#include "exterior_lattice.h"

#include <algorithm>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sphys::tools::build {

ExteriorLattice::ExteriorLattice(const MeshQuery& query, std::size_t target_points, double margin)
    : margin_(margin) {
  const Box3d bounds = query.mesh().bounds();
  origin_ = bounds.min() - Vec3d::Constant(margin);
  const Vec3d size = bounds.sizes() + Vec3d::Constant(2.0 * margin);
  spacing_ = std::cbrt(size.prod() / static_cast<double>(std::max<std::size_t>(target_points, 1)));
  for (int axis = 0; axis < 3; ++axis) {
    dims_[axis] = static_cast<int>(std::ceil(size[axis] / spacing_)) + 1;
  }
  const auto nx = static_cast<std::size_t>(dims_[0]);
  const auto ny = static_cast<std::size_t>(dims_[1]);
  distance_.resize(nx * ny * static_cast<std::size_t>(dims_[2]));
  // Each row of points is independent, so the rows are filled in parallel and the lattice is the
  // same on any number of threads.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ny * static_cast<std::size_t>(dims_[2])),
                    [&](const tbb::blocked_range<std::size_t>& rows) {
                      for (std::size_t row = rows.begin(); row != rows.end(); ++row) {
                        const double y = origin_[1] + static_cast<double>(row % ny) * spacing_;
                        const double z = origin_[2] + static_cast<double>(row / ny) * spacing_;
                        for (std::size_t x = 0; x < nx; ++x) {
                          const Vec3d p(origin_[0] + static_cast<double>(x) * spacing_, y, z);
                          distance_[row * nx + x] = static_cast<float>(query.signed_distance(p));
                        }
                      }
                    });
}

ExteriorLattice ExteriorLattice::refined(int factor, const Box3d& region) const {
  ExteriorLattice fine;
  fine.margin_ = margin_;
  fine.spacing_ = spacing_ / factor;
  // The region's corners snapped outward to this lattice's points and clipped to it.
  Vec3d lo;
  for (int axis = 0; axis < 3; ++axis) {
    const double last = static_cast<double>(dims_[axis] - 1);
    const double first =
        std::clamp(std::floor((region.min()[axis] - origin_[axis]) / spacing_), 0.0, last);
    const double end =
        std::clamp(std::ceil((region.max()[axis] - origin_[axis]) / spacing_), first, last);
    lo[axis] = first;
    fine.dims_[axis] = static_cast<int>(end - first) * factor + 1;
  }
  fine.origin_ = origin_ + spacing_ * lo;
  const auto nx = static_cast<std::size_t>(fine.dims_[0]);
  const auto ny = static_cast<std::size_t>(fine.dims_[1]);
  fine.distance_.resize(nx * ny * static_cast<std::size_t>(fine.dims_[2]));
  const Vec3d last(static_cast<double>(dims_[0] - 1), static_cast<double>(dims_[1] - 1),
                   static_cast<double>(dims_[2] - 1));
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, ny * static_cast<std::size_t>(fine.dims_[2])),
      [&](const tbb::blocked_range<std::size_t>& rows) {
        for (std::size_t row = rows.begin(); row != rows.end(); ++row) {
          for (std::size_t x = 0; x < nx; ++x) {
            // In this lattice's coordinates, kept inside it at its far faces.
            const Vec3d q = (lo + Vec3d(static_cast<double>(x), static_cast<double>(row % ny),
                                        static_cast<double>(row / ny)) /
                                      factor)
                                .cwiseMin(last - Vec3d::Constant(1e-9));
            fine.distance_[row * nx + x] = static_cast<float>(distance_at(origin_ + spacing_ * q));
          }
        }
      });
  return fine;
}

double ExteriorLattice::distance_at(const Vec3d& p) const {
  const Vec3d q = (p - origin_) / spacing_;
  int base[3];
  double t[3];
  for (int axis = 0; axis < 3; ++axis) {
    const double last = static_cast<double>(dims_[axis] - 1);
    if (!(q[axis] >= 0.0 && q[axis] <= last) || dims_[axis] < 2) {
      return std::numeric_limits<double>::infinity();
    }
    // The last cell also answers for the far face.
    const double f = std::min(std::floor(q[axis]), last - 1.0);
    base[axis] = static_cast<int>(f);
    t[axis] = q[axis] - f;
  }
  const auto nx = static_cast<std::size_t>(dims_[0]);
  const auto nxy = nx * static_cast<std::size_t>(dims_[1]);
  const std::size_t corner = static_cast<std::size_t>(base[2]) * nxy +
                             static_cast<std::size_t>(base[1]) * nx +
                             static_cast<std::size_t>(base[0]);
  double value = 0.0;
  for (int k = 0; k < 8; ++k) {
    const int dx = k & 1;
    const int dy = (k >> 1) & 1;
    const int dz = k >> 2;
    const double weight = (dx != 0 ? t[0] : 1.0 - t[0]) * (dy != 0 ? t[1] : 1.0 - t[1]) *
                          (dz != 0 ? t[2] : 1.0 - t[2]);
    const std::size_t index = corner + static_cast<std::size_t>(dz) * nxy +
                              static_cast<std::size_t>(dy) * nx + static_cast<std::size_t>(dx);
    value += weight * static_cast<double>(distance_[index]);
  }
  return value;
}

double ExteriorLattice::protrusion(const Ball& ball, std::span<const Vec3d> directions) const {
  double worst = -std::numeric_limits<double>::infinity();
  for (const Vec3d& u : directions)
    worst = std::max(worst, distance_at(ball.center + ball.radius * u));
  return worst;
}

}  // namespace sphys::tools::build
