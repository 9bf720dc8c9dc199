#pragma once

// `sphys spherize`: sphere sets for a robot's links whose coverage of each link's geometry is
// certified, for motion planners that check robots with spheres.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sphys/sphere_tree.h"
#include "sphys/tools/robot.h"

namespace sphys::tools {

// How many spheres spherize makes: set exactly one of total_spheres and max_protrusion.
struct SpherizeOptions {
  // Spheres for the whole robot (at most), shared among the links through one protrusion bound
  // for all (ProtrusionCover), the tightest whose covers fit the budget.
  std::optional<int> total_spheres;
  // Or: each link's spheres reach at most this far out of it (as measured). unit: m
  std::optional<double> max_protrusion;
  // Called with the fraction done (0..1) now and then, for progress bars.
  std::function<void(double)> progress;
};

// The spheres of one link, in the link's frame. unit: m
struct LinkSpheres {
  std::string link;             // the link's name
  Sphere bounding;              // holds every sphere of `spheres`: the two-level form's root
  std::vector<Sphere> spheres;  // together they cover the link's whole surface
  // Measured on the link's mesh, not taken from the builder: the fraction of 100,000 surface
  // samples inside some sphere (1 where the certificate holds), the farthest the union of
  // spheres reaches out of the link's geometry (m), and the union's volume outside it (m³).
  double coverage = 0.0;
  double worst_protrusion = 0.0;  // unit: m
  double outside_volume = 0.0;    // unit: m³
};

// Throws sphys::Error when neither or both of the options are set, the total is below the number
// of links with geometry, or the protrusion is not positive and finite.
[[nodiscard]] std::vector<LinkSpheres> spherize(const Robot& robot, const SpherizeOptions& options);

// The files planners read. Curobo: cuRobo's `collision_spheres` YAML (link → list of centre and
// radius), with `bounding_spheres` beside it; Srdf: MoveIt's `link_sphere_approximation`
// elements; Urdf: a copy of the robot's URDF whose collision elements are the spheres.
enum class SphereFileFormat { Curobo, Srdf, Urdf };
// "curobo", "srdf" or "urdf" to its format; throws sphys::Error listing them for another name.
[[nodiscard]] SphereFileFormat parse_sphere_file_format(std::string_view name);
// The format's name as parse_sphere_file_format reads it.
[[nodiscard]] std::string_view format_name(SphereFileFormat format);

// Writes the whole file or nothing (an existing file stays as it was when writing fails).
void write_robot_spheres(const std::filesystem::path& path, SphereFileFormat format,
                         const Robot& robot, std::span<const LinkSpheres> links);

// Reads the spheres back from a file in any of the three formats (told apart by its content).
// Only `link`, `spheres` and, from the YAML, `bounding` are filled. Throws sphys::Error naming the
// file and the problem.
[[nodiscard]] std::vector<LinkSpheres> read_robot_spheres(const std::filesystem::path& path);

}  // namespace sphys::tools
