#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "progress.h"
#include "sphys/tools/interrupt.h"
#include "sphys/tools/note.h"
#include "sphys/tools/robot.h"
#include "sphys/tools/spherize.h"
#include "standard_output.h"

namespace sphys::cli {
namespace {

struct SpherizeArguments {
  std::string urdf;
  std::optional<int> spheres;
  std::optional<double> max_protrusion;
  std::vector<std::string> packages;
  std::string format;
  std::string output;
  bool json = false;
};

// Links larger or smaller than these are more likely a unit mistake (millimetres exported as
// metres) than a robot: said on standard error, spheres built all the same. unit: m
constexpr double kLargeLink = 10.0;
constexpr double kSmallLink = 1e-3;

// The whole robot's figures: the report's last line.
struct Totals {
  std::size_t spheres = 0;
  double worst_protrusion = 0.0;  // unit: m
  double outside_volume = 0.0;    // unit: m³
};

Totals totals(const std::vector<tools::LinkSpheres>& links) {
  Totals t;
  for (const tools::LinkSpheres& link : links) {
    t.spheres += link.spheres.size();
    t.worst_protrusion = std::max(t.worst_protrusion, link.worst_protrusion);
    t.outside_volume += link.outside_volume;
  }
  return t;
}

nlohmann::json sphere_json(const Sphere& s) {
  return {{"center", {s.center.x(), s.center.y(), s.center.z()}}, {"radius", s.radius}};
}

nlohmann::json report_json(const SpherizeArguments& args, const tools::Robot& robot,
                           const std::vector<tools::LinkSpheres>& links, double seconds) {
  nlohmann::json out;
  out["robot"] = robot.name;
  out["urdf"] = args.urdf;
  out["format"] = args.format;
  out["output"] = args.output;
  out["seconds"] = seconds;
  for (std::size_t i = 0; i < links.size(); ++i) {
    const tools::LinkGeometry& geometry = robot.links[i];
    const tools::LinkSpheres& link = links[i];
    out["links"].push_back({{"link", link.link},
                            {"spheres", link.spheres.size()},
                            {"coverage", link.coverage},
                            {"worst_protrusion_m", link.worst_protrusion},
                            {"outside_volume_m3", link.outside_volume},
                            {"size_m", geometry.mesh.bounds().diagonal().norm()},
                            {"from_visual", geometry.from_visual},
                            {"tessellation_error_m", geometry.tessellation_error},
                            {"sources", geometry.sources},
                            {"bounding_sphere", sphere_json(link.bounding)}});
  }
  out["links_without_geometry"] = robot.empty_links;
  const Totals total = totals(links);
  out["total"] = {{"spheres", total.spheres},
                  {"worst_protrusion_m", total.worst_protrusion},
                  {"outside_volume_m3", total.outside_volume}};
  return out;
}

void print_report(const SpherizeArguments& args, const tools::Robot& robot,
                  const std::vector<tools::LinkSpheres>& links, double seconds) {
  std::printf("%s: %s, %zu links with geometry\n", args.urdf.c_str(), robot.name.c_str(),
              robot.links.size());
  std::printf("%-24s %8s %10s %16s %18s\n", "link", "spheres", "coverage", "protrusion (m)",
              "outside vol (m3)");
  for (std::size_t i = 0; i < links.size(); ++i) {
    const tools::LinkSpheres& link = links[i];
    std::printf("%-24s %8zu %10.6f %16.5f %18.3e%s\n", link.link.c_str(), link.spheres.size(),
                link.coverage, link.worst_protrusion, link.outside_volume,
                robot.links[i].from_visual ? "  (visual geometry: no collision element)" : "");
  }
  const Totals total = totals(links);
  std::printf("%-24s %8zu %10s %16.5f %18.3e\n", "total", total.spheres, "", total.worst_protrusion,
              total.outside_volume);
  for (const std::string& link : robot.empty_links) {
    std::printf("link %s has no geometry: no spheres\n", link.c_str());
  }
  std::printf("wrote %s (%s) in %.2f s\n", args.output.c_str(), args.format.c_str(), seconds);
}

void run(const SpherizeArguments& args) {
  tools::catch_interruptions();
  const auto start = std::chrono::steady_clock::now();
  const tools::SphereFileFormat format =
      parse_option("--format", args.format, tools::parse_sphere_file_format);
  // Refused before the work rather than after it.
  const std::filesystem::path folder = std::filesystem::absolute(args.output).parent_path();
  if (!std::filesystem::is_directory(folder)) {
    throw Error::in_file(args.output, "cannot write: the directory does not exist");
  }
  std::vector<tools::RobotPackage> packages;
  for (const std::string& package : args.packages) {
    packages.push_back(tools::parse_robot_package(package));
  }
  const tools::Robot robot = tools::load_robot(args.urdf, packages);
  for (const tools::LinkGeometry& link : robot.links) {
    const double size = link.mesh.bounds().diagonal().norm();
    if (size > kLargeLink || size < kSmallLink) {
      std::ostringstream text;
      text << "link \"" << link.link << "\" is " << size
           << " m across: check the mesh's units (a scale in the URDF fixes them)";
      tools::note(text.str());
    }
  }
  tools::SpherizeOptions options;
  options.total_spheres = args.spheres;
  options.max_protrusion = args.max_protrusion;
  ProgressBar bar("spherizing " + robot.name);
  options.progress = [&bar](double fraction) { bar.update(fraction); };
  const std::vector<tools::LinkSpheres> links = tools::spherize(robot, options);
  tools::write_robot_spheres(args.output, format, robot, links);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (args.json) {
    print_output(report_json(args, robot, links, seconds).dump(2) + "\n");
  } else {
    print_report(args, robot, links, seconds);
  }
}

}  // namespace

void add_spherize_command(CLI::App& app) {
  auto args = std::make_shared<SpherizeArguments>();
  CLI::App* cmd = app.add_subcommand(
      "spherize", "Cover each link of a URDF robot with spheres, for motion planners");
  cmd->add_option("urdf", args->urdf, "The robot's URDF file")->check(kFileName)->required();
  cmd->add_option(
      "--spheres", args->spheres,
      "Spheres for the whole robot at most, shared among the links so that all have the "
      "same, smallest protrusion bound");
  cmd->add_option("--max-protrusion", args->max_protrusion,
                  "Or: each link's spheres reach at most this far out of it (unit: m)");
  cmd->add_option("--package", args->packages,
                  "NAME=DIR: where package://NAME/ mesh paths point (repeatable)");
  cmd->add_option("--format", args->format,
                  "curobo (collision_spheres YAML), srdf (MoveIt's link_sphere_approximation) or "
                  "urdf (the URDF with spheres as collision elements)")
      ->required();
  cmd->add_option("-o,--output", args->output, "The file to write")->check(kFileName)->required();
  cmd->add_flag("--json", args->json, "Print the report as JSON");
  cmd->callback([args] { run(*args); });
}

}  // namespace sphys::cli
