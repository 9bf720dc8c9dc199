// Sphere sets for a robot's links: how many spheres each link gets, and what they are worth.
#include "sphys/tools/spherize.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "sphys/error.h"
#include "sphys/tools/mesh_query.h"
#include "sphys/tools/protrusion_cover.h"
#include "sphys/tools/tree_quality.h"

namespace sphys::tools {
namespace {

// A budget is met by bisecting the protrusion bound on a log scale this many times: the bound
// then lies within a factor kBoundRange^(-1 / 2^k) ≈ 1.0002 of the tightest that fits.
constexpr int kBisections = 16;
// The bounds searched for a budget: from the largest link's diagonal (one sphere each) down to
// this fraction of it.
constexpr double kBoundRange = 1e-5;
// A protrusion limit is met by lowering the bound given to the cover while the measured
// protrusion (the certificate may grow spheres) exceeds the limit, at most this often.
constexpr int kLimitTries = 8;

// The report's figures, sampled as tree-info samples a level; links may be open meshes.
QualityOptions report_quality() {
  QualityOptions options;
  options.require_volume = false;
  return options;
}

// The protrusion alone, for meeting a limit: it depends only on the spheres, the mesh and the
// boundary samples, which are the report's, so the protrusion that met the limit is the one
// reported; the coverage and volume figures, not needed here, get few samples.
QualityOptions protrusion_quality() {
  QualityOptions options = report_quality();
  options.surface_samples = 1000;
  options.volume_samples = 1000;
  return options;
}

// The spheres of one link for a bound, grown by the gap between the meshed and the true
// primitives so that the true shape is covered too.
std::vector<Sphere> link_spheres(const ProtrusionCover& cover, const LinkGeometry& link,
                                 double bound) {
  std::vector<Sphere> spheres = cover.cover(bound);
  for (Sphere& s : spheres) s.radius += static_cast<float>(link.tessellation_error);
  return spheres;
}

Sphere bounding_sphere(const std::vector<Sphere>& spheres) {
  // Ritter-style: the box's centre, then the farthest sphere's far side decides the radius. Not
  // the smallest, but it holds every sphere, which is what a first level needs.
  Eigen::AlignedBox3f box;
  for (const Sphere& s : spheres) {
    box.extend(s.center - Vec3::Constant(s.radius));
    box.extend(s.center + Vec3::Constant(s.radius));
  }
  const Vec3 centre = box.center();
  float radius = 0.0f;
  for (const Sphere& s : spheres) radius = std::max(radius, (s.center - centre).norm() + s.radius);
  // Rounding of the sum above must not leave a sphere poking out.
  return {centre, radius * (1.0f + 4.0f * std::numeric_limits<float>::epsilon())};
}

void validate(const Robot& robot, const SpherizeOptions& options) {
  if (options.total_spheres.has_value() == options.max_protrusion.has_value()) {
    throw Error(options.total_spheres ? "give --spheres or --max-protrusion, not both"
                                      : "give --spheres N or --max-protrusion D");
  }
  const auto links = static_cast<int>(robot.links.size());
  if (options.total_spheres && *options.total_spheres < links) {
    throw Error("--spheres: " + std::to_string(*options.total_spheres) + " is fewer than the " +
                std::to_string(links) + " links with geometry (each needs at least one)");
  }
  if (options.max_protrusion &&
      !(std::isfinite(*options.max_protrusion) && *options.max_protrusion > 0.0)) {
    throw Error("--max-protrusion must be positive and finite (unit: m)");
  }
}

// One bound for every link, the tightest whose spheres fit the budget: the robot's worst
// protrusion, what a planner's clearance must allow for, is then as small as the covers allow,
// and no link is tighter than it needs to be at another's expense.
std::vector<std::vector<Sphere>> share_budget(const Robot& robot,
                                              const std::vector<ProtrusionCover>& covers, int total,
                                              const SpherizeOptions& options) {
  double largest = 0.0;
  for (const LinkGeometry& link : robot.links) {
    largest = std::max(largest, link.mesh.bounds().diagonal().norm());
  }
  const auto budget = static_cast<std::size_t>(total);
  // Each link's count stops once it alone would overrun what the others left.
  const auto fits = [&](double bound) {
    std::size_t spheres = 0;
    for (const ProtrusionCover& cover : covers) {
      spheres += cover.count(bound, budget - spheres);
      if (spheres > budget) return false;
    }
    return true;
  };
  double high = largest;  // fits: one sphere per link reaches everything
  double low = largest * kBoundRange;
  if (fits(low)) {
    high = low;
  } else {
    for (int k = 0; k < kBisections; ++k) {
      const double middle = std::sqrt(low * high);
      (fits(middle) ? high : low) = middle;
      if (options.progress) options.progress(0.9 * (k + 1) / kBisections);
    }
  }
  std::vector<std::vector<Sphere>> spheres;
  for (std::size_t i = 0; i < covers.size(); ++i) {
    spheres.push_back(link_spheres(covers[i], robot.links[i], high));
  }
  return spheres;
}

// The link's spheres for the bound that keeps the measured protrusion within the limit.
std::vector<Sphere> meet_protrusion(const ProtrusionCover& cover, const LinkGeometry& link,
                                    const MeshQuery& query, double limit) {
  double bound = limit - link.tessellation_error;
  for (int attempt = 0; attempt < kLimitTries && bound > 0.0; ++attempt) {
    std::vector<Sphere> spheres = link_spheres(cover, link, bound);
    const double protrusion =
        measure_level(spheres, query, protrusion_quality()).worst_protrusion_m;
    if (protrusion <= limit) return spheres;
    // The certificate grew some sphere by protrusion - bound; ask for that much less.
    bound -= 1.1 * (protrusion - bound) + 0.05 * bound;
  }
  throw Error::in_file(link.mesh.name, "no cover within --max-protrusion " + std::to_string(limit) +
                                           " m: the surface samples are " +
                                           std::to_string(cover.spacing()) +
                                           " m apart; ask for a larger protrusion");
}

}  // namespace

std::vector<LinkSpheres> spherize(const Robot& robot, const SpherizeOptions& options) {
  validate(robot, options);
  std::vector<ProtrusionCover> covers;
  std::vector<MeshQuery> queries;
  covers.reserve(robot.links.size());
  queries.reserve(robot.links.size());
  for (const LinkGeometry& link : robot.links) {
    covers.emplace_back(link.mesh, options.max_protrusion.value_or(0.0));
    queries.emplace_back(link.mesh);
  }
  std::vector<std::vector<Sphere>> spheres;
  if (options.total_spheres) {
    spheres = share_budget(robot, covers, *options.total_spheres, options);
  } else {
    for (std::size_t i = 0; i < covers.size(); ++i) {
      spheres.push_back(
          meet_protrusion(covers[i], robot.links[i], queries[i], *options.max_protrusion));
      if (options.progress) {
        options.progress(0.9 * static_cast<double>(i + 1) / static_cast<double>(covers.size()));
      }
    }
  }
  std::vector<LinkSpheres> result;
  for (std::size_t i = 0; i < covers.size(); ++i) {
    const LevelQuality quality = measure_level(spheres[i], queries[i], report_quality());
    LinkSpheres link;
    link.link = robot.links[i].link;
    link.bounding = bounding_sphere(spheres[i]);
    link.spheres = std::move(spheres[i]);
    link.coverage = quality.coverage;
    link.worst_protrusion = quality.worst_protrusion_m;
    link.outside_volume = quality.outside_volume_m3;
    result.push_back(std::move(link));
  }
  if (options.progress) options.progress(1.0);
  return result;
}

}  // namespace sphys::tools
