// Robots simulated in a world (World.add_robot): a Robot handle whose joints are read and driven
// as PyBullet users do it, numpy arrays in the model's joint order in and out.

#include <initializer_list>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "sphys/robot_model.h"

namespace sphys::python {
namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A robot of a Python World: the world (kept alive while the handle is) and the robot's id.
struct SimulatedRobotHandle {
  SharedWorld world;
  RobotId id;
};

// One value per joint, from a number (the same for every joint) or any (J,) array.
std::vector<double> per_joint(const py::handle& value, const char* what, std::size_t joints) {
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
    return std::vector<double>(joints, value.cast<double>());
  }
  const Doubles array = Doubles::ensure(value);
  if (!array || array.ndim() != 1 || array.shape(0) != static_cast<py::ssize_t>(joints)) {
    throw Error(std::string(what) + " must be a number or a (" + std::to_string(joints) +
                ",) array, one per joint in the model's order");
  }
  return {array.data(), array.data() + joints};
}

// A control's argument: its name in messages, its value (a number, or one per joint in the
// model's order) and the field of every joint's RobotJointControl it sets.
struct ControlArgument {
  const char* name;
  const py::object& value;
  double RobotJointControl::*field;
};

// Puts every joint of the robot under `mode` with the arguments' values (the other fields at their
// defaults), on the world's turn; sphys.Error naming an argument that is not one value per joint.
void set_controls(SimulatedRobotHandle& robot, RobotControlMode mode,
                  std::initializer_list<ControlArgument> arguments) {
  const Turn::Held turn = take_turn(*robot.world.turn);
  World& world = *robot.world.world;
  std::vector<RobotJointControl> controls(world.robot_joints(robot.id).size());
  for (RobotJointControl& control : controls) control.mode = mode;
  for (const ControlArgument& argument : arguments) {
    const std::vector<double> values = per_joint(argument.value, argument.name, controls.size());
    for (std::size_t j = 0; j < controls.size(); ++j) controls[j].*argument.field = values[j];
  }
  world.set_robot_controls(robot.id, controls);
}

// A figure of robot_joint_states as a (J,) float64 array.
template <std::vector<double> RobotJointStates::*figure>
py::array_t<double> joint_figure(const SimulatedRobotHandle& robot) {
  const Turn::Held turn = take_turn(*robot.world.turn);
  const std::vector<double> values = robot.world.world->robot_joint_states(robot.id).*figure;
  return copied_array<double>({static_cast<py::ssize_t>(values.size())}, values.data());
}

// The robot's bodies or joints as a list of ids.
template <class Id, std::span<const Id> (World::*ids)(RobotId) const>
std::vector<Id> robot_ids(const SimulatedRobotHandle& robot) {
  const Turn::Held turn = take_turn(*robot.world.turn);
  const std::span<const Id> found = (std::as_const(*robot.world.world).*ids)(robot.id);
  return {found.begin(), found.end()};
}

}  // namespace

void bind_robot_world(py::module_& m) {
  py::class_<SimulatedRobotHandle>(
      m, "Robot",
      "A robot simulated in a World (World.add_robot): its joints read and driven in the model's "
      "joint order, numpy arrays in and out. Controls last until changed; World.step applies "
      "them before every step.")
      .def_property_readonly("bodies", &robot_ids<BodyId, &World::robot_bodies>,
                             "The robot's BodyIds: the root link's, then the link each joint "
                             "moves.")
      .def_property_readonly("joints", &robot_ids<JointId, &World::robot_joints>,
                             "The robot's JointIds, one per model joint.")
      .def("joint_positions", &joint_figure<&RobotJointStates::positions>,
           "The joints' positions from the links' poses, (J,) float64. unit: rad or m")
      .def("joint_velocities", &joint_figure<&RobotJointStates::speeds>,
           "The joints' speeds, (J,) float64. unit: rad/s or m/s")
      .def("joint_efforts", &joint_figure<&RobotJointStates::efforts>,
           "The torque or force each joint applied along its axis in the last step, (J,) "
           "float64. unit: N·m or N")
      .def(
          "set_joint_targets",
          [](SimulatedRobotHandle& robot, const py::object& positions, const py::object& kp,
             const py::object& kd, const py::object& velocities, const py::object& max_efforts) {
            set_controls(robot, RobotControlMode::kPosition,
                         {{"positions", positions, &RobotJointControl::target_position},
                          {"kp", kp, &RobotJointControl::position_gain},
                          {"kd", kd, &RobotJointControl::velocity_gain},
                          {"velocities", velocities, &RobotJointControl::target_velocity},
                          {"max_efforts", max_efforts, &RobotJointControl::max_effort}});
          },
          py::arg("positions"), py::arg("kp") = RobotJointControl{}.position_gain,
          py::arg("kd") = RobotJointControl{}.velocity_gain, py::arg("velocities") = 0.0,
          py::arg("max_efforts") = std::numeric_limits<double>::infinity(),
          "Position control of every joint (PyBullet's POSITION_CONTROL): the motor drives to "
          "kp·(target − q)/dt + q̇ + kd·(velocity − q̇), with at most the URDF's effort (or "
          "max_efforts, if less). kp, kd, velocities and max_efforts: a number or one per joint.")
      .def(
          "set_joint_velocities",
          [](SimulatedRobotHandle& robot, const py::object& velocities,
             const py::object& max_efforts) {
            set_controls(robot, RobotControlMode::kVelocity,
                         {{"velocities", velocities, &RobotJointControl::target_velocity},
                          {"max_efforts", max_efforts, &RobotJointControl::max_effort}});
          },
          py::arg("velocities"), py::arg("max_efforts") = std::numeric_limits<double>::infinity(),
          "Velocity control of every joint: the motor drives to the speed (rad/s or m/s) with at "
          "most the URDF's effort (or max_efforts, if less).")
      .def(
          "apply_torques",
          [](SimulatedRobotHandle& robot, const py::object& torques) {
            set_controls(robot, RobotControlMode::kTorque,
                         {{"torques", torques, &RobotJointControl::torque}});
          },
          py::arg("torques"),
          "Torque control of every joint: the torque (N·m, or N for a sliding joint) between "
          "its links in every step until changed, at most the URDF's effort; no motor.")
      .def(
          "set_configuration",
          [](SimulatedRobotHandle& robot, const py::object& positions) {
            const Turn::Held turn = take_turn(*robot.world.turn);
            World& world = *robot.world.world;
            world.set_robot_configuration(
                robot.id, per_joint(positions, "positions", world.robot_joints(robot.id).size()));
          },
          py::arg("positions"),
          "Puts every link where the joint values place it, the root where it stands, all at "
          "rest: a reset (sphys.Error for a value outside its limits).")
      .def(
          "link_poses",
          [](const SimulatedRobotHandle& robot) {
            const Turn::Held turn = take_turn(*robot.world.turn);
            const std::vector<Eigen::Isometry3d> poses =
                robot.world.world->robot_link_poses_in_world(robot.id);
            std::vector<double> rows;
            for (const Eigen::Isometry3d& pose : poses) {
              const Eigen::Matrix4d row_major = pose.matrix().transpose();
              rows.insert(rows.end(), row_major.data(), row_major.data() + 16);
            }
            return copied_array<double>({static_cast<py::ssize_t>(poses.size()), 4, 4},
                                        rows.data());
          },
          "Every link's pose in the world as an (L, 4, 4) float64 array of homogeneous "
          "matrices, in RobotModel.links' order. unit: m")
      .def(
          "remove",
          [](SimulatedRobotHandle& robot) {
            const Turn::Held turn = take_turn(*robot.world.turn);
            robot.world.world->remove_robot(robot.id);
          },
          "Takes the robot's bodies and joints out of the world.");

  auto world = py::reinterpret_borrow<py::class_<SharedWorld>>(m.attr("World"));
  world.def(
      "add_robot",
      [](SharedWorld& w, const FileRobotModel& model, const py::object& base, bool fixed_base) {
        Transform pose{Quat(model.base.linear().cast<float>()),
                       model.base.translation().cast<float>()};
        if (!base.is_none()) {
          const auto parts = base.cast<std::pair<py::object, py::object>>();
          pose.translation = vec3_from(parts.first, "base position");
          pose.rotation = quat_from(parts.second, "base orientation");
        }
        const Turn::Held turn = take_turn(*w.turn);
        const RobotId id =
            w.world->add_robot(model, pose, fixed_base ? RobotBase::kFixed : RobotBase::kFree);
        tools::SceneRobot placed = model.files;
        placed.position = pose.translation;
        placed.orientation = pose.rotation;
        placed.fixed_base = fixed_base;
        w.robots->added.emplace_back(id, std::move(placed));
        return SimulatedRobotHandle{w, id};
      },
      py::arg("model"), py::arg("base") = py::none(), py::arg("fixed_base") = true,
      "Adds the robot (plausible mode): one body per moving link with the URDF's masses and the "
      "model's spheres, one joint per joint with its limits. base: (position, orientation "
      "(x, y, z, w)) of the root link, or None for the model's base; fixed_base: the root is "
      "static, else free. Returns a Robot, limp (no torque) with every joint at 0 (or its "
      "nearest limit); sphys.Error naming the link for one with no mass or no spheres.");
}

}  // namespace sphys::python
