#pragma once

// What the binding files share: how sphys's types cross into Python. Each bind_* function adds
// one area of the API to the module (module.cpp calls them in order).

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sphys/configuration_check.h"
#include "sphys/error.h"
#include "sphys/math.h"
#include "sphys/robot_model.h"
#include "sphys/slot_id.h"
#include "sphys/tools/scene.h"

namespace sphys::python {

namespace py = pybind11;

// A world's id type (sphys/slot_id.h) as the Python class `name`, with the docs of the class and
// of its index, generation and is_null: ids compare and hash by value (a dict key or a set
// member) and print as "BodyId(index=3, generation=1)".
template <class Tag>
void bind_slot_id(py::module_& m, const char* name, const char* doc, const char* index_doc,
                  const char* generation_doc, const char* is_null_doc) {
  using Id = SlotId<Tag>;
  py::class_<Id>(m, name, doc)
      .def(py::init<>(), "The null id.")
      .def_readonly("index", &Id::index, index_doc)
      .def_readonly("generation", &Id::generation, generation_doc)
      .def_property_readonly("is_null", &Id::is_null, is_null_doc)
      .def("__eq__", [](const Id& a, const Id& b) { return a == b; })
      .def("__hash__", [](const Id& id) { return (std::uint64_t{id.generation} << 32) | id.index; })
      .def("__repr__", [type = std::string(name)](const Id& id) {
        return type + "(index=" + std::to_string(id.index) +
               ", generation=" + std::to_string(id.generation) + ")";
      });
}

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
// A batched check's answers as a dict of (N,) arrays: free, sphere, body, other_sphere.
py::dict configuration_results_dict(std::span<const ConfigurationResult> results);
// A preset's name or a file's path from a str or an os.PathLike (pathlib.Path); sphys::Error
// naming `what` otherwise.
std::string spec_from(const py::handle& value, const char* what);
// A unit quaternion from (x, y, z, w), scalar last as scipy and PyBullet write it; within 1e-3 of
// unit length, then normalised.
Quat quat_from(const py::handle& value, const char* what);

void bind_mesh(py::module_& m);
void bind_tree(py::module_& m);
void bind_world(py::module_& m);
void bind_joints(py::module_& m);       // after bind_world: it adds to World
void bind_query(py::module_& m);        // after bind_world: it adds to World
void bind_robot(py::module_& m);        // after bind_query: it adds to World and WorldQuery
void bind_robot_world(py::module_& m);  // after bind_robot: it adds to World
void bind_scene(py::module_& m);
void bind_experiment(py::module_& m);

}  // namespace sphys::python

namespace sphys {
struct WorldSettings;
class World;
class WorldQuery;
}  // namespace sphys

namespace sphys::python {

// `base` with the settings a Python mapping gives, by field as docs/scenes.md names them: either
// dotted ({"solver.soft_substeps": 8}) or nested ({"solver": {"soft_substeps": 8}});
// values as Python writes them (numbers, True/False, a choice's name, 3 numbers for a vector).
// Raises sphys.Error naming the setting for an unknown one or a value out of its range, with the
// command line's messages.
WorldSettings settings_from(const py::handle& mapping, WorldSettings base);
// Every setting of the table by its dotted field, with Python values.
py::dict settings_dict(const WorldSettings& settings);

// Python threads take turns on a world (docs/python.md): every call on it first takes its turn,
// waiting with the GIL released, so that calls from many threads run one after another where the
// C++ world would turn the second away (sphys/world.h). A Simulation and its world share one turn.
// A flag under a mutex with a condition variable rather than a timed mutex: ThreadSanitizer does
// not see a timed mutex's timed lock (glibc's pthread_mutex_clocklock) and reports its unlock.
class Turn {
 public:
  // The turn, held until it goes.
  class Held {
   public:
    explicit Held(Turn& turn) : turn_(&turn) {}
    Held(Held&& other) noexcept : turn_(std::exchange(other.turn_, nullptr)) {}
    Held(const Held&) = delete;
    Held& operator=(const Held&) = delete;
    Held& operator=(Held&&) = delete;
    ~Held() {
      if (turn_ != nullptr) turn_->give_back();
    }

   private:
    Turn* turn_;
  };

  // Takes the turn now if it is free.
  [[nodiscard]] bool try_take();
  // Waits up to `wait` for the turn (called without the GIL); true when taken.
  [[nodiscard]] bool take_within(std::chrono::milliseconds wait);

 private:
  void give_back();

  std::mutex mutex_;
  std::condition_variable freed_;
  bool taken_ = false;  // guarded by mutex_
};

// Takes the turn, waiting with the GIL released (called with the GIL held); between waits of
// 50 ms it takes the GIL back to let Ctrl-C through.
[[nodiscard]] Turn::Held take_turn(Turn& turn);

// The Python RobotModel: the model and the files it was loaded from (absolute paths, as a scene
// names a robot's), which a recording of a world holding the robot names so that a viewer loads
// its links' meshes.
struct FileRobotModel : RobotModel {
  tools::SceneRobot files;  // the files alone: no pose, configuration or targets
};

// The robots of a Python world, in the order they were added (a Simulation's scene's first), each
// with its files and base as a scene names a robot: what a recording of the world keeps of them.
// Changed and read on the world's turn.
struct WorldRobots {
  std::vector<std::pair<RobotId, tools::SceneRobot>> added;
};

// The Python World: the world, its turn and its robots. `world` owns the world, or points into a
// Simulation that the Python object keeps alive.
struct SharedWorld {
  std::shared_ptr<World> world;
  std::shared_ptr<Turn> turn = std::make_shared<Turn>();
  std::shared_ptr<WorldRobots> robots = std::make_shared<WorldRobots>();
};

// The Python WorldQuery: the query's snapshot of the world, replaced whole by refresh() (which
// takes the world's turn), so that queries on many threads at once each read one snapshot whole.
class SharedQuery {
 public:
  explicit SharedQuery(SharedWorld world);
  // The query as last made or refreshed, kept alive for the caller's query.
  [[nodiscard]] std::shared_ptr<const WorldQuery> current() const;
  void refresh();

 private:
  SharedWorld world_;
  mutable std::mutex swap_;  // guards `query_` while it is copied or replaced
  std::shared_ptr<const WorldQuery> query_;
};

}  // namespace sphys::python
