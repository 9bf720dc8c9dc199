#include "sphys/tools/tree_quality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "ball.h"
#include "grid_cells.h"
#include "sphys/error.h"
#include "sphys/tools/mass_properties.h"

namespace sphys::tools {
namespace {

// Samples per parallel task. Fixed, so how the work is split (and with it every per-chunk
// result) does not depend on the number of threads.
constexpr std::size_t kChunk = 1024;

// A boundary point counts as inside another sphere only when it is inside by more than this
// fraction of the diagonal, so that a sphere and its duplicate do not hide each other.
constexpr double kStrictlyInside = 1e-9;

// SplitMix64 (Steele, Lea & Flood 2014) read as a counter-based generator: draw k of a stream is
// mix(base + (k + 1)·γ), exactly the k-th output of the serial generator, so any sample can be
// drawn on any thread and the figures stay identical on every platform.
constexpr std::uint64_t kGamma = 0x9E3779B97F4A7C15ULL;

std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

class RandomStream {
 public:
  // `purpose` separates the streams of one seed.
  RandomStream(std::uint64_t seed, std::uint64_t purpose) : base_(mix(seed + purpose * kGamma)) {}

  // Uniform in [0, 1): the top 53 bits as the mantissa.
  [[nodiscard]] double uniform(std::uint64_t draw) const {
    return static_cast<double>(mix(base_ + (draw + 1) * kGamma) >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t base_;
};

using build::Ball;

// Runs body(chunk, begin, end) for every kChunk-sized piece of [0, count) in parallel and
// returns the chunks' results in chunk order.
template <typename Result, typename Body>
std::vector<Result> per_chunk(std::size_t count, const Body& body) {
  std::vector<Result> results((count + kChunk - 1) / kChunk);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, results.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& chunks) {
                      for (std::size_t c = chunks.begin(); c != chunks.end(); ++c) {
                        results[c] = body(c * kChunk, std::min(count, (c + 1) * kChunk));
                      }
                    });
  return results;
}

// A uniform grid over the spheres: each cell lists the spheres whose bounding box touches it, so
// "which spheres hold p" looks at one cell and "how far is the nearest sphere" at growing shells
// of cells instead of at every sphere.
class SphereGrid {
 public:
  SphereGrid(const std::vector<Ball>& balls, const Box3d& domain)
      : balls_(balls), grid_(domain, cell_size(balls, domain)) {
    // Two passes (count, then fill) give each cell a contiguous, sphere-ordered list.
    cell_begin_.assign(grid_.count() + 1, 0);
    for_each_ball_cell([&](std::size_t cell, std::uint32_t) { ++cell_begin_[cell + 1]; });
    for (std::size_t c = 0; c < grid_.count(); ++c) cell_begin_[c + 1] += cell_begin_[c];
    entries_.resize(cell_begin_.back());
    std::vector<std::size_t> fill(cell_begin_.begin(), cell_begin_.end() - 1);
    for_each_ball_cell(
        [&](std::size_t cell, std::uint32_t ball) { entries_[fill[cell]++] = ball; });
  }

  // Whether a sphere other than `skip` holds p, by more than `margin` when margin > 0.
  [[nodiscard]] bool covered(const Vec3d& p, double margin = 0.0,
                             std::uint32_t skip = kNone) const {
    const std::size_t cell = grid_.index(grid_.cell_of(p));
    for (std::size_t e = cell_begin_[cell]; e < cell_begin_[cell + 1]; ++e) {
      const std::uint32_t b = entries_[e];
      if (b == skip) continue;
      const double r = balls_[b].radius - margin;
      if (r >= 0.0 && (p - balls_[b].center).squaredNorm() <= r * r) return true;
    }
    return false;
  }

  // Distance from p to the nearest sphere's surface (negative inside). Searches shells of cells
  // around p's cell; a sphere listed only beyond shell k has its bounding box, and so its
  // surface, at least k cells from p, which ends the search once the best is within that.
  [[nodiscard]] double distance_to_nearest(const Vec3d& p) const {
    const std::array<int, 3> home = grid_.cell_of(p);
    const int last_shell = std::max({grid_.dims[0], grid_.dims[1], grid_.dims[2]});
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= last_shell && best > (k - 1) * grid_.cell; ++k) {
      for (int dz = -k; dz <= k; ++dz) {
        for (int dy = -k; dy <= k; ++dy) {
          const bool on_face = std::abs(dz) == k || std::abs(dy) == k;
          // Inside the shell only the two cells at dx = ±k are new.
          for (int dx = -k; dx <= k; dx += on_face ? 1 : std::max(1, 2 * k)) {
            const std::array<int, 3> c{home[0] + dx, home[1] + dy, home[2] + dz};
            if (!grid_.contains(c)) continue;
            const std::size_t cell = grid_.index(c);
            for (std::size_t e = cell_begin_[cell]; e < cell_begin_[cell + 1]; ++e) {
              const Ball& b = balls_[entries_[e]];
              best = std::min(best, (p - b.center).norm() - b.radius);
            }
          }
        }
      }
    }
    return best;
  }

  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

 private:
  // Cells about a sphere across, but not more than a few per sphere (spheres far apart).
  static double cell_size(const std::vector<Ball>& balls, const Box3d& domain) {
    std::vector<double> radii;
    radii.reserve(balls.size());
    for (const Ball& b : balls) radii.push_back(b.radius);
    std::nth_element(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2),
                     radii.end());
    const Vec3d extent = domain.sizes();
    const double max_cells = 8.0 * static_cast<double>(balls.size()) + 64.0;
    const double volume = std::max(extent.prod(), std::pow(extent.maxCoeff(), 3) * 1e-9);
    return std::max({2.0 * radii[radii.size() / 2], std::cbrt(volume / max_cells),
                     1e-9 * extent.maxCoeff(), std::numeric_limits<double>::min()});
  }
  template <typename Visit>
  void for_each_ball_cell(const Visit& visit) const {
    for (std::uint32_t b = 0; b < balls_.size(); ++b) {
      const Vec3d r = Vec3d::Constant(balls_[b].radius);
      const std::array<int, 3> lo = grid_.cell_of(balls_[b].center - r);
      const std::array<int, 3> hi = grid_.cell_of(balls_[b].center + r);
      for (int z = lo[2]; z <= hi[2]; ++z) {
        for (int y = lo[1]; y <= hi[1]; ++y) {
          for (int x = lo[0]; x <= hi[0]; ++x) visit(grid_.index({x, y, z}), b);
        }
      }
    }
  }

  const std::vector<Ball>& balls_;
  build::GridCells grid_;
  std::vector<std::size_t> cell_begin_;
  std::vector<std::uint32_t> entries_;
};

// What depends on the mesh and the options only, shared by every level of a tree.
struct Reference {
  const MeshQuery* query = nullptr;
  Box3d bounds;
  double diagonal = 0.0;
  double volume = 0.0;
  std::vector<Vec3d> surface_points;     // area-weighted random
  std::vector<Vec3d> sphere_directions;  // unit, evenly spread
};

void validate(const QualityOptions& options) {
  if (options.surface_samples == 0 || options.volume_samples == 0 ||
      options.boundary_samples == 0) {
    throw Error("tree quality: surface, volume and boundary sample counts must be positive");
  }
}

std::vector<Vec3d> sample_surface(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed) {
  std::vector<double> cumulative_area(mesh.triangles.size());
  double total = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    total += 0.5 * mesh.area_normal(t).norm();
    cumulative_area[t] = total;
  }
  const RandomStream random(seed, 1);
  std::vector<Vec3d> points(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kChunk),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        // upper_bound never picks a zero-area triangle.
                        const double at = random.uniform(3 * i) * total;
                        const auto it =
                            std::upper_bound(cumulative_area.begin(), cumulative_area.end(), at);
                        const auto t = static_cast<std::size_t>(
                            std::min(it - cumulative_area.begin(),
                                     static_cast<std::ptrdiff_t>(cumulative_area.size()) - 1));
                        // Uniform over the triangle: s = √u spreads the mass away from corner a.
                        const double s = std::sqrt(random.uniform(3 * i + 1));
                        const double v = random.uniform(3 * i + 2);
                        points[i] = (1.0 - s) * mesh.corner(t, 0) +
                                    s * (1.0 - v) * mesh.corner(t, 1) + s * v * mesh.corner(t, 2);
                      }
                    });
  return points;
}

Reference make_reference(const MeshQuery& query, const QualityOptions& options) {
  validate(options);
  const TriangleMesh& mesh = query.mesh();
  Reference reference;
  reference.query = &query;
  reference.bounds = mesh.bounds();
  reference.diagonal = reference.bounds.diagonal().norm();
  if (!(reference.diagonal > 0.0)) {
    throw Error::in_file(mesh.name, "has a point-sized bounding box, so quality is undefined");
  }
  if (options.require_volume) {
    reference.volume = compute_mass_properties(mesh).volume;
  } else {
    try {
      reference.volume = compute_mass_properties(mesh).volume;
    } catch (const Error&) {
      reference.volume = std::numeric_limits<double>::quiet_NaN();  // open or flat
    }
  }
  reference.surface_points = sample_surface(mesh, options.surface_samples, options.seed);
  reference.sphere_directions = build::evenly_spread_directions(options.boundary_samples);
  return reference;
}

std::vector<Ball> to_balls(std::span<const Sphere> spheres) {
  if (spheres.empty()) throw Error("tree quality: no spheres to measure");
  std::vector<Ball> balls;
  balls.reserve(spheres.size());
  for (const Sphere& s : spheres) {
    const Ball ball{s.center.cast<double>(), static_cast<double>(s.radius)};
    if (!ball.center.allFinite() || !std::isfinite(ball.radius) || ball.radius < 0.0) {
      throw Error("tree quality: a sphere has a non-finite centre or a bad radius");
    }
    balls.push_back(ball);
  }
  return balls;
}

struct Coverage {
  std::size_t covered = 0;
  double worst_gap = 0.0;
};

struct Boundary {
  double worst = 0.0;
};

LevelQuality measure(std::span<const Sphere> spheres, const Reference& reference,
                     const QualityOptions& options) {
  const std::vector<Ball> balls = to_balls(spheres);
  Box3d union_box;
  for (const Ball& b : balls) {
    union_box.extend(b.center - Vec3d::Constant(b.radius));
    union_box.extend(b.center + Vec3d::Constant(b.radius));
  }
  const SphereGrid grid(balls, union_box.merged(reference.bounds));
  const MeshQuery& query = *reference.query;

  LevelQuality quality;
  quality.spheres = balls.size();

  // Coverage and gap: surface samples outside every sphere, and how far the nearest one is.
  const std::vector<Vec3d>& surface = reference.surface_points;
  std::size_t covered = 0;
  for (const Coverage& chunk :
       per_chunk<Coverage>(surface.size(), [&](std::size_t begin, std::size_t end) {
         Coverage c;
         for (std::size_t i = begin; i < end; ++i) {
           if (grid.covered(surface[i])) {
             ++c.covered;
           } else {
             c.worst_gap = std::max(c.worst_gap, grid.distance_to_nearest(surface[i]));
           }
         }
         return c;
       })) {
    covered += chunk.covered;
    quality.worst_gap = std::max(quality.worst_gap, chunk.worst_gap);
  }
  quality.coverage = static_cast<double>(covered) / static_cast<double>(surface.size());
  quality.worst_gap /= reference.diagonal;

  // Tightness: Monte Carlo over the union's box; the cheap sphere test goes first, so the mesh
  // is asked only about points in the union.
  const RandomStream random(options.seed, 2);
  const Vec3d box_min = union_box.min();
  const Vec3d box_size = union_box.sizes();
  std::size_t outside_mesh = 0;
  for (const std::size_t count :
       per_chunk<std::size_t>(options.volume_samples, [&](std::size_t begin, std::size_t end) {
         std::size_t c = 0;
         for (std::size_t i = begin; i < end; ++i) {
           const Vec3d p = box_min + Vec3d(random.uniform(3 * i), random.uniform(3 * i + 1),
                                           random.uniform(3 * i + 2))
                                         .cwiseProduct(box_size);
           if (grid.covered(p) && !query.inside(p)) ++c;
         }
         return c;
       })) {
    outside_mesh += count;
  }
  const double union_outside_volume = static_cast<double>(outside_mesh) /
                                      static_cast<double>(options.volume_samples) * box_size.prod();
  quality.outside_volume_m3 = union_outside_volume;
  quality.outside_volume = union_outside_volume / reference.volume;

  // Protrusion: points of each sphere's surface that lie on the union's boundary and outside the
  // mesh. A point is asked whether it is inside the mesh only when it is farther from the mesh
  // than the chunk's best so far (the inside test is the costly one); that skips no candidate
  // for the maximum, so the figure is the same as testing every point.
  const std::vector<Vec3d>& directions = reference.sphere_directions;
  const double margin = kStrictlyInside * reference.diagonal;
  for (const Boundary& chunk : per_chunk<Boundary>(
           balls.size() * directions.size(), [&](std::size_t begin, std::size_t end) {
             Boundary c;
             for (std::size_t i = begin; i < end; ++i) {
               const auto b = static_cast<std::uint32_t>(i / directions.size());
               const Vec3d p =
                   balls[b].center + balls[b].radius * directions[i % directions.size()];
               if (grid.covered(p, margin, b)) continue;
               const double d = query.distance(p);
               if (d > c.worst && !query.inside(p)) c.worst = d;
             }
             return c;
           })) {
    quality.worst_protrusion = std::max(quality.worst_protrusion, chunk.worst);
  }
  quality.worst_protrusion_m = quality.worst_protrusion;
  quality.worst_protrusion /= reference.diagonal;
  return quality;
}

}  // namespace

LevelQuality measure_level(std::span<const Sphere> spheres, const MeshQuery& mesh,
                           const QualityOptions& options) {
  return measure(spheres, make_reference(mesh, options), options);
}

std::vector<LevelQuality> measure_tree(const SphereTree& tree, const MeshQuery& mesh,
                                       const QualityOptions& options) {
  std::vector<std::vector<Sphere>> levels;
  for (int level = 0; level < tree.depth(); ++level) {
    const std::span<const Sphere> spheres = tree.level_spheres(level);
    levels.emplace_back(spheres.begin(), spheres.end());
  }
  return measure_levels(levels, mesh, options);
}

std::vector<LevelQuality> measure_levels(std::span<const std::vector<Sphere>> levels,
                                         const MeshQuery& mesh, const QualityOptions& options) {
  const Reference reference = make_reference(mesh, options);
  std::vector<LevelQuality> qualities;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    qualities.push_back(measure(levels[level], reference, options));
    qualities.back().level = static_cast<int>(level);
  }
  return qualities;
}

}  // namespace sphys::tools
