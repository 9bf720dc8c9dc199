#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "progress.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/interrupt.h"
#include "sphys/tools/model.h"
#include "sphys/tools/sph_file.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::cli {
namespace {

struct BuildTreeOptions {
  std::string mesh;
  std::optional<std::size_t> triangles;
  std::string method = "combined";
  int branching = 8;
  int depth = 3;
  std::uint64_t seed = 1;
  std::string output;
  bool no_cache = false;
};

void run(const BuildTreeOptions& options) {
  tools::catch_interruptions();
  const tools::TriangleMesh mesh = tools::load_model(options.mesh, options.triangles);
  tools::BuildOptions build;
  build.method = tools::parse_method(options.method);
  build.branching = options.branching;
  build.depth = options.depth;
  build.seed = options.seed;
  ProgressBar bar("building " + std::string(tools::method_name(build.method)));
  build.progress = [&bar](double fraction) { bar.update(fraction); };

  const auto start = std::chrono::steady_clock::now();
  const std::optional<std::filesystem::path> cache =
      options.no_cache ? std::nullopt : std::optional(tools::default_cache_dir());
  const tools::CachedTree result = tools::build_sphere_tree_cached(mesh, build, cache);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  tools::write_sph(options.output, result.tree);

  std::printf("%s: %s tree, branching %d, %d levels, %zu spheres (", options.output.c_str(),
              std::string(tools::method_name(build.method)).c_str(), result.tree.branching(),
              result.tree.depth(), result.tree.size());
  for (int level = 0; level < result.tree.depth(); ++level) {
    std::printf("%s%u", level == 0 ? "" : " + ",
                result.tree.level_end(level) - result.tree.level_begin(level));
  }
  std::printf(")\n%s in %.3f s\n", result.from_cache ? "loaded from the cache" : "built", seconds);
}

}  // namespace

void add_build_tree_command(CLI::App& app) {
  auto options = std::make_shared<BuildTreeOptions>();
  CLI::App* cmd = app.add_subcommand("build-tree", "Build a sphere-tree for a mesh");
  cmd->add_option("mesh", options->mesh, "Mesh file, or 'bunny' for the default model")
      ->check(kFileName)
      ->required();
  cmd->add_option("--triangles", options->triangles,
                  "Decimate to this many triangles first (bunny: 2000 by default; 0 keeps all)");
  cmd->add_option("--method", options->method,
                  "octree, grid, spawn, hubbard, merge, burst, expand, combined or tight")
      ->capture_default_str();
  cmd->add_option("--branching", options->branching, "Children per node, 2..8")
      ->capture_default_str();
  cmd->add_option("--depth", options->depth, "Levels including the root")->capture_default_str();
  cmd->add_option("--seed", options->seed, "Seed of every random choice")->capture_default_str();
  cmd->add_option("-o,--output", options->output, "The .sph file to write")
      ->check(kFileName)
      ->required();
  cmd->add_flag("--no-cache", options->no_cache, "Build even if the tree is in the cache");
  cmd->callback([options] { run(*options); });
}

}  // namespace sphys::cli
