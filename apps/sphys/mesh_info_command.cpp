#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "sphys/tools/check_mesh.h"
#include "sphys/tools/mass_properties.h"
#include "sphys/tools/model.h"
#include "sphys/tools/normalize.h"
#include "standard_output.h"

namespace sphys::cli {
namespace {

using tools::Mat3d;
using tools::Vec3d;

struct MeshInfoOptions {
  std::string mesh;
  std::optional<std::size_t> triangles;
  double density = 1000.0;
  std::optional<double> size;
  bool json = false;
};

std::string format_vec(const Vec3d& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g, %.6g)", v.x(), v.y(), v.z());
  return buffer;
}

nlohmann::json to_json(const Vec3d& v) { return {v.x(), v.y(), v.z()}; }
nlohmann::json to_json(const Mat3d& m) {  // rows
  return {to_json(Vec3d(m.row(0))), to_json(Vec3d(m.row(1))), to_json(Vec3d(m.row(2)))};
}

const char* method_name(tools::MassMethod method) {
  return method == tools::MassMethod::Polyhedral ? "polyhedral" : "winding-number";
}

void print_text(const tools::TriangleMesh& mesh, const tools::MeshReport& report,
                const tools::MassProperties& mass, double density) {
  const tools::Box3d box = mesh.bounds();
  std::printf("mesh              %s\n", mesh.name.c_str());
  std::printf("triangles         %zu\n", report.triangles);
  std::printf("vertices          %zu\n", report.vertices);
  std::printf("bounds            min %s  max %s\n", format_vec(box.min()).c_str(),
              format_vec(box.max()).c_str());
  std::printf("size              %s\n", format_vec(box.sizes()).c_str());
  std::printf(
      "watertight        %s (%zu boundary, %zu non-manifold, %zu misoriented edges; "
      "%zu degenerate triangles)\n",
      report.watertight() ? "yes" : "no", report.boundary_edges, report.non_manifold_edges,
      report.misoriented_edges, report.degenerate_triangles);
  std::printf("volume            %.9g m^3  (%s)\n", mass.volume,
              mass.method == tools::MassMethod::Polyhedral
                  ? "exact polyhedral integrals"
                  : "winding-number integration: the mesh is not closed");
  std::printf("density           %.9g kg/m^3\n", density);
  std::printf("mass              %.9g kg\n", mass.mass);
  std::printf("centre of mass    %s m\n", format_vec(mass.center_of_mass).c_str());
  std::printf("inertia tensor    about the centre of mass, kg m^2\n");
  for (int r = 0; r < 3; ++r) {
    std::printf("                  [%14.7g %14.7g %14.7g]\n", mass.inertia(r, 0),
                mass.inertia(r, 1), mass.inertia(r, 2));
  }
  std::printf("principal moments %s kg m^2\n", format_vec(mass.principal_moments).c_str());
  for (int c = 0; c < 3; ++c) {
    std::printf("principal axis %d  %s\n", c + 1, format_vec(mass.principal_axes.col(c)).c_str());
  }
}

void print_json(const tools::TriangleMesh& mesh, const tools::MeshReport& report,
                const tools::MassProperties& mass, double density) {
  const tools::Box3d box = mesh.bounds();
  const nlohmann::json out = {
      {"mesh", mesh.name},
      {"triangles", report.triangles},
      {"vertices", report.vertices},
      {"bounds", {{"min", to_json(box.min())}, {"max", to_json(box.max())}}},
      {"watertight", report.watertight()},
      {"boundary_edges", report.boundary_edges},
      {"non_manifold_edges", report.non_manifold_edges},
      {"misoriented_edges", report.misoriented_edges},
      {"degenerate_triangles", report.degenerate_triangles},
      {"mass_method", method_name(mass.method)},
      {"volume", mass.volume},
      {"density", density},
      {"mass", mass.mass},
      {"center_of_mass", to_json(mass.center_of_mass)},
      {"inertia", to_json(mass.inertia)},
      {"principal_moments", to_json(mass.principal_moments)},
      {"principal_axes", to_json(mass.principal_axes)},
  };
  print_output(out.dump(2) + "\n");
}

void run(const MeshInfoOptions& options) {
  tools::TriangleMesh mesh = tools::load_model(options.mesh, options.triangles);
  tools::MassPropertiesOptions mass_options;
  mass_options.density = options.density;
  if (options.size) mesh = tools::normalize(mesh, *options.size, mass_options).mesh;
  const tools::MeshReport report = tools::check_mesh(mesh);
  const tools::MassProperties mass = tools::compute_mass_properties(mesh, mass_options);
  if (options.json) {
    print_json(mesh, report, mass, options.density);
  } else {
    print_text(mesh, report, mass, options.density);
  }
}

}  // namespace

void add_mesh_info_command(CLI::App& app) {
  auto options = std::make_shared<MeshInfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mesh-info",
      "Size, closedness and mass properties of a mesh (OBJ, PLY, STL, OFF or 'bunny')");
  cmd->add_option("mesh", options->mesh, "Mesh file, or 'bunny' for the default model")
      ->check(kFileName)
      ->required();
  cmd->add_option("--triangles", options->triangles,
                  "Decimate to this many triangles (bunny: 2000 by default; 0 keeps all)");
  cmd->add_option("--density", options->density, "Density in kg/m^3 (mesh units are metres)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--size", options->size,
                  "First scale to this longest bounding-box side (m), centre of mass at origin")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--json", options->json, "Print JSON instead of text");
  cmd->callback([options] { run(*options); });
}

}  // namespace sphys::cli
