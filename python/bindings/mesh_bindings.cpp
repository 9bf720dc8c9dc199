// Meshes: load, check, decimate, normalise, mass properties, simple solids.

#include <memory>
#include <optional>
#include <string>

#include "bindings.h"
#include "sphys/tools/check_mesh.h"
#include "sphys/tools/decimate.h"
#include "sphys/tools/load_mesh.h"
#include "sphys/tools/mass_properties.h"
#include "sphys/tools/model.h"
#include "sphys/tools/normalize.h"
#include "sphys/tools/primitives.h"

namespace sphys::python {
namespace {

using tools::TriangleMesh;

// A mesh from numpy arrays, checked as every computation on a mesh checks it.
TriangleMesh mesh_from_arrays(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& vertices,
    const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& triangles,
    const std::string& name) {
  if (vertices.ndim() != 2 || vertices.shape(1) != 3) {
    throw Error("vertices must be an array of shape (N, 3)");
  }
  if (triangles.ndim() != 2 || triangles.shape(1) != 3) {
    throw Error("triangles must be an array of shape (M, 3)");
  }
  TriangleMesh mesh;
  mesh.name = name;
  const auto v = vertices.unchecked<2>();
  mesh.vertices.reserve(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i)
    mesh.vertices.emplace_back(v(i, 0), v(i, 1), v(i, 2));
  const auto t = triangles.unchecked<2>();
  mesh.triangles.reserve(static_cast<std::size_t>(t.shape(0)));
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    tools::Triangle triangle{};
    for (py::ssize_t k = 0; k < 3; ++k) {
      const std::int64_t index = t(i, k);
      if (index < 0 || index >= v.shape(0)) {
        throw Error(name + ": triangle " + std::to_string(i) + " refers to vertex " +
                    std::to_string(index) + " of " + std::to_string(v.shape(0)));
      }
      triangle[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(index);
    }
    mesh.triangles.push_back(triangle);
  }
  tools::require_usable(mesh);
  return mesh;
}

py::array_t<double> vec3d_array(const tools::Vec3d& v) {
  return copied_array<double>({3}, v.data());
}

// Eigen matrices are column-major: the transpose of a row-major copy.
py::array_t<double> mat3d_array(const tools::Mat3d& m) {
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> rows = m;
  return copied_array<double>({3, 3}, rows.data());
}

const char* method_text(tools::MassMethod method) {
  return method == tools::MassMethod::Polyhedral ? "polyhedral" : "winding_number";
}

}  // namespace

void bind_mesh(py::module_& m) {
  py::class_<TriangleMesh, std::shared_ptr<TriangleMesh>>(
      m, "Mesh",
      "An indexed triangle mesh in double precision (metres): vertices (N, 3) float64, triangles "
      "(M, 3) uint32, counter-clockwise seen from outside. Immutable: the arrays are read-only "
      "views of the mesh's own memory, no copies.")
      .def(py::init(&mesh_from_arrays), py::arg("vertices"), py::arg("triangles"),
           py::arg("name") = "mesh",
           "A mesh from a (N, 3) array of vertices (m) and a (M, 3) array of vertex indices. "
           "Raises sphys.Error for a wrong shape, an index out of range, a non-finite vertex or "
           "no triangles.")
      .def_property_readonly(
          "vertices",
          [](const py::object& self) {
            const auto& mesh = self.cast<const TriangleMesh&>();
            return view_array<double>(
                {static_cast<py::ssize_t>(mesh.vertices.size()), 3},
                mesh.vertices.empty() ? nullptr : mesh.vertices.front().data(), self);
          },
          "(N, 3) float64, read-only view. unit: m")
      .def_property_readonly(
          "triangles",
          [](const py::object& self) {
            const auto& mesh = self.cast<const TriangleMesh&>();
            return view_array<std::uint32_t>(
                {static_cast<py::ssize_t>(mesh.triangles.size()), 3},
                mesh.triangles.empty() ? nullptr : mesh.triangles.front().data(), self);
          },
          "(M, 3) uint32 vertex indices, read-only view")
      .def_readonly("name", &TriangleMesh::name, "Where the mesh came from, for messages")
      .def_property_readonly(
          "bounds",
          [](const TriangleMesh& mesh) {
            const tools::Box3d box = mesh.bounds();
            return py::make_tuple(vec3d_array(box.min()), vec3d_array(box.max()));
          },
          "(min corner, max corner) of the bounding box. unit: m")
      .def("__repr__", [](const TriangleMesh& mesh) {
        return "<sphys.Mesh '" + mesh.name + "': " + std::to_string(mesh.vertices.size()) +
               " vertices, " + std::to_string(mesh.triangles.size()) + " triangles>";
      });

  m.def(
      "load_mesh", [](const std::filesystem::path& path) { return tools::load_mesh(path); },
      py::arg("path"), py::call_guard<py::gil_scoped_release>(),
      "Reads OBJ, PLY, STL or OFF; welds vertices that share a position. Raises sphys.Error "
      "naming the file and the problem.");
  m.def(
      "load_model",
      [](const py::object& spec, std::optional<std::uint32_t> triangles) {
        const std::string text = spec_from(spec, "spec");
        py::gil_scoped_release unlocked;
        return tools::load_model(text, triangles);
      },
      py::arg("spec") = "bunny", py::arg("triangles") = std::nullopt,
      "What the command line accepts where a mesh is asked for: 'bunny' (the Stanford bunny, "
      "decimated to 2000 triangles unless `triangles` says otherwise; 0 keeps all) or a mesh "
      "file (decimated only when `triangles` is given).");
  m.def("decimate", &tools::decimate, py::arg("mesh"), py::arg("triangles"),
        py::call_guard<py::gil_scoped_release>(),
        "At most `triangles` triangles by edge collapse; a watertight mesh stays watertight or "
        "sphys.Error is raised.");

  py::class_<tools::MeshReport>(m, "MeshReport", "What check_mesh found; counts.")
      .def_readonly("triangles", &tools::MeshReport::triangles, "Triangles in the mesh")
      .def_readonly("vertices", &tools::MeshReport::vertices, "Vertices in the mesh")
      .def_readonly("degenerate_triangles", &tools::MeshReport::degenerate_triangles,
                    "Triangles with a repeated vertex or an area below 1e-12 of the bounds' "
                    "size squared")
      .def_readonly("non_finite_vertices", &tools::MeshReport::non_finite_vertices,
                    "Vertices with a NaN or infinite coordinate")
      .def_readonly("boundary_edges", &tools::MeshReport::boundary_edges,
                    "Edges used by one triangle: holes")
      .def_readonly("non_manifold_edges", &tools::MeshReport::non_manifold_edges,
                    "Edges used by three or more triangles")
      .def_readonly("misoriented_edges", &tools::MeshReport::misoriented_edges,
                    "Edges two triangles traverse the same way")
      .def_readonly("unused_vertices", &tools::MeshReport::unused_vertices,
                    "Vertices no triangle uses")
      .def_property_readonly("watertight", &tools::MeshReport::watertight,
                             "Closed, manifold and consistently oriented")
      .def("__repr__", [](const tools::MeshReport& r) {
        return "<sphys.MeshReport " + std::to_string(r.triangles) + " triangles, " +
               (r.watertight() ? "watertight" : "not watertight") + ">";
      });
  m.def("check_mesh", &tools::check_mesh, py::arg("mesh"),
        "Counts degenerate triangles, holes, non-manifold and misoriented edges.");

  py::class_<tools::MassProperties>(m, "MassProperties",
                                    "A homogeneous solid's mass properties in the mesh's frame.")
      .def_readonly("volume", &tools::MassProperties::volume, "unit: m³")
      .def_readonly("mass", &tools::MassProperties::mass, "unit: kg")
      .def_property_readonly(
          "center_of_mass",
          [](const tools::MassProperties& p) { return vec3d_array(p.center_of_mass); },
          "(3,) unit: m")
      .def_property_readonly(
          "inertia", [](const tools::MassProperties& p) { return mat3d_array(p.inertia); },
          "(3, 3) about the centre of mass, mesh axes. unit: kg·m²")
      .def_property_readonly(
          "principal_moments",
          [](const tools::MassProperties& p) { return vec3d_array(p.principal_moments); },
          "(3,) ascending. unit: kg·m²")
      .def_property_readonly(
          "principal_axes",
          [](const tools::MassProperties& p) { return mat3d_array(p.principal_axes); },
          "(3, 3) the axes as columns, matching principal_moments")
      .def_property_readonly(
          "method", [](const tools::MassProperties& p) { return method_text(p.method); },
          "'polyhedral' (exact, watertight meshes) or 'winding_number' (meshes with holes)");
  m.def(
      "mass_properties",
      [](const TriangleMesh& mesh, double density, bool force_winding_number, int columns) {
        tools::MassPropertiesOptions options;
        options.density = density;
        options.force_winding_number = force_winding_number;
        options.columns = columns;
        return tools::compute_mass_properties(mesh, options);
      },
      py::arg("mesh"), py::kw_only(), py::arg("density") = 1000.0,
      py::arg("force_winding_number") = false, py::arg("columns") = 160,
      py::call_guard<py::gil_scoped_release>(),
      "Volume, mass, centre of mass and inertia of the solid the mesh bounds, of `density` "
      "(kg/m³). Exact for watertight meshes; by winding numbers on `columns` columns otherwise.");

  py::class_<tools::NormalizedMesh>(m, "NormalizedMesh",
                                    "A mesh scaled and moved by normalize(), and how: x' = scale "
                                    "* x + translation.")
      .def_readonly("mesh", &tools::NormalizedMesh::mesh, "The mesh scaled and moved")
      .def_readonly("scale", &tools::NormalizedMesh::scale, "applied first, about the origin")
      .def_property_readonly(
          "translation", [](const tools::NormalizedMesh& n) { return vec3d_array(n.translation); },
          "(3,) applied after scaling: x' = scale x + translation. unit: m");
  m.def(
      "normalize",
      [](const TriangleMesh& mesh, double size, double density) {
        tools::MassPropertiesOptions options;
        options.density = density;
        return tools::normalize(mesh, size, options);
      },
      py::arg("mesh"), py::arg("size") = 1.0, py::kw_only(), py::arg("density") = 1000.0,
      py::call_guard<py::gil_scoped_release>(),
      "Scales uniformly so that the bounding box's longest side is `size` (m), then moves the "
      "centre of mass to the origin: the body frame.");

  m.def(
      "box",
      [](const std::array<double, 3>& size) {
        return tools::make_box({size[0], size[1], size[2]});
      },
      py::arg("size"), "A box of full side lengths `size` (3 numbers, m), centred: 12 triangles.");
  m.def("icosphere", &tools::make_icosphere, py::arg("radius"), py::arg("subdivisions") = 3,
        "A sphere of `radius` (m): an icosahedron subdivided, 20·4^subdivisions triangles.");
  m.def("torus", &tools::make_torus, py::arg("major"), py::arg("minor"), py::arg("rings") = 32,
        py::arg("sides") = 16, "A torus around y: ring radius `major`, tube radius `minor` (m).");
}

}  // namespace sphys::python
