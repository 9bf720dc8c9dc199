// Robot checks from joint values: a RobotModel from a robot's files, and a world (or a query of
// it) checking configurations and straight motions of it, numpy in and out, the GIL released.

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "sphys/robot_check.h"
#include "sphys/tools/robot_model_file.h"
#include "sphys/world_query.h"

namespace sphys::python {
namespace {

using DoubleRows = py::array_t<double, py::array::c_style | py::array::forcecast>;

// An (N, J) float64 array of joint values; sphys::Error naming `what` otherwise.
DoubleRows joint_rows(const py::handle& value, const char* what, std::size_t joints) {
  DoubleRows array = DoubleRows::ensure(value);
  if (!array || array.ndim() != 2 || array.shape(1) != static_cast<py::ssize_t>(joints)) {
    throw Error(std::string(what) + " must be an (N, " + std::to_string(joints) +
                ") array of joint values (rad, m)");
  }
  return array;
}

RobotCheckSettings check_settings(bool self_collision, const QueryFilter& filter, int tree_depth) {
  RobotCheckSettings settings;
  settings.filter = filter;
  settings.self_collision = self_collision;
  settings.tree_depth = tree_depth;
  return settings;
}

py::dict check_joint_values(const WorldQuery& query, const RobotModel& model,
                            const py::object& values, bool self_collision,
                            const QueryFilter& filter, int tree_depth, std::uint32_t threads) {
  const DoubleRows rows = joint_rows(values, "values", model.joints.size());
  const RobotChecker checker(query, model, check_settings(self_collision, filter, tree_depth));
  const auto count = static_cast<std::size_t>(rows.shape(0));
  std::vector<ConfigurationResult> results(count);
  {
    py::gil_scoped_release unlocked;
    const Parallel parallel(threads);
    checker.check(std::span(rows.data(), static_cast<std::size_t>(rows.size())), results,
                  &parallel);
  }
  return configuration_results_dict(results);
}

py::dict check_motions(const WorldQuery& query, const RobotModel& model, const py::object& from,
                       const py::object& to, double resolution, bool self_collision,
                       const QueryFilter& filter, int tree_depth, std::uint32_t threads) {
  const DoubleRows starts = joint_rows(from, "from", model.joints.size());
  const DoubleRows ends = joint_rows(to, "to", model.joints.size());
  if (starts.shape(0) != ends.shape(0)) throw Error("from and to must hold as many motions");
  const RobotChecker checker(query, model, check_settings(self_collision, filter, tree_depth));
  const auto count = static_cast<std::size_t>(starts.shape(0));
  std::vector<MotionResult> results(count);
  {
    py::gil_scoped_release unlocked;
    const Parallel parallel(threads);
    checker.check_motions(std::span(starts.data(), static_cast<std::size_t>(starts.size())),
                          std::span(ends.data(), static_cast<std::size_t>(ends.size())), resolution,
                          results, &parallel);
  }
  const auto n = static_cast<py::ssize_t>(count);
  py::array_t<bool> free({n});
  py::array_t<std::uint32_t> states({n});
  py::array_t<std::int32_t> first({n});
  py::array_t<double> last_free({n});
  for (std::size_t i = 0; i < count; ++i) {
    free.mutable_data()[i] = results[i].free;
    states.mutable_data()[i] = results[i].states;
    first.mutable_data()[i] = results[i].first_collision;
    last_free.mutable_data()[i] = results[i].last_free;
  }
  py::dict d;
  d["free"] = free;
  d["states"] = states;
  d["first_collision"] = first;
  d["last_free"] = last_free;
  return d;
}

constexpr const char* kJointValuesDoc =
    "Checks N configurations of a robot from its joint values: values (N, J) float64 (rad, m, in "
    "model.joints' order), posed by the model's kinematics (float, in SIMD lanes) and checked as "
    "check_configurations checks spheres (self_collision: spheres of links the model does not "
    "allow; tree_depth: the bodies' trees' levels asked, deeper than the world's, 0 for the "
    "world's). A value that is NaN or outside its joint's limits is an error naming it. Returns a "
    "dict of (N,) arrays: free, sphere, body, other_sphere.";

constexpr const char* kMotionsDoc =
    "Checks M straight motions from[m] -> to[m] ((M, J) float64 each): states no farther apart "
    "than `resolution` in joint space, both ends included, coarse to fine, stopping at the first "
    "collision (self_collision and tree_depth as check_joint_values'). Returns a dict of (M,) "
    "arrays: free, states, first_collision (the first "
    "colliding state, -1), last_free (0..1 along the motion: the last free state before the "
    "first colliding one).";

}  // namespace

void bind_robot(py::module_& m) {
  py::class_<FileRobotModel>(m, "RobotModel",
                             "A robot as its checks need it: links, joints with limits, spheres, "
                             "disabled link pairs and the base's pose (load_robot_model).")
      .def_readonly("name", &RobotModel::name, "The robot's name in its URDF.")
      .def_property_readonly(
          "joints",
          [](const FileRobotModel& model) {
            std::vector<std::string> names;
            for (const auto& joint : model.joints) names.push_back(joint.name);
            return names;
          },
          "The moving joints' names, in the order joint values are given.")
      .def_property_readonly(
          "limits",
          [](const FileRobotModel& model) {
            std::vector<std::array<double, 2>> limits;
            for (const auto& joint : model.joints) {
              limits.push_back({joint.lower, joint.upper});
            }
            return limits;
          },
          "(lower, upper) of each joint, as joints lists them. unit: rad for "
          "turning joints, m for sliding ones")
      .def_property_readonly(
          "links",
          [](const FileRobotModel& model) {
            std::vector<std::string> names;
            for (const auto& link : model.links) names.push_back(link.name);
            return names;
          },
          "The links' names.")
      .def_property_readonly(
          "spheres", [](const FileRobotModel& model) { return model.spheres.size(); },
          "How many spheres the links have in all (a count).")
      .def(
          "set_base",
          [](FileRobotModel& model, const py::object& position, const py::object& orientation) {
            const Vec3 p = vec3_from(position, "position");
            const Quat q = quat_from(orientation, "orientation");
            model.base = Eigen::Isometry3d::Identity();
            model.base.translate(p.cast<double>());
            model.base.rotate(q.cast<double>().normalized());
          },
          py::arg("position"), py::arg("orientation") = py::make_tuple(0, 0, 0, 1),
          "Stands the robot's root link at `position` (m), turned by `orientation` (x, y, z, w).");

  m.def(
      "load_robot_model",
      [](const py::object& urdf, const py::object& spheres, const py::object& srdf,
         const std::map<std::string, std::string>& packages) {
        const std::filesystem::path urdf_path = spec_from(urdf, "urdf");
        const std::filesystem::path spheres_path = spec_from(spheres, "spheres");
        std::vector<tools::RobotPackage> list;
        for (const auto& [name, directory] : packages) list.push_back({name, directory});
        std::optional<std::filesystem::path> srdf_path;
        if (!srdf.is_none()) srdf_path = spec_from(srdf, "srdf");
        FileRobotModel model{{tools::load_robot_model(urdf_path, spheres_path, list, srdf_path)},
                             {}};
        // Absolute, so that a recording naming them replays from any folder.
        model.files.urdf = std::filesystem::absolute(urdf_path);
        model.files.spheres = std::filesystem::absolute(spheres_path);
        if (srdf_path) model.files.srdf = std::filesystem::absolute(*srdf_path);
        for (const tools::RobotPackage& package : list) {
          model.files.packages[package.name] = std::filesystem::absolute(package.directory);
        }
        return model;
      },
      py::arg("urdf"), py::arg("spheres"), py::arg("srdf") = py::none(),
      py::arg("packages") = std::map<std::string, std::string>{},
      "A RobotModel from a URDF, the spheres `sphys spherize` wrote for it (any format) and, for "
      "self-collision, an SRDF's disable_collisions; packages: {name: directory} for "
      "package:// meshes. The model keeps the files' absolute paths: a recording of a world "
      "holding the robot (RecordingWriter) names them, for `sphys view` to draw its links.");

  auto query = py::reinterpret_borrow<py::class_<SharedQuery>>(m.attr("WorldQuery"));
  auto world = py::reinterpret_borrow<py::class_<SharedWorld>>(m.attr("World"));
  query.def(
      "check_joint_values",
      [](const SharedQuery& shared, const FileRobotModel& model, const py::object& values,
         bool self_collision, const QueryFilter& filter, int tree_depth, std::uint32_t threads) {
        return check_joint_values(*shared.current(), model, values, self_collision, filter,
                                  tree_depth, threads);
      },
      py::arg("model"), py::arg("values"), py::kw_only(), py::arg("self_collision") = false,
      py::arg("filter") = QueryFilter{}, py::arg("tree_depth") = 0, py::arg("threads") = 1,
      kJointValuesDoc);
  world.def(
      "check_joint_values",
      [](const SharedWorld& w, const FileRobotModel& model, const py::object& values,
         bool self_collision, const QueryFilter& filter, int tree_depth, std::uint32_t threads) {
        return check_joint_values(*SharedQuery(w).current(), model, values, self_collision, filter,
                                  tree_depth, threads);
      },
      py::arg("model"), py::arg("values"), py::kw_only(), py::arg("self_collision") = false,
      py::arg("filter") = QueryFilter{}, py::arg("tree_depth") = 0, py::arg("threads") = 1,
      kJointValuesDoc);
  query.def(
      "check_motions",
      [](const SharedQuery& shared, const FileRobotModel& model, const py::object& from,
         const py::object& to, double resolution, bool self_collision, const QueryFilter& filter,
         int tree_depth, std::uint32_t threads) {
        return check_motions(*shared.current(), model, from, to, resolution, self_collision, filter,
                             tree_depth, threads);
      },
      py::arg("model"), py::arg("from_values"), py::arg("to_values"), py::arg("resolution"),
      py::kw_only(), py::arg("self_collision") = false, py::arg("filter") = QueryFilter{},
      py::arg("tree_depth") = 0, py::arg("threads") = 1, kMotionsDoc);
  world.def(
      "check_motions",
      [](const SharedWorld& w, const FileRobotModel& model, const py::object& from,
         const py::object& to, double resolution, bool self_collision, const QueryFilter& filter,
         int tree_depth, std::uint32_t threads) {
        return check_motions(*SharedQuery(w).current(), model, from, to, resolution, self_collision,
                             filter, tree_depth, threads);
      },
      py::arg("model"), py::arg("from_values"), py::arg("to_values"), py::arg("resolution"),
      py::kw_only(), py::arg("self_collision") = false, py::arg("filter") = QueryFilter{},
      py::arg("tree_depth") = 0, py::arg("threads") = 1, kMotionsDoc);
}

}  // namespace sphys::python
