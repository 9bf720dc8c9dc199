// sphys-tree-eval: every sphere-tree build method on a fixed set of meshes, with the figures
// `sphys tree-info` prints (docs/sphere-tree-methods.md, "The evaluation set").
//
// Each mesh of the set gets a tree of depth 3, branching 8, from every method; its level 1 (up to
// 8 spheres) and level 2 (up to 64) are measured by tools::measure_levels with tree-info's
// options (the same Monte Carlo, the same seeds). The output is markdown: the meshes (closed or
// not, as check_mesh finds them), one table per mesh, and per method the mean over the set and
// over its closed meshes; --csv writes the rows as well.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include "sphys/error.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/check_mesh.h"
#include "sphys/tools/csv_file.h"
#include "sphys/tools/load_mesh.h"
#include "sphys/tools/mass_properties.h"
#include "sphys/tools/mesh_query.h"
#include "sphys/tools/model.h"
#include "sphys/tools/primitives.h"
#include "sphys/tools/robot.h"
#include "sphys/tools/tree_quality.h"
#include "support/test_robot.h"

namespace sphys::tree_eval {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kDepth = 3;      // root, up to 8, up to 64
constexpr int kBranching = 8;  // the paper's
constexpr int kLevels[] = {1, 2};
const fs::path kModels = "/usr/share/glmark2/models";

struct EvalMesh {
  std::string name;
  std::string source;  // what it is, for the table of meshes
  std::function<tools::TriangleMesh()> load;
};

// The test robot's links with one solid each, as `sphys spherize` reads them from its URDF.
// shoulder_link and hand_link are two overlapping closed solids each: their divergence volume
// counts the overlap twice and the inside test (ray parity) puts the overlap outside, so neither
// figure of the fit would be the union's; finger_right_link is finger_left_link's plate again.
constexpr const char* kRobotLinks[] = {"base_link", "upper_arm_link", "forearm_link",
                                       "finger_left_link"};

std::map<std::string, tools::TriangleMesh> robot_link_meshes() {
  const fs::path dir =
      fs::temp_directory_path() / ("sphys-tree-eval-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::map<std::string, tools::TriangleMesh> meshes;
  try {
    const test::TestRobot written = test::write_test_robot(dir, test::standard_test_robot());
    const tools::RobotPackage package = tools::parse_robot_package(written.package_option);
    const tools::Robot robot = tools::load_robot(written.urdf, std::span(&package, 1));
    for (const tools::LinkGeometry& link : robot.links) {
      tools::TriangleMesh mesh = link.mesh;
      mesh.name = "robot " + link.link;
      meshes.emplace(link.link, std::move(mesh));
    }
  } catch (...) {
    fs::remove_all(dir);
    throw;
  }
  fs::remove_all(dir);
  return meshes;
}

std::vector<EvalMesh> evaluation_set() {
  auto bunny = [](std::size_t triangles) {
    return [triangles] { return tools::load_model(tools::kBunnyName, triangles); };
  };
  auto model = [](const char* file) { return [file] { return tools::load_mesh(kModels / file); }; };
  std::vector<EvalMesh> set = {
      {"bunny-1500", "glmark2 bunny.obj decimated to 1,500 triangles", bunny(1500)},
      {"bunny-2000", "glmark2 bunny.obj decimated to 2,000 triangles (the default bunny)",
       bunny(2000)},
      {"bunny-full", "glmark2 bunny.obj, every triangle", bunny(0)},
      {"horse", "glmark2 horse.3ds", model("horse.3ds")},
      {"cat", "glmark2 cat.3ds", model("cat.3ds")},
      {"asteroid", "glmark2 asteroid-high.3ds", model("asteroid-high.3ds")},
      {"torus", "make_torus(1, 0.25, 64, 32): tube a quarter of the ring",
       [] { return tools::make_torus(1.0, 0.25, 64, 32); }},
      {"box-1-4-16", "make_box(0.1, 0.4, 1.6)",
       [] { return tools::make_box(tools::Vec3d(0.1, 0.4, 1.6)); }},
  };
  auto links = std::make_shared<std::optional<std::map<std::string, tools::TriangleMesh>>>();
  for (const char* link : kRobotLinks) {
    set.push_back(
        {std::string("robot-") + link, std::string("test robot's ") + link, [links, link] {
           if (!*links) *links = robot_link_meshes();
           return (*links)->at(link);
         }});
  }
  return set;
}

std::vector<tools::BuildMethod> all_methods() {
  return {tools::BuildMethod::Octree,  tools::BuildMethod::Grid,     tools::BuildMethod::Spawn,
          tools::BuildMethod::Hubbard, tools::BuildMethod::Merge,    tools::BuildMethod::Burst,
          tools::BuildMethod::Expand,  tools::BuildMethod::Combined, tools::BuildMethod::Tight};
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

struct MeshFacts {
  std::string name;
  std::string source;
  std::size_t triangles = 0;
  std::string closed;     // "yes", or what check_mesh found
  double volume = 0.0;    // unit: m^3
  double diagonal = 0.0;  // of the bounding box. unit: m
};

struct Row {
  std::string mesh;
  std::string method;
  tools::LevelQuality levels[2];
  double build_seconds = 0.0;  // the whole depth-3 tree
};

std::string closedness(const tools::MeshReport& report) {
  if (report.watertight()) return "yes";
  std::string text = "no:";
  auto add = [&](std::size_t count, const char* what) {
    if (count != 0) text += (text.size() > 3 ? ", " : " ") + std::to_string(count) + " " + what;
  };
  add(report.boundary_edges, "boundary edges");
  add(report.non_manifold_edges, "non-manifold edges");
  add(report.misoriented_edges, "misoriented edges");
  return text + " (winding number)";
}

MeshFacts mesh_facts(const EvalMesh& eval, const tools::TriangleMesh& mesh) {
  const tools::MeshReport report = tools::check_mesh(mesh);
  // As `sphys mesh-info` and `tree-info` do: a mesh that is not closed gets its volume and its
  // inside tests from the winding number.
  return {eval.name,
          eval.source,
          report.triangles,
          closedness(report),
          tools::compute_mass_properties(mesh).volume,
          mesh.bounds().diagonal().norm()};
}

std::string level_cells(const tools::LevelQuality& q) {
  char text[160];
  std::snprintf(text, sizeof text, "%zu | %.3f | %.4f | %.4f%%", q.spheres, q.outside_volume,
                q.worst_protrusion, 100.0 * q.coverage);
  return text;
}

void print_table_head() {
  std::printf(
      "| method | L1 spheres | L1 outside volume | L1 protrusion | L1 coverage | L2 spheres | "
      "L2 outside volume | L2 protrusion | L2 coverage | build s |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
}

void print_meshes(const std::vector<MeshFacts>& facts) {
  std::printf("## The meshes\n\n");
  std::printf("| mesh | source | triangles | closed | volume m^3 | box diagonal m |\n");
  std::printf("| --- | --- | --- | --- | --- | --- |\n");
  for (const MeshFacts& f : facts) {
    std::printf("| %s | %s | %zu | %s | %.6g | %.6g |\n", f.name.c_str(), f.source.c_str(),
                f.triangles, f.closed.c_str(), f.volume, f.diagonal);
  }
  std::printf("\n");
}

// One row per method: each figure's mean over the rows of the meshes `counted` accepts.
void print_means(const std::vector<tools::BuildMethod>& methods, const std::vector<Row>& rows,
                 const std::function<bool(const std::string&)>& counted) {
  print_table_head();
  for (const tools::BuildMethod method : methods) {
    const std::string name(tools::method_name(method));
    double spheres[2] = {}, outside[2] = {}, protrusion[2] = {}, coverage[2] = {};
    double lowest[2] = {1.0, 1.0};
    double seconds = 0.0;
    std::size_t count = 0;
    for (const Row& row : rows) {
      if (row.method != name || !counted(row.mesh)) continue;
      ++count;
      seconds += row.build_seconds;
      for (std::size_t k = 0; k < 2; ++k) {
        spheres[k] += static_cast<double>(row.levels[k].spheres);
        outside[k] += row.levels[k].outside_volume;
        protrusion[k] += row.levels[k].worst_protrusion;
        coverage[k] += row.levels[k].coverage;
        lowest[k] = std::min(lowest[k], row.levels[k].coverage);
      }
    }
    const auto n = static_cast<double>(count);
    std::printf("| %s", name.c_str());
    for (std::size_t k = 0; k < 2; ++k) {
      std::printf(" | %.1f | %.3f | %.4f | %.4f%% (%.4f%%)", spheres[k] / n, outside[k] / n,
                  protrusion[k] / n, 100.0 * coverage[k] / n, 100.0 * lowest[k]);
    }
    std::printf(" | %.3f |\n", seconds / n);
  }
}

struct Options {
  std::string meshes;
  std::string methods;
  std::optional<std::string> csv;
  int threads = 1;
  bool list = false;
};

int run(const Options& options) {
  std::vector<EvalMesh> set = evaluation_set();
  if (!options.meshes.empty()) {
    std::vector<EvalMesh> chosen;
    for (const std::string& name : split_list(options.meshes)) {
      const auto found =
          std::find_if(set.begin(), set.end(), [&](const EvalMesh& m) { return m.name == name; });
      if (found == set.end()) {
        std::string names;
        for (const EvalMesh& m : set) names += (names.empty() ? "" : ", ") + m.name;
        throw Error("unknown mesh '" + name + "'; the set: " + names);
      }
      chosen.push_back(*found);
    }
    set = chosen;
  }
  std::vector<tools::BuildMethod> methods = all_methods();
  if (!options.methods.empty()) {
    methods.clear();
    for (const std::string& name : split_list(options.methods)) {
      methods.push_back(tools::parse_method(name));
    }
  }

  if (options.list) {
    std::vector<MeshFacts> facts;
    for (const EvalMesh& eval : set) {
      const tools::TriangleMesh mesh = eval.load();
      facts.push_back(mesh_facts(eval, mesh));
    }
    print_meshes(facts);
    return 0;
  }

  const tools::QualityOptions quality;  // tree-info's
  tools::BuildOptions build;
  build.depth = kDepth;
  build.branching = kBranching;

  std::printf("# Sphere-trees on the evaluation set\n\n");
  std::printf(
      "Depth %d, branching %d, build seed %llu; each tree built on %d thread(s). Levels measured "
      "as `sphys tree-info` does (tools::measure_levels): coverage from %zu surface samples, "
      "outside volume from %zu Monte Carlo points in the union's box, protrusion from %zu points "
      "on each sphere, seed %llu. Outside volume / mesh volume; protrusion / bounding-box "
      "diagonal; build s is the whole depth-%d tree.\n\n",
      kDepth, kBranching, static_cast<unsigned long long>(build.seed), options.threads,
      quality.surface_samples, quality.volume_samples, quality.boundary_samples,
      static_cast<unsigned long long>(quality.seed), kDepth);

  const Clock::time_point start = Clock::now();
  std::vector<MeshFacts> facts;
  std::vector<Row> rows;
  std::vector<std::string> tables;
  for (const EvalMesh& eval : set) {
    const tools::TriangleMesh mesh = eval.load();
    facts.push_back(mesh_facts(eval, mesh));
    const tools::MeshQuery query(mesh);

    std::string table;
    for (const tools::BuildMethod method : methods) {
      build.method = method;
      Row row{eval.name, std::string(tools::method_name(method)), {}, 0.0};
      std::optional<SphereTree> tree;
      {
        const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                          static_cast<std::size_t>(options.threads));
        const Clock::time_point begin = Clock::now();
        tree = tools::build_sphere_tree(mesh, build);
        row.build_seconds = std::chrono::duration<double>(Clock::now() - begin).count();
      }
      std::vector<std::vector<Sphere>> levels;
      for (const int level : kLevels) {
        const std::span<const Sphere> spheres = tree->level_spheres(level);
        levels.emplace_back(spheres.begin(), spheres.end());
      }
      const std::vector<tools::LevelQuality> measured =
          tools::measure_levels(levels, query, quality);
      for (std::size_t k = 0; k < 2; ++k) {
        row.levels[k] = measured[k];
        row.levels[k].level = kLevels[k];
      }
      std::fprintf(stderr, "%s %s: build %.2f s, %.0f s so far\n", row.mesh.c_str(),
                   row.method.c_str(), row.build_seconds,
                   std::chrono::duration<double>(Clock::now() - start).count());
      char build_cell[32];
      std::snprintf(build_cell, sizeof build_cell, "%.3f", row.build_seconds);
      table += "| " + row.method + " | " + level_cells(row.levels[0]) + " | " +
               level_cells(row.levels[1]) + " | " + build_cell + " |\n";
      rows.push_back(row);
    }
    tables.push_back(table);
  }

  print_meshes(facts);
  for (std::size_t m = 0; m < facts.size(); ++m) {
    std::printf("## %s\n\n", facts[m].name.c_str());
    print_table_head();
    std::printf("%s\n", tables[m].c_str());
  }

  std::printf("## Mean over the set (%zu meshes)\n\n", facts.size());
  std::printf(
      "Each figure's plain mean over the meshes; the lowest coverage of any mesh in brackets.\n\n");
  print_means(methods, rows, [](const std::string&) { return true; });
  std::vector<std::string> closed;
  for (const MeshFacts& f : facts) {
    if (f.closed == "yes") closed.push_back(f.name);
  }
  if (closed.size() != facts.size()) {
    std::printf("\n## Mean over the closed meshes (%zu)\n\n", closed.size());
    std::printf("The same, without the meshes that are not closed.\n\n");
    print_means(methods, rows, [&](const std::string& mesh) {
      return std::find(closed.begin(), closed.end(), mesh) != closed.end();
    });
  }
  std::printf("\nWhole run: %.0f s.\n",
              std::chrono::duration<double>(Clock::now() - start).count());

  if (options.csv) {
    const std::vector<std::string> columns = {"mesh",     "method",         "level",
                                              "spheres",  "outside_volume", "worst_protrusion",
                                              "coverage", "build_s"};
    std::vector<std::vector<tools::CsvCell>> cells;
    for (const Row& row : rows) {
      for (const tools::LevelQuality& q : row.levels) {
        cells.push_back({row.mesh, row.method, static_cast<double>(q.level),
                         static_cast<double>(q.spheres), q.outside_volume, q.worst_protrusion,
                         q.coverage, row.build_seconds});
      }
    }
    tools::write_csv(*options.csv, columns, cells);
  }
  return 0;
}

}  // namespace
}  // namespace sphys::tree_eval

int main(int argc, char** argv) {
  sphys::tree_eval::Options options;
  CLI::App app("Every sphere-tree build method on the evaluation set of meshes");
  app.add_option("--meshes", options.meshes,
                 "Comma-separated subset of the set's meshes (default: all)");
  app.add_option("--methods", options.methods,
                 "Comma-separated subset of the build methods (default: all)");
  app.add_option("--csv", options.csv, "Also write one row per mesh, method and level here");
  app.add_option("--threads", options.threads, "Threads each build may use (default 1)")
      ->check(CLI::Range(1, 256));
  app.add_flag("--list", options.list,
               "Only load the meshes and print their table (triangles, closed, volume)");
  CLI11_PARSE(app, argc, argv);
  try {
    return sphys::tree_eval::run(options);
  } catch (const sphys::Error& e) {
    std::fprintf(stderr, "sphys-tree-eval: %s\n", e.what());
    return 1;
  }
}
