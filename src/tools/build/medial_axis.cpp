// The only translation unit of the builders that compiles CGAL's triangulation (tens of seconds
// each): the reducers see plain vectors of spheres.
#include "medial_axis.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

namespace sphys::tools::build {
namespace {

constexpr std::uint32_t kNoPoint = std::numeric_limits<std::uint32_t>::max();

// The point a vertex stands for (a struct, so that new vertices start out with none).
struct VertexInfo {
  std::uint32_t point = kNoPoint;
};

// What a tetrahedron's circumsphere says about the medial axis, worked out once per cell.
struct CellInfo {
  bool evaluated = false;
  bool medial = false;     // relevant to the region and centred inside the object
  bool exhausted = false;  // refinement could not split it (its surface point is a generator)
  MedialSphere sphere;
};

// Exact predicates keep the triangulation valid on the degenerate (cospherical) samples of boxes
// and other flat faces; the circumcentres themselves need no exactness.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<VertexInfo, Kernel>;
using CellBase =
    CGAL::Triangulation_cell_base_with_info_3<CellInfo, Kernel,
                                              CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
using CgalPoint = Kernel::Point_3;

CgalPoint to_cgal(const Vec3d& p) { return {p.x(), p.y(), p.z()}; }
Vec3d to_vec(const CgalPoint& p) { return {p.x(), p.y(), p.z()}; }

// Spreads the low 21 bits of v three apart, for a Morton code.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffffULL;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

// Point indices in Morton order: consecutive insertions land near each other, so the walk from
// the previous vertex is short. Ours rather than CGAL's spatial_sort, whose shuffle we do not
// control.
std::vector<std::uint32_t> spatial_order(std::span<const Vec3d> points) {
  Box3d box;
  for (const Vec3d& p : points) box.extend(p);
  const double extent = std::max(box.sizes().maxCoeff(), 1e-300);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3d q = (points[i] - box.min()) / extent * 2097151.0;
    keyed.emplace_back(spread_bits(static_cast<std::uint64_t>(q.x())) |
                           spread_bits(static_cast<std::uint64_t>(q.y())) << 1 |
                           spread_bits(static_cast<std::uint64_t>(q.z())) << 2,
                       static_cast<std::uint32_t>(i));
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order;
  order.reserve(keyed.size());
  for (const auto& [key, index] : keyed) order.push_back(index);
  return order;
}

class Approximation {
 public:
  Approximation(std::span<const Vec3d> points, std::size_t focus, const ErrorMeasure& measure)
      : points_(points.begin(), points.end()),
        input_count_(points.size()),
        focus_(focus),
        measure_(measure),
        vertex_of_(points.size()) {
    Delaunay::Vertex_handle hint;
    for (const std::uint32_t i : spatial_order(points)) {
      const Delaunay::Vertex_handle v = dt_.insert(to_cgal(points_[i]), hint);
      // A repeated position keeps the smallest index, so a focus point wins over a context one.
      if (v->info().point == kNoPoint || i < v->info().point) v->info().point = i;
      vertex_of_[i] = v;
      hint = v;
    }
  }

  // Bradshaw §3.3: the sphere that pokes out furthest is split by adding the surface point
  // nearest its centre as a new generator; its tetrahedron is then no longer empty, and the
  // spheres that replace it hug the surface there more closely.
  void refine(const MedialAxisOptions& options) {
    for (int added = 0; added < options.max_added_points; ++added) {
      Delaunay::Cell_handle worst;
      double worst_error = options.tolerance;
      for (const Delaunay::Cell_handle cell : dt_.finite_cell_handles()) {
        const CellInfo& info = evaluate(cell);
        if (info.medial && !info.exhausted && info.sphere.error > worst_error) {
          worst_error = info.sphere.error;
          worst = cell;
        }
      }
      if (worst == Delaunay::Cell_handle()) return;
      const Vec3d surface_point = measure_.closest_point(worst->info().sphere.ball.center);
      const std::size_t before = dt_.number_of_vertices();
      const Delaunay::Vertex_handle v = dt_.insert(to_cgal(surface_point), worst);
      if (dt_.number_of_vertices() == before) {
        worst->info().exhausted = true;
        continue;
      }
      v->info().point = static_cast<std::uint32_t>(points_.size());
      points_.push_back(surface_point);
    }
  }

  MedialAxis result() {
    MedialAxis axis;
    axis.point_spheres.resize(focus_);
    for (const Delaunay::Cell_handle cell : dt_.finite_cell_handles()) {
      const CellInfo& info = evaluate(cell);
      if (!info.medial) continue;
      const auto index = static_cast<std::uint32_t>(axis.spheres.size());
      axis.spheres.push_back(info.sphere);
      for (const std::uint32_t g : info.sphere.generators) {
        if (g < focus_) axis.point_spheres[g].push_back(index);
      }
    }
    // A focus point that shares its position with another keeps that vertex's spheres.
    for (std::size_t i = 0; i < focus_; ++i) {
      const std::uint32_t owner = vertex_of_[i]->info().point;
      if (owner != i && owner < focus_) axis.point_spheres[i] = axis.point_spheres[owner];
    }
    axis.points = std::move(points_);
    return axis;
  }

 private:
  bool relevant(std::uint32_t point) const { return point < focus_ || point >= input_count_; }

  // The centre of the sphere through the cell's four corners: solves 2 (p_k - p_0) . x =
  // |p_k - p_0|² for x = centre - p_0. Nothing when the cell is too flat for a stable answer.
  static std::optional<Vec3d> circumcentre(const Delaunay::Cell_handle& cell) {
    const Vec3d p0 = to_vec(cell->vertex(0)->point());
    Eigen::Matrix3d edges;
    Vec3d lengths;
    double longest = 0.0;
    for (int k = 1; k < 4; ++k) {
      const Vec3d d = to_vec(cell->vertex(k)->point()) - p0;
      edges.row(k - 1) = 2.0 * d.transpose();
      lengths[k - 1] = d.squaredNorm();
      longest = std::max(longest, d.norm());
    }
    const double determinant = edges.determinant();
    if (!(std::abs(determinant) > 1e-12 * 8.0 * longest * longest * longest)) return std::nullopt;
    const Vec3d center = p0 + edges.inverse() * lengths;
    if (!center.allFinite()) return std::nullopt;
    return center;
  }

  const CellInfo& evaluate(const Delaunay::Cell_handle& cell) {
    CellInfo& info = cell->info();
    if (info.evaluated) return info;
    info.evaluated = true;
    bool touches_region = false;
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t g = cell->vertex(k)->info().point;
      info.sphere.generators[static_cast<std::size_t>(k)] = g;
      touches_region = touches_region || relevant(g);
    }
    if (!touches_region) return info;
    // Nearly flat tetrahedra put their circumcentres far away, or at infinity (where CGAL's
    // construction asserts); nothing outside the object's box is inside the object.
    const std::optional<Vec3d> center = circumcentre(cell);
    if (!center || !measure_.bounds().contains(*center)) return info;
    const double signed_distance = measure_.signed_distance(*center);
    if (signed_distance >= 0.0) return info;  // outside: not part of the medial axis
    info.medial = true;
    info.sphere.ball = {*center, (to_vec(cell->vertex(0)->point()) - *center).norm()};
    info.sphere.error = info.sphere.ball.radius + signed_distance;
    return info;
  }

  std::vector<Vec3d> points_;
  std::size_t input_count_;
  std::size_t focus_;
  const ErrorMeasure& measure_;
  std::vector<Delaunay::Vertex_handle> vertex_of_;
  Delaunay dt_;
};

}  // namespace

MedialAxis approximate_medial_axis(std::span<const Vec3d> points, std::size_t focus,
                                   const ErrorMeasure& measure, const MedialAxisOptions& options) {
  Approximation approximation(points, std::min(focus, points.size()), measure);
  approximation.refine(options);
  return approximation.result();
}

}  // namespace sphys::tools::build
