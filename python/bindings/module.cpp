// The native part of the Python package `sphys` (python/sphys/__init__.py re-exports it).

#include <cmath>
#include <string>

#include "bindings.h"
#include "sphys/version.h"

namespace sphys::python {

namespace {

// `count` finite numbers from any sequence of numbers, as floats.
void numbers_from(const py::handle& value, const char* what, std::size_t count, float* out) {
  const std::string expected = std::string(what) + " must be " + std::to_string(count) + " numbers";
  std::vector<double> numbers;
  try {
    numbers = value.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw Error(expected + ", got " + py::repr(value).cast<std::string>());
  }
  if (numbers.size() != count) {
    throw Error(expected + ", got " + std::to_string(numbers.size()));
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (!std::isfinite(numbers[i])) {
      throw Error(std::string(what) + " must be finite, got " +
                  py::repr(value).cast<std::string>());
    }
    out[i] = static_cast<float>(numbers[i]);
  }
}

}  // namespace

Vec3 vec3_from(const py::handle& value, const char* what) {
  Vec3 v;
  numbers_from(value, what, 3, v.data());
  return v;
}

std::string spec_from(const py::handle& value, const char* what) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__")) {
    const py::object path = py::module_::import("os").attr("fspath")(value);
    if (py::isinstance<py::str>(path)) return path.cast<std::string>();
  }
  throw Error(std::string(what) + " must be a str or a path (os.PathLike), got " +
              py::repr(value).cast<std::string>());
}

Quat quat_from(const py::handle& value, const char* what) {
  float xyzw[4];
  numbers_from(value, what, 4, xyzw);
  return Quat(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
}

}  // namespace sphys::python

PYBIND11_MODULE(_sphys, m) {
  namespace py = pybind11;
  using namespace sphys::python;
  m.doc() = "sphys: rigid-body collision handling with sphere-trees (the native module).";
  m.attr("__version__") = SPHYS_VERSION_STRING;
  // sphys's bad-input errors, with the command line's messages. A ValueError, so that code
  // catching ValueError for bad arguments catches them too.
  py::register_exception<sphys::Error>(m, "Error", PyExc_ValueError).doc() =
      "Bad input: the message names the file, line, JSON path or argument and the problem.";
  bind_mesh(m);
  bind_tree(m);
  bind_world(m);
  bind_joints(m);
  bind_query(m);
  bind_robot(m);
  bind_robot_world(m);
  bind_scene(m);
  bind_experiment(m);
}
