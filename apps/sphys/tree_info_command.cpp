#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "sphys/error.h"
#include "sphys/tools/mesh_query.h"
#include "sphys/tools/model.h"
#include "sphys/tools/sph_file.h"
#include "sphys/tools/tree_quality.h"
#include "standard_output.h"

namespace sphys::cli {
namespace {

struct TreeInfoOptions {
  std::string tree;
  std::optional<std::string> mesh;
  std::optional<std::size_t> triangles;
  bool toolkit_shift = false;
  bool json = false;
};

void run(const TreeInfoOptions& options) {
  if (options.toolkit_shift && !options.mesh) {
    throw Error("--toolkit-shift needs --mesh: the shift is the mesh's bounding-box centre");
  }
  std::optional<tools::TriangleMesh> mesh;
  if (options.mesh) mesh = tools::load_model(*options.mesh, options.triangles);
  tools::SphReadOptions read;
  if (options.toolkit_shift) read.shift = mesh->bounds().center();
  // Any file the toolkit writes, flat sphere sets of more than 8 included: only measured here.
  const tools::SphSpheres file = tools::read_sph_spheres(options.tree, read);
  const std::vector<std::vector<Sphere>> levels = file.levels();
  const int depth = static_cast<int>(levels.size());

  std::vector<tools::LevelQuality> quality;
  if (mesh) quality = tools::measure_levels(levels, tools::MeshQuery(*mesh));

  if (options.json) {
    nlohmann::json entries = nlohmann::json::array();
    for (int level = 0; level < depth; ++level) {
      nlohmann::json entry = {{"level", level},
                              {"spheres", levels[static_cast<std::size_t>(level)].size()}};
      if (mesh) {
        const tools::LevelQuality& q = quality[static_cast<std::size_t>(level)];
        entry["coverage"] = q.coverage;
        entry["worst_gap"] = q.worst_gap;
        entry["outside_volume"] = q.outside_volume;
        entry["worst_protrusion"] = q.worst_protrusion;
      }
      entries.push_back(entry);
    }
    nlohmann::json out = {{"tree", options.tree},
                          {"branching", file.branching},
                          {"depth", depth},
                          {"spheres", file.nodes.size()},
                          {"levels", entries}};
    if (mesh) out["mesh"] = mesh->name;
    print_output(out.dump(2) + "\n");
    return;
  }

  std::printf("%s: branching %d, %d levels, %zu spheres\n", options.tree.c_str(), file.branching,
              depth, file.nodes.size());
  if (!mesh) {
    for (int level = 0; level < depth; ++level) {
      std::printf("level %d: %zu spheres\n", level, levels[static_cast<std::size_t>(level)].size());
    }
    return;
  }
  std::printf("measured against %s (distances / bounding-box diagonal, volumes / mesh volume)\n",
              mesh->name.c_str());
  std::printf("level  spheres   coverage  worst gap  outside volume  worst protrusion\n");
  for (const tools::LevelQuality& q : quality) {
    std::printf("%5d  %7zu  %8.4f%%  %9.5f  %14.4f  %16.5f\n", q.level, q.spheres,
                100.0 * q.coverage, q.worst_gap, q.outside_volume, q.worst_protrusion);
  }
}

}  // namespace

void add_tree_info_command(CLI::App& app) {
  auto options = std::make_shared<TreeInfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tree-info", "Levels of a sphere-tree (.sph) and, given the mesh, how well each fits it");
  cmd->add_option("tree", options->tree, "The .sph file")->check(kFileName)->required();
  cmd->add_option("--mesh", options->mesh, "Mesh file or 'bunny': measure the fit")
      ->check(kFileName);
  cmd->add_option("--triangles", options->triangles,
                  "Decimate the mesh first (bunny: 2000 by default; 0 keeps all)");
  cmd->add_flag("--toolkit-shift", options->toolkit_shift,
                "The file comes from Bradshaw's toolkit: undo its shift by the mesh's "
                "bounding-box centre");
  cmd->add_flag("--json", options->json, "Print JSON instead of text");
  cmd->callback([options] { run(*options); });
}

}  // namespace sphys::cli
