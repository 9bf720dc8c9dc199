#include "sphys/tools/protrusion_cover.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <queue>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "coverage.h"
#include "grid_cells.h"
#include "sphys/error.h"
#include "sphys/tools/mesh_query.h"
#include "surface_samples.h"

namespace sphys::tools {
namespace {

using build::Ball;

// The samples a cover must reach: enough that the pieces between samples are small beside a
// link, few enough that one cover costs milliseconds; more (up to kMaxCoverSamples) when a small
// bound asks for them. The lattice of surface samples has at least three per triangle; a finely
// meshed part keeps every `stride`-th so that about the number asked for remain.
constexpr std::size_t kCoverSamples = 5000;
constexpr std::size_t kMaxCoverSamples = 60000;
// One sample in this many grows candidates, at most kMaxGenerators of them.
constexpr std::size_t kSamplesPerGenerator = 10;
constexpr std::size_t kMaxGenerators = 4000;
// Candidates step down the inward normal from one sample spacing, each this many times deeper
// than the last, until the depth falls below kPastMedial of the deepest so far: the centre has
// then crossed the medial axis and comes nearer the opposite side.
constexpr double kDepthRatio = 2.0;
constexpr double kPastMedial = 0.7;
// Golden-section steps for the deepest point: 0.618^12 of the bracket, 0.3% of it.
constexpr int kMedialSearchSteps = 12;
// Grid cells are at least this fraction of the mesh's diagonal, so a grid has at most about
// 64³ cells.
constexpr double kFinestCell = 1.0 / 64.0;

// A candidate's centre and its distance to the surface (0 on the surface). unit: m
struct CoverCandidate {
  Vec3d centre;
  double depth = 0.0;
};

// The samples bucketed in a uniform grid, for "which samples lie in this ball".
class SampleGrid {
 public:
  SampleGrid(const std::vector<Vec3d>& points, const Box3d& bounds, double cell)
      : points_(points), grid_(bounds, cell) {
    std::vector<std::uint32_t> count(grid_.count() + 1, 0);
    for (const Vec3d& p : points) ++count[grid_.index(grid_.cell_of(p)) + 1];
    for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    start_ = count;
    order_.resize(points.size());
    for (std::uint32_t i = 0; i < points.size(); ++i) {
      order_[count[grid_.index(grid_.cell_of(points[i]))]++] = i;
    }
  }

  // Calls visit(i) for every sample i within `radius` of `centre`.
  template <typename Visit>
  void for_each_in_ball(const Vec3d& centre, double radius, Visit visit) const {
    const std::array<int, 3> low = grid_.cell_of(centre - Vec3d::Constant(radius));
    const std::array<int, 3> high = grid_.cell_of(centre + Vec3d::Constant(radius));
    const double r2 = radius * radius;
    for (int z = low[2]; z <= high[2]; ++z) {
      for (int y = low[1]; y <= high[1]; ++y) {
        for (int x = low[0]; x <= high[0]; ++x) {
          const std::size_t c = grid_.index({x, y, z});
          for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
            if ((points_[order_[k]] - centre).squaredNorm() <= r2) visit(order_[k]);
          }
        }
      }
    }
  }

 private:
  const std::vector<Vec3d>& points_;
  build::GridCells grid_;
  std::vector<std::uint32_t> start_;  // per cell, where its samples begin in order_
  std::vector<std::uint32_t> order_;  // sample indices, cell by cell
};

// The outward unit normal at a sample, from its triangle and the inside test (triangles may be
// flipped), or nothing where the surface has no inside on either hand (an open sheet, a sliver).
std::optional<Vec3d> outward_normal(const TriangleMesh& mesh, const MeshQuery& query,
                                    const Vec3d& point, std::uint32_t triangle, double step) {
  const Vec3d normal = mesh.area_normal(triangle);
  if (!(normal.norm() > 0.0)) return std::nullopt;
  const Vec3d n = normal.normalized();
  const bool behind = query.inside(point - step * n);
  const bool ahead = query.inside(point + step * n);
  if (behind && !ahead) return n;
  if (ahead && !behind) return -n;
  return std::nullopt;
}

}  // namespace

struct ProtrusionCover::Impl {
  Impl(const TriangleMesh& mesh_in, std::size_t sample_count)
      : mesh(mesh_in),
        query(mesh),
        samples(build::sample_surface(mesh, sample_count)),
        bounds(mesh.bounds()),
        diagonal(bounds.diagonal().norm()) {
    // A finely meshed part: thin the lattice (it holds every triangle's corners) to about
    // sample_count, and widen the spacing by as much.
    if (samples.points.size() > 2 * sample_count) {
      const std::size_t stride = samples.points.size() / sample_count;
      build::SurfaceSamples kept;
      for (std::size_t i = 0; i < samples.points.size(); i += stride) {
        kept.points.push_back(samples.points[i]);
        kept.triangle.push_back(samples.triangle[i]);
      }
      kept.spacing = samples.spacing * std::sqrt(static_cast<double>(stride));
      samples = std::move(kept);
    }
    const std::size_t generators =
        std::min(kMaxGenerators, samples.points.size() / kSamplesPerGenerator + 1);
    const std::size_t stride = std::max<std::size_t>(1, samples.points.size() / generators);
    for (std::size_t i = 0; i < samples.points.size(); i += stride) {
      const Vec3d& p = samples.points[i];
      candidates.push_back({p, 0.0});
      const std::optional<Vec3d> n =
          outward_normal(mesh, query, p, samples.triangle[i], 1e-6 * diagonal);
      if (!n) continue;
      add_ladder(p, *n);
    }
    std::vector<double> depths;
    for (const CoverCandidate& c : candidates) depths.push_back(c.depth);
    std::nth_element(depths.begin(),
                     depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2), depths.end());
    median_depth = depths[depths.size() / 2];
  }

  // Candidates down the inward normal `n` from surface point `p`: a ladder of depths, then the
  // deepest point along the normal (the medial axis, where a ball of the least protrusion for
  // its reach sits), found by golden-section search between the ladder's rungs around the deepest.
  // Depths are distances to the surface, the costly inside test made once per candidate kept (a
  // rung may have jumped across a thin wall).
  void add_ladder(const Vec3d& p, const Vec3d& n) {
    const auto depth_at = [&](double t) { return query.distance(p - t * n); };
    const auto add = [&](double t, double depth) {
      if (query.inside(p - t * n)) candidates.push_back({p - t * n, depth});
    };
    std::vector<std::pair<double, double>> rungs{{0.0, 0.0}};  // t, depth
    double deepest = 0.0;
    for (double t = samples.spacing; t < diagonal; t *= kDepthRatio) {
      const double depth = depth_at(t);
      rungs.push_back({t, depth});
      if (!(depth > kPastMedial * deepest)) break;
      deepest = std::max(deepest, depth);
      add(t, depth);
    }
    if (!(deepest > 0.0)) return;
    std::size_t best = 0;
    for (std::size_t k = 1; k < rungs.size(); ++k) {
      if (rungs[k].second > rungs[best].second) best = k;
    }
    double low = rungs[best - 1].first;
    double high = best + 1 < rungs.size() ? rungs[best + 1].first : rungs[best].first;
    // Golden-section search: one new depth per step.
    const double shrink = 0.5 * (std::sqrt(5.0) - 1.0);
    double a = high - shrink * (high - low);
    double b = low + shrink * (high - low);
    double depth_a = depth_at(a);
    double depth_b = depth_at(b);
    for (int step = 0; step < kMedialSearchSteps; ++step) {
      if (depth_a < depth_b) {
        low = a;
        a = b;
        depth_a = depth_b;
        b = low + shrink * (high - low);
        depth_b = depth_at(b);
      } else {
        high = b;
        b = a;
        depth_b = depth_a;
        a = high - shrink * (high - low);
        depth_a = depth_at(a);
      }
    }
    const double t = 0.5 * (low + high);
    const double depth = depth_at(t);
    if (depth > deepest) add(t, depth);
  }

  // Greedy set cover of the samples by the candidates grown to protrusion `bound`. Stops once
  // more than `limit` balls are chosen.
  [[nodiscard]] std::vector<Ball> choose(double bound, std::size_t limit) const {
    if (!(std::isfinite(bound) && bound > 0.0)) {
      throw Error("a protrusion bound must be positive and finite (unit: m)");
    }
    // A sample counts as covered only when the surface within `margin` of it is covered too
    // (every surface point is within spacing/√3 of a sample). Where the surface is a plane at
    // distance h from the centre, the ball meets it in a disc of radius a = √(r² - h²), and the
    // sample must lie within a - margin of the disc's centre: |q - c|² ≤ r² - 2·margin·a +
    // margin². The centre's depth t ≤ h stands in for h, which only makes the test stricter.
    const double margin = std::min(samples.spacing / std::sqrt(3.0), 0.5 * bound);
    const auto counting_radius = [&](double depth) {
      const double r = depth + bound;
      const double disc = std::sqrt(std::max(0.0, r * r - depth * depth));
      return std::sqrt(std::max(0.0, r * r - 2.0 * margin * disc + margin * margin));
    };
    const SampleGrid grid(samples.points, bounds,
                          std::max(bound + median_depth, kFinestCell * diagonal));
    std::vector<char> covered(samples.points.size(), 0);
    const auto uncovered_in = [&](const CoverCandidate& c) {
      std::size_t n = 0;
      grid.for_each_in_ball(c.centre, counting_radius(c.depth),
                            [&](std::uint32_t i) { n += covered[i] == 0; });
      return n;
    };
    std::vector<std::size_t> gain(candidates.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size()),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t c = range.begin(); c != range.end(); ++c) {
                          gain[c] = uncovered_in(candidates[c]);
                        }
                      });
    // Lazy greedy: a candidate's gain only falls as others are chosen, so one whose recomputed
    // gain still tops the queue is the best. Ties go to the lower index: the same every run.
    using Entry = std::pair<std::size_t, std::size_t>;  // gain, candidate
    const auto lower = [](const Entry& a, const Entry& b) {
      return a.first != b.first ? a.first < b.first : a.second > b.second;
    };
    std::priority_queue<Entry, std::vector<Entry>, decltype(lower)> queue(lower);
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (gain[c] > 0) queue.push({gain[c], c});
    }
    std::vector<Ball> chosen;
    const auto take = [&](const CoverCandidate& c) {
      chosen.push_back({c.centre, c.depth + bound});
      grid.for_each_in_ball(c.centre, counting_radius(c.depth),
                            [&](std::uint32_t i) { covered[i] = 1; });
    };
    while (!queue.empty() && chosen.size() <= limit) {
      const auto [stale, c] = queue.top();
      queue.pop();
      const std::size_t fresh = uncovered_in(candidates[c]);
      if (fresh == 0) continue;
      if (fresh < stale && !queue.empty() && lower(Entry{fresh, c}, queue.top())) {
        queue.push({fresh, c});
        continue;
      }
      take(candidates[c]);
    }
    // Samples no candidate reaches (far from every generator when the bound is small) get a ball
    // of their own, centred on them.
    for (std::size_t i = 0; i < samples.points.size() && chosen.size() <= limit; ++i) {
      if (covered[i] == 0) take({samples.points[i], 0.0});
    }
    return chosen;
  }

  TriangleMesh mesh;
  MeshQuery query;
  build::SurfaceSamples samples;
  Box3d bounds;
  double diagonal = 0.0;
  std::vector<CoverCandidate> candidates;
  double median_depth = 0.0;
};

ProtrusionCover::ProtrusionCover(const TriangleMesh& mesh, double finest_bound) {
  if (mesh.triangles.empty()) throw Error::in_file(mesh.name, "the mesh has no triangles");
  std::size_t sample_count = kCoverSamples;
  if (finest_bound > 0.0) {
    // The lattice puts about 2 / spacing² samples on each unit of area; a spacing of half the
    // bound keeps the certificate's growth well inside it.
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      area += 0.5 * mesh.area_normal(t).norm();
    const double wanted = 8.0 * area / (finest_bound * finest_bound);
    sample_count = static_cast<std::size_t>(std::clamp(wanted, static_cast<double>(kCoverSamples),
                                                       static_cast<double>(kMaxCoverSamples)));
  }
  impl_ = std::make_unique<Impl>(mesh, sample_count);
}

ProtrusionCover::~ProtrusionCover() = default;
ProtrusionCover::ProtrusionCover(ProtrusionCover&&) noexcept = default;
ProtrusionCover& ProtrusionCover::operator=(ProtrusionCover&&) noexcept = default;

std::vector<Sphere> ProtrusionCover::cover(double max_protrusion) const {
  return build::certified_spheres(
      impl_->choose(max_protrusion, std::numeric_limits<std::size_t>::max()), impl_->mesh);
}

std::size_t ProtrusionCover::count(double max_protrusion, std::size_t stop_after) const {
  return impl_->choose(max_protrusion, stop_after).size();
}

double ProtrusionCover::spacing() const { return impl_->samples.spacing; }

}  // namespace sphys::tools
