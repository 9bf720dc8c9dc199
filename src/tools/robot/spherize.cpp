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
#include "sphys/tools/sphere_set.h"
#include "sphys/tools/tree_quality.h"

namespace sphys::tools {
namespace {

// A link's spheres are never more than this: a budget or protrusion that asks for more is a
// mistake (a millimetre on a metre-long link), and it bounds the time spent.
constexpr int kMaxSpheresPerLink = 512;

// Quick figures for choosing sphere counts (hundreds of builds), and the full ones for the report
// (one per link). Only the protrusion matters while choosing, so the other figures get few
// samples; the protrusion's own samples are the report's, so that the protrusion that met a
// limit is the one reported.
QualityOptions choosing_quality() {
  QualityOptions options;
  options.surface_samples = 1000;
  options.volume_samples = 1000;
  options.require_volume = false;
  return options;
}

QualityOptions report_quality() {
  QualityOptions options;
  options.require_volume = false;
  return options;
}

// One link while its spheres are being chosen.
struct LinkWork {
  const LinkGeometry* geometry = nullptr;
  std::unique_ptr<MeshQuery> query;
  std::unique_ptr<SphereSetBuilder> builder;
  std::vector<Sphere> spheres;
  double protrusion = 0.0;  // unit: m

  // Takes the builder's spheres, grown by the gap between the meshed and the true primitives so
  // that the true shape is covered too, and measures them.
  void update() {
    spheres = builder->spheres();
    for (Sphere& s : spheres) s.radius += static_cast<float>(geometry->tessellation_error);
    protrusion = measure_level(spheres, *query, choosing_quality()).worst_protrusion_m;
  }
  [[nodiscard]] int count() const { return static_cast<int>(spheres.size()); }
};

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
    throw Error("give either a number of spheres or a largest protrusion, not " +
                std::string(options.total_spheres ? "both" : "neither"));
  }
  const auto links = static_cast<int>(robot.links.size());
  if (options.total_spheres && *options.total_spheres < links) {
    throw Error("--spheres: " + std::to_string(*options.total_spheres) + " is fewer than the " +
                std::to_string(links) + " links with geometry (each needs at least one)");
  }
  if (options.total_spheres && *options.total_spheres > links * kMaxSpheresPerLink) {
    throw Error("--spheres: at most " + std::to_string(kMaxSpheresPerLink) + " per link (" +
                std::to_string(links * kMaxSpheresPerLink) + " for this robot), got " +
                std::to_string(*options.total_spheres));
  }
  if (options.max_protrusion &&
      !(std::isfinite(*options.max_protrusion) && *options.max_protrusion > 0.0)) {
    throw Error("--max-protrusion must be positive and finite (unit: m)");
  }
}

// Each refinement goes to the link that protrudes most: the robot's worst protrusion is what a
// planner's clearance must allow for, and this lowers it first. A link whose spheres can no
// longer be split drops out.
void share_budget(std::vector<LinkWork>& links, int total, const SpherizeOptions& options) {
  int given = static_cast<int>(links.size());
  const int extra = total - given;
  std::vector<bool> done(links.size(), false);
  while (given < total) {
    std::size_t worst = links.size();
    for (std::size_t i = 0; i < links.size(); ++i) {
      if (!done[i] && (worst == links.size() || links[i].protrusion > links[worst].protrusion)) {
        worst = i;
      }
    }
    if (worst == links.size()) break;
    LinkWork& link = links[worst];
    const int before = link.count();
    if (link.count() >= kMaxSpheresPerLink ||
        !link.builder->refine(
            std::min(8, std::min(total - given, kMaxSpheresPerLink - before) + 1))) {
      done[worst] = true;
      continue;
    }
    link.update();
    given += link.count() - before;
    if (options.progress && extra > 0) {
      options.progress(0.9 * (given - total + extra) / static_cast<double>(extra));
    }
  }
}

// Refines the link's worst sphere until the protrusion is within the limit.
void meet_protrusion(LinkWork& link, double limit) {
  while (link.protrusion > limit) {
    if (link.count() >= kMaxSpheresPerLink || !link.builder->refine()) {
      throw Error::in_file(link.geometry->mesh.name,
                           "still protrudes " + std::to_string(link.protrusion) + " m with " +
                               std::to_string(link.count()) +
                               " spheres, more than --max-protrusion allows");
    }
    link.update();
  }
}

}  // namespace

std::vector<LinkSpheres> spherize(const Robot& robot, const SpherizeOptions& options) {
  validate(robot, options);
  std::vector<LinkWork> links(robot.links.size());
  for (std::size_t i = 0; i < links.size(); ++i) {
    links[i].geometry = &robot.links[i];
    links[i].query = std::make_unique<MeshQuery>(robot.links[i].mesh);
    links[i].builder = std::make_unique<SphereSetBuilder>(robot.links[i].mesh,
                                                          BuildMethod::Combined, options.seed);
    links[i].update();
    if (options.max_protrusion) {
      meet_protrusion(links[i], *options.max_protrusion);
      if (options.progress)
        options.progress(0.9 * static_cast<double>(i + 1) / static_cast<double>(links.size()));
    }
  }
  if (options.total_spheres) share_budget(links, *options.total_spheres, options);

  std::vector<LinkSpheres> result;
  for (LinkWork& link : links) {
    const LevelQuality quality = measure_level(link.spheres, *link.query, report_quality());
    LinkSpheres spheres;
    spheres.link = link.geometry->link;
    spheres.bounding = bounding_sphere(link.spheres);
    spheres.spheres = std::move(link.spheres);
    spheres.coverage = quality.coverage;
    spheres.worst_protrusion = quality.worst_protrusion_m;
    spheres.outside_volume = quality.outside_volume_m3;
    result.push_back(std::move(spheres));
  }
  if (options.progress) options.progress(1.0);
  return result;
}

}  // namespace sphys::tools
