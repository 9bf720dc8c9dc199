// Sphere-trees: build with any method, read and write .sph, levels as arrays, quality measures.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "sphys/sphere_tree.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/mesh_query.h"
#include "sphys/tools/sph_file.h"
#include "sphys/tools/tree_quality.h"

namespace sphys::python {
namespace {

constexpr py::ssize_t kSphereStride = sizeof(Sphere);

// Read-only views of spheres [begin, end) of the tree that `self` holds: centres (n, 3) and radii
// (n,), float32, strided over the tree's own array of spheres.
py::tuple sphere_views(const py::object& self, std::uint32_t begin, std::uint32_t end) {
  const auto& tree = self.cast<const SphereTree&>();
  const auto n = static_cast<py::ssize_t>(end - begin);
  const Sphere* first = tree.spheres().data() + begin;
  py::array_t<float> centres({n, py::ssize_t{3}}, {kSphereStride, py::ssize_t{sizeof(float)}},
                             first->center.data(), self);
  py::array_t<float> radii({n}, {kSphereStride}, &first->radius, self);
  for (py::array* array : {static_cast<py::array*>(&centres), static_cast<py::array*>(&radii)}) {
    py::detail::array_proxy(array->ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  }
  return py::make_tuple(centres, radii);
}

std::vector<Sphere> spheres_from(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& centres,
    const py::array_t<double, py::array::c_style | py::array::forcecast>& radii) {
  if (centres.ndim() != 2 || centres.shape(1) != 3)
    throw Error("centres must be an array of shape (N, 3)");
  if (radii.ndim() != 1 || radii.shape(0) != centres.shape(0)) {
    throw Error("radii must be an array of shape (N,) with N the number of centres");
  }
  const auto c = centres.unchecked<2>();
  const auto r = radii.unchecked<1>();
  std::vector<Sphere> spheres(static_cast<std::size_t>(c.shape(0)));
  for (py::ssize_t i = 0; i < c.shape(0); ++i) {
    spheres[static_cast<std::size_t>(i)] = {
        Vec3(static_cast<float>(c(i, 0)), static_cast<float>(c(i, 1)), static_cast<float>(c(i, 2))),
        static_cast<float>(r(i))};
  }
  return spheres;
}

tools::QualityOptions quality_options(std::size_t surface_samples, std::size_t volume_samples,
                                      std::size_t boundary_samples, std::uint64_t seed) {
  tools::QualityOptions options;
  options.surface_samples = surface_samples;
  options.volume_samples = volume_samples;
  options.boundary_samples = boundary_samples;
  options.seed = seed;
  return options;
}

}  // namespace

void bind_tree(py::module_& m) {
  py::class_<SphereTree, std::shared_ptr<SphereTree>>(
      m, "SphereTree",
      "A hierarchy of spheres bounding one body, in its body frame (metres). Nodes are "
      "breadth-first: node 0 is the root, each level a contiguous range. Depth counts the levels "
      "including the root (the paper's depth 2 is a root and its leaves). Arrays are read-only "
      "views of the tree's memory (float32, as the simulation uses them).")
      .def_static(
          "from_arrays",
          [](const py::array_t<double, py::array::c_style | py::array::forcecast>& centres,
             const py::array_t<double, py::array::c_style | py::array::forcecast>& radii,
             const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& parents,
             int branching) {
            const std::vector<Sphere> spheres = spheres_from(centres, radii);
            if (parents.ndim() != 1 ||
                static_cast<std::size_t>(parents.shape(0)) != spheres.size()) {
              throw Error("parents must be an array of shape (N,) with N the number of centres");
            }
            std::vector<SphereTreeNode> nodes(spheres.size());
            for (std::size_t i = 0; i < nodes.size(); ++i) {
              const std::int64_t parent = parents.at(static_cast<py::ssize_t>(i));
              if (parent < -1 || parent >= static_cast<std::int64_t>(nodes.size())) {
                throw Error("parents[" + std::to_string(i) + "] must be -1 or a node index, got " +
                            std::to_string(parent));
              }
              nodes[i] = {spheres[i], static_cast<std::int32_t>(parent)};
            }
            return SphereTree::from_nodes(nodes, branching);
          },
          py::arg("centres"), py::arg("radii"), py::arg("parents"), py::arg("branching"),
          "A tree from breadth-first nodes: centres (N, 3) m, radii (N,) m, parents (N,) with -1 "
          "for the root. Raises sphys.Error for an invalid tree.")
      .def_property_readonly("depth", &SphereTree::depth, "Levels, the root's included")
      .def_property_readonly("branching", &SphereTree::branching, "Most children per node")
      .def("__len__", &SphereTree::size)
      .def_property_readonly(
          "centres",
          [](const py::object& self) -> py::object {
            return sphere_views(
                self, 0, static_cast<std::uint32_t>(self.cast<const SphereTree&>().size()))[0];
          },
          "(N, 3) float32 every node's centre, breadth-first. unit: m")
      .def_property_readonly(
          "radii",
          [](const py::object& self) -> py::object {
            return sphere_views(
                self, 0, static_cast<std::uint32_t>(self.cast<const SphereTree&>().size()))[1];
          },
          "(N,) float32. unit: m")
      .def_property_readonly(
          "parents",
          [](const SphereTree& tree) {
            std::vector<std::int32_t> parents(tree.size());
            for (std::uint32_t i = 0; i < parents.size(); ++i) parents[i] = tree.parent(i);
            return copied_array<std::int32_t>({static_cast<py::ssize_t>(parents.size())},
                                              parents.data());
          },
          "(N,) int32 each node's parent, -1 for the root")
      .def(
          "level",
          [](const py::object& self, int level) {
            const auto& tree = self.cast<const SphereTree&>();
            if (level < 0 || level >= tree.depth()) {
              throw Error("level must be 0 to " + std::to_string(tree.depth() - 1) + ", got " +
                          std::to_string(level));
            }
            return sphere_views(self, tree.level_begin(level), tree.level_end(level));
          },
          py::arg("level"), "(centres (n, 3), radii (n,)) of one level, 0 being the root. unit: m")
      .def("truncated", &SphereTree::truncated, py::arg("depth"),
           "The tree cut to its first `depth` levels.")
      .def("__eq__", [](const SphereTree& a, const SphereTree& b) { return a == b; })
      .def("__repr__", [](const SphereTree& tree) {
        return "<sphys.SphereTree " + std::to_string(tree.size()) + " spheres, depth " +
               std::to_string(tree.depth()) + ", branching " + std::to_string(tree.branching()) +
               ">";
      });

  m.def(
      "build_methods",
      [] {
        std::vector<std::string> names;
        for (int i = 0; i <= static_cast<int>(tools::BuildMethod::Tight); ++i) {
          names.emplace_back(tools::method_name(static_cast<tools::BuildMethod>(i)));
        }
        return names;
      },
      "The construction methods build_tree accepts.");
  m.def(
      "build_tree",
      [](const tools::TriangleMesh& mesh, const std::string& method, int branching, int depth,
         std::uint64_t seed) {
        tools::BuildOptions options;
        options.method = tools::parse_method(method);
        options.branching = branching;
        options.depth = depth;
        options.seed = seed;
        return tools::build_sphere_tree(mesh, options);
      },
      py::arg("mesh"), py::kw_only(), py::arg("method") = "combined", py::arg("branching") = 8,
      py::arg("depth") = 3, py::arg("seed") = 1, py::call_guard<py::gil_scoped_release>(),
      "A sphere-tree each level of which covers the whole surface of the mesh, certified on its "
      "triangles. `method`: one of build_methods(); `branching` 2..8; `depth` levels including "
      "the root; `seed` fixes every random choice.");
  m.def(
      "read_sph",
      [](const std::filesystem::path& path, const std::optional<std::array<double, 3>>& shift) {
        tools::SphReadOptions options;
        if (shift) options.shift = {(*shift)[0], (*shift)[1], (*shift)[2]};
        return tools::read_sph(path, options);
      },
      py::arg("path"), py::kw_only(), py::arg("shift") = std::nullopt,
      "Reads a .sph file (Bradshaw's toolkit format). `shift` (m) is added to every centre: the "
      "toolkit's centres are relative to the mesh's bounding-box centre.");
  m.def(
      "write_sph",
      [](const std::filesystem::path& path, const SphereTree& tree) {
        tools::write_sph(path, tree);
      },
      py::arg("path"), py::arg("tree"), "Writes the tree as a .sph file, whole or not at all.");

  py::class_<tools::LevelQuality>(
      m, "LevelQuality",
      "How well one level approximates the mesh: distances as fractions of the mesh's "
      "bounding-box diagonal, volumes as multiples of the mesh's volume, all sampled.")
      .def_readonly("level", &tools::LevelQuality::level, "the level, 0 being the root")
      .def_readonly("spheres", &tools::LevelQuality::spheres, "spheres in the level (a count)")
      .def_readonly("coverage", &tools::LevelQuality::coverage,
                    "fraction of the surface inside (want 1)")
      .def_readonly("worst_gap", &tools::LevelQuality::worst_gap,
                    "largest distance from an uncovered surface sample to the nearest sphere. "
                    "unit: the mesh's bounding-box diagonal")
      .def_readonly("outside_volume", &tools::LevelQuality::outside_volume,
                    "volume of the spheres' union outside the mesh. unit: the mesh's volume")
      .def_readonly("worst_protrusion", &tools::LevelQuality::worst_protrusion,
                    "largest distance from the union's boundary outside the mesh to the mesh. "
                    "unit: the mesh's bounding-box diagonal")
      .def("__repr__", [](const tools::LevelQuality& q) {
        return "<sphys.LevelQuality level " + std::to_string(q.level) + ", " +
               std::to_string(q.spheres) + " spheres, coverage " + std::to_string(q.coverage) + ">";
      });
  m.def(
      "tree_quality",
      [](const SphereTree& tree, const tools::TriangleMesh& mesh, std::size_t surface_samples,
         std::size_t volume_samples, std::size_t boundary_samples, std::uint64_t seed) {
        return tools::measure_tree(
            tree, tools::MeshQuery(mesh),
            quality_options(surface_samples, volume_samples, boundary_samples, seed));
      },
      py::arg("tree"), py::arg("mesh"), py::kw_only(), py::arg("surface_samples") = 100000,
      py::arg("volume_samples") = 400000, py::arg("boundary_samples") = 400, py::arg("seed") = 2008,
      py::call_guard<py::gil_scoped_release>(),
      "A LevelQuality per level of the tree against the mesh it bounds (in the same frame).");
  m.def(
      "sphere_quality",
      [](const py::array_t<double, py::array::c_style | py::array::forcecast>& centres,
         const py::array_t<double, py::array::c_style | py::array::forcecast>& radii,
         const tools::TriangleMesh& mesh, std::size_t surface_samples, std::size_t volume_samples,
         std::size_t boundary_samples, std::uint64_t seed) {
        const std::vector<Sphere> spheres = spheres_from(centres, radii);
        py::gil_scoped_release unlocked;
        return tools::measure_level(
            spheres, tools::MeshQuery(mesh),
            quality_options(surface_samples, volume_samples, boundary_samples, seed));
      },
      py::arg("centres"), py::arg("radii"), py::arg("mesh"), py::kw_only(),
      py::arg("surface_samples") = 100000, py::arg("volume_samples") = 400000,
      py::arg("boundary_samples") = 400, py::arg("seed") = 2008,
      "The LevelQuality of any set of spheres (centres (N, 3), radii (N,), m), e.g. from "
      "another tool.");
}

}  // namespace sphys::python
