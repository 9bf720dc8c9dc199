#include "sphys/tools/mass_properties.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sphys/error.h"
#include "sphys/tools/check_mesh.h"
#include "sphys/tools/winding_number.h"

namespace sphys::tools {
namespace {

// More columns than this is a typo: 8192² columns put the O(cell) error far below rounding noise
// in any mesh's coordinates and take seconds.
constexpr int kMaxColumns = 8192;
// A flat mesh's volume is rounding noise of either sign; below this fraction of the bounding
// cube of its longest side a mesh is taken to enclose nothing.
constexpr double kMinRelativeVolume = 1e-12;

std::string to_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// Volume integrals of 1, r and r·rᵀ over the solid, r measured from a reference point (the
// bounding-box centre: near the centre of mass, so the shift to it loses no digits).
struct Moments {
  double volume = 0.0;
  Vec3d first = Vec3d::Zero();
  Mat3d second = Mat3d::Zero();

  Moments& operator+=(const Moments& other) {
    volume += other.volume;
    first += other.first;
    second += other.second;
    return *this;
  }
};

void validate(const TriangleMesh& mesh, const MassPropertiesOptions& options) {
  if (!std::isfinite(options.density) || options.density <= 0.0) {
    throw Error::in_file(mesh.name,
                         "density must be positive and finite, got " + to_text(options.density));
  }
  if (options.columns < 1 || options.columns > kMaxColumns) {
    throw Error::in_file(mesh.name, "columns must be between 1 and " + std::to_string(kMaxColumns) +
                                        ", got " + std::to_string(options.columns));
  }
  require_usable(mesh);
}

struct DirectedEdge {
  std::uint32_t from;
  std::uint32_t to;
};

struct EdgeSummary {
  // Every edge used by exactly two triangles, once each way.
  bool watertight = true;
  // The surface's boundary as a chain: the uses of each edge that do not cancel, one entry per
  // surviving use. Holes show here, and so do non-manifold and misoriented edges.
  std::vector<DirectedEdge> boundary;
};

// Calls visit(a, b) for each edge a → b of each triangle, skipping collapsed edges (a == b),
// which bound nothing.
template <typename Visit>
void for_each_edge(const std::vector<Triangle>& triangles, Visit visit) {
  for (const Triangle& triangle : triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (triangle[k] != triangle[(k + 1) % 3]) visit(triangle[k], triangle[(k + 1) % 3]);
    }
  }
}

// Tallies each edge's uses, grouped by the edge's lower vertex (a counting sort, linear in the
// mesh size) and sorted by the higher one within each group.
EdgeSummary summarize_edges(std::size_t vertex_count, const std::vector<Triangle>& triangles) {
  struct Use {
    std::uint32_t high;
    int direction;  // +1 when the triangle runs from the lower vertex to the higher
  };
  std::vector<std::size_t> group_start(vertex_count + 1, 0);
  for_each_edge(triangles,
                [&](std::uint32_t a, std::uint32_t b) { ++group_start[std::min(a, b) + 1]; });
  std::partial_sum(group_start.begin(), group_start.end(), group_start.begin());
  std::vector<Use> uses(group_start.back());
  std::vector<std::size_t> next(group_start.begin(), group_start.end() - 1);
  for_each_edge(triangles, [&](std::uint32_t a, std::uint32_t b) {
    uses[next[std::min(a, b)]++] = {std::max(a, b), a < b ? 1 : -1};
  });

  EdgeSummary summary;
  for (std::uint32_t low = 0; low < vertex_count; ++low) {
    const auto group_begin = uses.begin() + static_cast<std::ptrdiff_t>(group_start[low]);
    const auto group_end = uses.begin() + static_cast<std::ptrdiff_t>(group_start[low + 1]);
    std::sort(group_begin, group_end, [](const Use& a, const Use& b) { return a.high < b.high; });
    for (auto first = group_begin; first != group_end;) {
      auto end = first;
      int net = 0;
      for (; end != group_end && end->high == first->high; ++end) net += end->direction;
      summary.watertight = summary.watertight && end - first == 2 && net == 0;
      for (int copy = 0; copy < std::abs(net); ++copy) {
        summary.boundary.push_back(net > 0 ? DirectedEdge{low, first->high}
                                           : DirectedEdge{first->high, low});
      }
      first = end;
    }
  }
  return summary;
}

// ---- Polyhedral method --------------------------------------------------------------------

// For one coordinate w at a triangle's three corners: f1, f2, f3 are the sums of all monomials
// of degree 1, 2 and 3 in (w0, w1, w2), and g_i = f2 + w_i (f1 + w_i) feeds the mixed products.
// Eberly, "Polyhedral Mass Properties (Revisited)", Geometric Tools (2002).
struct PowerSums {
  double f1;
  double f2;
  double f3;
  std::array<double, 3> g;
};

PowerSums power_sums(double w0, double w1, double w2) {
  const double w01 = w0 + w1;
  const double f1 = w01 + w2;
  const double w0_squared = w0 * w0;
  const double f2_01 = w0_squared + w1 * w01;  // degree-2 monomials of (w0, w1) alone
  const double f2 = f2_01 + w2 * f1;
  const double f3 = w0 * w0_squared + w1 * f2_01 + w2 * f2;
  return {f1, f2, f3, {f2 + w0 * (f1 + w0), f2 + w1 * (f1 + w1), f2 + w2 * (f1 + w2)}};
}

// The divergence theorem turns each volume integral of 1, x, y, z, x², y², z², xy, yz, zx into
// a sum over the triangles of a polynomial integrated exactly over the triangle (Mirtich, "Fast
// and Accurate Computation of Polyhedral Mass Properties", 1996, in Eberly's 2002 form). Exact
// for any closed, consistently oriented surface.
Moments polyhedral_moments(const std::vector<Vec3d>& vertices,
                           const std::vector<Triangle>& triangles) {
  double volume = 0.0;
  Vec3d first = Vec3d::Zero();
  Vec3d squares = Vec3d::Zero();   // ∫x², ∫y², ∫z²
  Vec3d products = Vec3d::Zero();  // ∫xy, ∫yz, ∫zx
  for (const auto& [i0, i1, i2] : triangles) {
    const Vec3d& p0 = vertices[i0];
    const Vec3d& p1 = vertices[i1];
    const Vec3d& p2 = vertices[i2];
    const Vec3d d = (p1 - p0).cross(p2 - p0);
    const PowerSums x = power_sums(p0.x(), p1.x(), p2.x());
    const PowerSums y = power_sums(p0.y(), p1.y(), p2.y());
    const PowerSums z = power_sums(p0.z(), p1.z(), p2.z());
    volume += d.x() * x.f1;
    first += d.cwiseProduct(Vec3d(x.f2, y.f2, z.f2));
    squares += d.cwiseProduct(Vec3d(x.f3, y.f3, z.f3));
    products += d.cwiseProduct(Vec3d(p0.y() * x.g[0] + p1.y() * x.g[1] + p2.y() * x.g[2],
                                     p0.z() * y.g[0] + p1.z() * y.g[1] + p2.z() * y.g[2],
                                     p0.x() * z.g[0] + p1.x() * z.g[1] + p2.x() * z.g[2]));
  }
  squares /= 60.0;
  products /= 120.0;
  Moments moments;
  moments.volume = volume / 6.0;
  moments.first = first / 24.0;
  moments.second << squares.x(), products.x(), products.z(),  //
      products.x(), squares.y(), products.y(),                //
      products.z(), products.y(), squares.z();
  return moments;
}

// ---- Winding-number method ----------------------------------------------------------------

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t size) : parent_(size) {
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }
  std::uint32_t find(std::uint32_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];  // path halving
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<std::uint32_t> parent_;
};

// The mesh M with caps C: one fan per connected piece of its boundary, from the piece's
// centroid. Each cap triangle runs a boundary edge backwards, so ∂C = −∂M and M + C is closed;
// its winding number is then an integer a ray counts exactly, and since the solid angle is
// linear in the surface, w_M = w_{M+C} − w_C needs the solid angles of the few cap triangles
// only.
struct CappedSurface {
  TriangleMesh closed;  // M's triangles, then C's; the caps' apexes follow M's vertices
  TriangleMesh caps;    // C alone, over the same vertices
};

CappedSurface cap_boundary(std::vector<Vec3d> vertices, const std::vector<Triangle>& triangles,
                           const std::vector<DirectedEdge>& boundary) {
  DisjointSets pieces(vertices.size());
  std::vector<std::uint32_t> boundary_vertices;
  for (const DirectedEdge& edge : boundary) {
    pieces.join(edge.from, edge.to);
    boundary_vertices.insert(boundary_vertices.end(), {edge.from, edge.to});
  }
  std::sort(boundary_vertices.begin(), boundary_vertices.end());
  boundary_vertices.erase(std::unique(boundary_vertices.begin(), boundary_vertices.end()),
                          boundary_vertices.end());

  constexpr std::uint32_t kNoApex = ~std::uint32_t{0};
  std::vector<std::uint32_t> apex_of_piece(vertices.size(), kNoApex);
  std::vector<Vec3d> sums;
  std::vector<double> counts;
  for (const std::uint32_t v : boundary_vertices) {
    std::uint32_t& apex = apex_of_piece[pieces.find(v)];
    if (apex == kNoApex) {
      apex = static_cast<std::uint32_t>(vertices.size() + sums.size());
      sums.emplace_back(Vec3d::Zero());
      counts.push_back(0.0);
    }
    sums[apex - vertices.size()] += vertices[v];
    counts[apex - vertices.size()] += 1.0;
  }
  for (std::size_t piece = 0; piece < sums.size(); ++piece) {
    vertices.push_back(sums[piece] / counts[piece]);
  }

  CappedSurface surface;
  for (const DirectedEdge& edge : boundary) {
    surface.caps.triangles.push_back({edge.to, edge.from, apex_of_piece[pieces.find(edge.from)]});
  }
  surface.closed.triangles = triangles;
  surface.closed.triangles.insert(surface.closed.triangles.end(), surface.caps.triangles.begin(),
                                  surface.caps.triangles.end());
  if (!boundary.empty()) surface.caps.vertices = vertices;
  surface.closed.vertices = std::move(vertices);
  return surface;
}

// Square cells over the x–z extent, `columns` of them along the longer side; the shorter side
// gets as many as it needs, centred so that any overhang is the same on both sides.
struct ColumnGrid {
  double cell = 0.0;
  double x0 = 0.0;  // lower corner
  double z0 = 0.0;
  int nx = 0;
  int nz = 0;

  [[nodiscard]] double x_at(int i) const { return x0 + (i + 0.5) * cell; }
  [[nodiscard]] double z_at(int k) const { return z0 + (k + 0.5) * cell; }
};

ColumnGrid make_grid(const Box3d& bounds, int columns) {
  const Vec3d sizes = bounds.sizes();
  const double longer = std::max(sizes.x(), sizes.z());
  ColumnGrid grid;
  if (!(longer > 0.0)) return grid;  // flat in x–z: no column crosses it
  grid.cell = longer / columns;
  const auto cells = [&](double width) {
    // The tolerance stops a side that is a whole number of cells from gaining one by rounding.
    if (width == longer) return columns;
    return std::max(1, static_cast<int>(std::ceil(width / grid.cell - 1e-9)));
  };
  grid.nx = cells(sizes.x());
  grid.nz = cells(sizes.z());
  grid.x0 = bounds.center().x() - 0.5 * grid.nx * grid.cell;
  grid.z0 = bounds.center().z() - 0.5 * grid.nz * grid.cell;
  return grid;
}

// The first and last of n cells (origin, cell) whose centres lie in [low, high]. Widened by a
// hair so that rounding cannot drop a centre on the boundary; the crossing test decides.
std::pair<int, int> centres_within(double low, double high, double origin, double cell, int n) {
  constexpr double kPad = 1e-9;
  const double first = std::ceil((low - origin) / cell - 0.5 - kPad);
  const double last = std::floor((high - origin) / cell - 0.5 + kPad);
  return {static_cast<int>(std::max(first, 0.0)), static_cast<int>(std::min(last, n - 1.0))};
}

// The integrals along one column (x, z fixed) of the inside intervals: ∫dy, ∫y dy, ∫y² dy.
struct ColumnIntegral {
  double length = 0.0;
  double y = 0.0;
  double y_squared = 0.0;
};

struct Crossing {
  double y;
  int sign;  // +1 where the column enters the closed surface going up (a downward-facing side)
};

// Which side of edge (a, b) in the x–z plane a column passes, and twice the area of the
// triangle (column, a, b). Computed from the lower-indexed end, so the two triangles sharing an
// edge see exactly opposite values. An exact zero (a column through an edge or a vertex) is
// decided as if the column were moved by (ε, ε²), Edelsbrunner & Mücke's "simulation of
// simplicity" (1990): the same for every triangle, so such a column crosses exactly one of the
// triangles around the edge or vertex.
struct EdgeSide {
  double area;
  int sign;
};

EdgeSide edge_side(const std::vector<Vec3d>& vertices, std::uint32_t a, std::uint32_t b, double x,
                   double z) {
  if (a > b) {
    const EdgeSide flipped = edge_side(vertices, b, a, x, z);
    return {-flipped.area, -flipped.sign};
  }
  const Vec3d& pa = vertices[a];
  const Vec3d& pb = vertices[b];
  const double area = (pa.x() - x) * (pb.z() - z) - (pa.z() - z) * (pb.x() - x);
  if (area != 0.0) return {area, area > 0.0 ? 1 : -1};
  // d(area) = ε (a_z − b_z) + ε² (b_x − a_x)
  if (pa.z() != pb.z()) return {0.0, pa.z() > pb.z() ? 1 : -1};
  return {0.0, pb.x() > pa.x() ? 1 : -1};
}

// Where the column at (x, z) crosses a triangle, if it does.
std::optional<Crossing> cross(const TriangleMesh& mesh, const Triangle& triangle, double x,
                              double z) {
  const EdgeSide e01 = edge_side(mesh.vertices, triangle[0], triangle[1], x, z);
  const EdgeSide e12 = edge_side(mesh.vertices, triangle[1], triangle[2], x, z);
  const EdgeSide e20 = edge_side(mesh.vertices, triangle[2], triangle[0], x, z);
  if (e01.sign != e12.sign || e12.sign != e20.sign) return std::nullopt;
  // Barycentric weights: a corner's is the area the column cuts off opposite it.
  const double w0 = std::abs(e12.area);
  const double w1 = std::abs(e20.area);
  const double w2 = std::abs(e01.area);
  const double total = w0 + w1 + w2;
  if (total == 0.0) return std::nullopt;  // a sliver that rounding flattened
  const double y = (w0 * mesh.vertices[triangle[0]].y() + w1 * mesh.vertices[triangle[1]].y() +
                    w2 * mesh.vertices[triangle[2]].y()) /
                   total;
  // All sides positive: counter-clockwise in (x, z), so the normal's y component is negative.
  return Crossing{y, e01.sign};
}

// Ids listed under each of `count` buckets, each id under the buckets [first, last] that
// range_of(id) gives, in the order the ids come: compressed rows built by a counting sort.
struct Buckets {
  std::vector<std::size_t> start;  // bucket b holds ids[start[b]] up to ids[start[b + 1]]
  std::vector<std::uint32_t> ids;

  [[nodiscard]] std::span<const std::uint32_t> operator[](int bucket) const {
    const auto b = static_cast<std::size_t>(bucket);
    return {ids.data() + start[b], ids.data() + start[b + 1]};
  }
};

template <typename RangeOf>
Buckets make_buckets(int count, std::span<const std::uint32_t> ids, RangeOf range_of) {
  Buckets buckets;
  buckets.start.assign(static_cast<std::size_t>(count) + 1, 0);
  for (const std::uint32_t id : ids) {
    const auto [first, last] = range_of(id);
    for (int b = first; b <= last; ++b) ++buckets.start[static_cast<std::size_t>(b) + 1];
  }
  std::partial_sum(buckets.start.begin(), buckets.start.end(), buckets.start.begin());
  buckets.ids.resize(buckets.start.back());
  std::vector<std::size_t> next(buckets.start.begin(), buckets.start.end() - 1);
  for (const std::uint32_t id : ids) {
    const auto [first, last] = range_of(id);
    for (int b = first; b <= last; ++b) buckets.ids[next[static_cast<std::size_t>(b)]++] = id;
  }
  return buckets;
}

// Integrates the region with generalized winding number >= 1/2 column by column along y. Every
// crossing of the closed surface M + C splits a column; between two crossings the winding number
// of M is continuous and away from holes constant, so one evaluation at the midpoint classifies
// the interval, and the interval is integrated exactly in y.
class ColumnIntegrator {
 public:
  ColumnIntegrator(const CappedSurface& surface, const ColumnGrid& grid)
      : surface_(surface), grid_(grid) {
    footprints_.reserve(surface_.closed.triangles.size());
    for (const Triangle& triangle : surface_.closed.triangles) {
      footprints_.push_back(footprint(triangle));
    }
    // Each triangle under every row of columns it may cross.
    std::vector<std::uint32_t> triangles(footprints_.size());
    std::iota(triangles.begin(), triangles.end(), std::uint32_t{0});
    rows_ = make_buckets(grid_.nx, triangles, [&](std::uint32_t t) {
      return std::pair(footprints_[t].i0, footprints_[t].i1);
    });
  }

  // Rows in parallel, summed in row order so that every run gives the same bits.
  [[nodiscard]] Moments integrate() const {
    std::vector<Moments> rows(static_cast<std::size_t>(grid_.nx));
    tbb::parallel_for(tbb::blocked_range<int>(0, grid_.nx), [&](const tbb::blocked_range<int>& r) {
      for (int i = r.begin(); i != r.end(); ++i) rows[static_cast<std::size_t>(i)] = row(i);
    });
    Moments total;
    for (const Moments& moments : rows) total += moments;
    return total;
  }

 private:
  // The columns whose centres a triangle's x–z bounding box covers; empty for a triangle seen
  // edge-on from above, which no column crosses.
  struct Footprint {
    int i0 = 0;
    int i1 = -1;
    int k0 = 0;
    int k1 = -1;
  };

  [[nodiscard]] Footprint footprint(const Triangle& triangle) const {
    const Vec3d& a = surface_.closed.vertices[triangle[0]];
    const Vec3d& b = surface_.closed.vertices[triangle[1]];
    const Vec3d& c = surface_.closed.vertices[triangle[2]];
    if ((b.x() - a.x()) * (c.z() - a.z()) - (b.z() - a.z()) * (c.x() - a.x()) == 0.0) return {};
    const Vec3d low = a.cwiseMin(b).cwiseMin(c);
    const Vec3d high = a.cwiseMax(b).cwiseMax(c);
    const auto [i0, i1] = centres_within(low.x(), high.x(), grid_.x0, grid_.cell, grid_.nx);
    const auto [k0, k1] = centres_within(low.z(), high.z(), grid_.z0, grid_.cell, grid_.nz);
    return {i0, i1, k0, k1};
  }

  [[nodiscard]] Moments row(int i) const {
    // The row's triangles sorted into its columns.
    const Buckets columns = make_buckets(grid_.nz, rows_[i], [&](std::uint32_t t) {
      return std::pair(footprints_[t].k0, footprints_[t].k1);
    });
    Moments moments;
    const double x = grid_.x_at(i);
    for (int k = 0; k < grid_.nz; ++k) {
      if (columns[k].empty()) continue;
      const double z = grid_.z_at(k);
      add_column(moments, x, z, column(x, z, columns[k]));
    }
    return moments;
  }

  [[nodiscard]] ColumnIntegral column(double x, double z,
                                      std::span<const std::uint32_t> candidates) const {
    std::vector<Crossing> crossings;
    for (const std::uint32_t t : candidates) {
      if (const auto crossing = cross(surface_.closed, surface_.closed.triangles[t], x, z)) {
        crossings.push_back(*crossing);
      }
    }
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& a, const Crossing& b) {
      return a.y < b.y || (a.y == b.y && a.sign < b.sign);
    });
    ColumnIntegral integral;
    int closed_winding = 0;  // of M + C above crossing k: the signed crossings below
    for (std::size_t k = 0; k + 1 < crossings.size(); ++k) {
      closed_winding += crossings[k].sign;
      const double y0 = crossings[k].y;
      const double y1 = crossings[k + 1].y;
      if (!(y1 > y0)) continue;
      const Vec3d midpoint(x, 0.5 * (y0 + y1), z);
      if (closed_winding - winding_number(surface_.caps, midpoint) < 0.5) continue;
      const double length = y1 - y0;
      integral.length += length;
      integral.y += length * 0.5 * (y0 + y1);
      integral.y_squared += length * (y0 * y0 + y0 * y1 + y1 * y1) / 3.0;
    }
    return integral;
  }

  // A column stands for its whole cell: x and z vary over the cell while y is integrated
  // exactly, so ∫x² over the cell is A·(x² + cell²/12) and the mixed terms use the centre.
  void add_column(Moments& moments, double x, double z, const ColumnIntegral& c) const {
    const double area = grid_.cell * grid_.cell;
    const double spread = grid_.cell * grid_.cell / 12.0;
    moments.volume += area * c.length;
    moments.first += area * Vec3d(x * c.length, c.y, z * c.length);
    Mat3d second;
    second << (x * x + spread) * c.length, x * c.y, x * z * c.length,  //
        x * c.y, c.y_squared, z * c.y,                                 //
        x * z * c.length, z * c.y, (z * z + spread) * c.length;
    moments.second += area * second;
  }

  const CappedSurface& surface_;
  ColumnGrid grid_;
  std::vector<Footprint> footprints_;
  Buckets rows_;
};

Moments winding_number_moments(std::vector<Vec3d> vertices, const std::vector<Triangle>& triangles,
                               const std::vector<DirectedEdge>& boundary, int columns) {
  const CappedSurface surface = cap_boundary(std::move(vertices), triangles, boundary);
  // The caps' apexes lie inside the boundary's hull, so these are the mesh's bounds.
  const ColumnGrid grid = make_grid(surface.closed.bounds(), columns);
  if (grid.nx == 0) return {};
  return ColumnIntegrator(surface, grid).integrate();
}

// ---- Common -------------------------------------------------------------------------------

void set_principal_axes(MassProperties& properties) {
  const Eigen::SelfAdjointEigenSolver<Mat3d> solver(properties.inertia);
  properties.principal_moments = solver.eigenvalues();  // ascending
  properties.principal_axes = solver.eigenvectors();
  if (properties.principal_axes.determinant() < 0.0) properties.principal_axes.col(2) *= -1.0;
}

MassProperties from_moments(const Moments& moments, const Vec3d& reference, double extent,
                            const TriangleMesh& mesh, const MassPropertiesOptions& options) {
  if (!(moments.volume > kMinRelativeVolume * extent * extent * extent)) {
    throw Error::in_file(
        mesh.name, "is inside out or encloses no volume (volume " + to_text(moments.volume) + ")");
  }
  MassProperties properties;
  properties.volume = moments.volume;
  properties.mass = options.density * moments.volume;
  const Vec3d center = moments.first / moments.volume;
  properties.center_of_mass = reference + center;
  // ∫r·rᵀ about the centre of mass, then I = ρ (tr(S)·1 − S).
  const Mat3d central = moments.second - moments.volume * center * center.transpose();
  properties.inertia = options.density * (central.trace() * Mat3d::Identity() - central);
  set_principal_axes(properties);
  return properties;
}

}  // namespace

MassProperties compute_mass_properties(const TriangleMesh& mesh,
                                       const MassPropertiesOptions& options) {
  validate(mesh, options);
  const EdgeSummary edges = summarize_edges(mesh.vertices.size(), mesh.triangles);
  const Box3d bounds = mesh.bounds();
  const Vec3d reference = bounds.center();
  std::vector<Vec3d> shifted;
  shifted.reserve(mesh.vertices.size());
  for (const Vec3d& v : mesh.vertices) shifted.push_back(v - reference);

  const MassMethod method = edges.watertight && !options.force_winding_number
                                ? MassMethod::Polyhedral
                                : MassMethod::WindingNumber;
  const Moments moments = method == MassMethod::Polyhedral
                              ? polyhedral_moments(shifted, mesh.triangles)
                              : winding_number_moments(std::move(shifted), mesh.triangles,
                                                       edges.boundary, options.columns);
  MassProperties properties =
      from_moments(moments, reference, bounds.sizes().maxCoeff(), mesh, options);
  properties.method = method;
  return properties;
}

}  // namespace sphys::tools
