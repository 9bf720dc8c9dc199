#pragma once

// What the binding files share: how sphys's types cross into Python. Each bind_* function adds
// one area of the API to the module (module.cpp calls them in order).

#include <array>
#include <cstddef>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <string>
#include <vector>

#include "sphys/error.h"
#include "sphys/math.h"

namespace sphys::python {

namespace py = pybind11;

// A C-contiguous numpy array of the given shape, owning a fresh copy of `data`.
template <typename T>
py::array_t<T> copied_array(const std::vector<py::ssize_t>& shape, const T* data) {
  py::array_t<T> array(shape);
  std::size_t count = 1;
  for (const py::ssize_t extent : shape) count *= static_cast<std::size_t>(extent);
  std::copy(data, data + count, array.mutable_data());
  return array;
}

// A read-only numpy view of memory that `owner` keeps alive: no copy.
template <typename T>
py::array_t<T> view_array(const std::vector<py::ssize_t>& shape, const T* data,
                          const py::handle& owner) {
  py::array_t<T> array(shape, data, owner);
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

// JSON text that sphys wrote (a summary, a scene) as Python's json module reads it: dicts, lists,
// numbers, None for null.
inline py::object from_json_text(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

// A Python value (a dict of a scene file, ...) as JSON text, for sphys's readers.
inline std::string to_json_text(const py::handle& value) {
  return py::module_::import("json").attr("dumps")(value).cast<std::string>();
}

// Three numbers from any sequence (a tuple, a list, a numpy array); sphys::Error naming `what`
// otherwise or when one is not finite.
Vec3 vec3_from(const py::handle& value, const char* what);
// A preset's name or a file's path from a str or an os.PathLike (pathlib.Path); sphys::Error
// naming `what` otherwise.
std::string spec_from(const py::handle& value, const char* what);
// A unit quaternion from (x, y, z, w), scalar last as scipy and PyBullet write it; within 1e-3 of
// unit length, then normalised.
Quat quat_from(const py::handle& value, const char* what);

void bind_mesh(py::module_& m);
void bind_tree(py::module_& m);
void bind_world(py::module_& m);
void bind_query(py::module_& m);  // after bind_world: it adds to World
void bind_scene(py::module_& m);
void bind_experiment(py::module_& m);

}  // namespace sphys::python

namespace sphys {
struct WorldSettings;
}

namespace sphys::python {

// `base` with the settings a Python mapping gives, by field as docs/scenes.md names them: either
// dotted ({"solver.soft_substeps": 8}) or nested ({"solver": {"soft_substeps": 8}});
// values as Python writes them (numbers, True/False, a choice's name, 3 numbers for a vector).
// Raises sphys.Error naming the setting for an unknown one or a value out of its range, with the
// command line's messages.
WorldSettings settings_from(const py::handle& mapping, WorldSettings base);
// Every setting of the table by its dotted field, with Python values.
py::dict settings_dict(const WorldSettings& settings);

}  // namespace sphys::python
