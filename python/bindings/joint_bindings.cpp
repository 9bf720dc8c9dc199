// Joints (sphys/joint.h, docs/joints.md): their types, descriptions and ids, and the World's
// add_joint / remove_joint, setters and read-back. Vectors go in as any three numbers and come out
// as numpy arrays; the world checks every field and raises sphys.Error naming it.

#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "sphys/joint.h"
#include "sphys/world.h"

namespace sphys::python {
namespace {

py::array_t<float> vec3_array(const Vec3& v) { return copied_array<float>({3}, v.data()); }

// A property of three numbers (unit in `doc`) read as a numpy array and set from any sequence,
// sphys.Error naming the field for anything else.
template <typename Owner, Vec3 Owner::*member>
void def_vec3(py::class_<Owner>& owner, const char* name, const char* doc) {
  owner.def_property(
      name, [](const Owner& o) { return vec3_array(o.*member); },
      [name](Owner& o, const py::object& value) { o.*member = vec3_from(value, name); }, doc);
}

void bind_parts(py::module_& m) {
  py::enum_<JointType>(m, "JointType", "What a joint leaves free between its bodies.")
      .value("HINGE", JointType::kHinge,
             "Revolute: turning about the axis; angle limits, motor and spring.")
      .value("SLIDER", JointType::kSlider,
             "Prismatic: sliding along the axis, no turning; position limits, motor, spring.")
      .value("BALL", JointType::kBall,
             "Spherical: any turning; an optional swing cone and twist limit.")
      .value("WELD", JointType::kWeld, "Fixed: nothing, stiff or soft (JointDesc.spring).")
      .value("DISTANCE", JointType::kDistance,
             "The anchors' distance: a rod, a spring, or a rope between min and max length.")
      // pybind11's own __init__ and value have no docstring: these replace them.
      .def(py::init([](int value) {
             if (value < 0 || value > static_cast<int>(JointType::kDistance)) {
               throw Error("JointType: no type " + std::to_string(value) + " (0 to 4)");
             }
             return static_cast<JointType>(value);
           }),
           py::arg("value"), "The type of the given number, 0 (HINGE) to 4 (DISTANCE).")
      .def_property_readonly(
          "value", [](JointType type) { return static_cast<int>(type); },
          "The type's number, 0 (HINGE) to 4 (DISTANCE).");

  py::class_<JointLimit>(m, "JointLimit",
                         "Limits on a joint's angle (hinge, ball twist; rad), position (slider; "
                         "m) or length (distance; m); lower <= upper.")
      .def(py::init([](bool enabled, float lower, float upper) {
             return JointLimit{enabled, lower, upper};
           }),
           py::kw_only(), py::arg("enabled") = JointLimit{}.enabled,
           py::arg("lower") = JointLimit{}.lower, py::arg("upper") = JointLimit{}.upper,
           "Limits from lower to upper (rad or m, as the joint's position); off unless enabled.")
      .def_readwrite("enabled", &JointLimit::enabled, "False leaves the joint free.")
      .def_readwrite("lower", &JointLimit::lower, "unit: rad or m, as the joint's position")
      .def_readwrite("upper", &JointLimit::upper, "unit: rad or m, as the joint's position");

  py::class_<JointMotor>(m, "JointMotor",
                         "A motor driving a hinge's or slider's speed with a bounded torque or "
                         "force.")
      .def(py::init([](bool enabled, float speed, float max_effort) {
             return JointMotor{enabled, speed, max_effort};
           }),
           py::kw_only(), py::arg("enabled") = JointMotor{}.enabled,
           py::arg("speed") = JointMotor{}.speed, py::arg("max_effort") = JointMotor{}.max_effort,
           "A motor to speed (rad/s or m/s) with at most max_effort (N·m or N); off unless "
           "enabled.")
      .def_readwrite("enabled", &JointMotor::enabled, "False: no motor.")
      .def_readwrite("speed", &JointMotor::speed,
                     "The relative speed it drives to (body b against body a). unit: rad/s "
                     "(hinge), m/s (slider)")
      .def_readwrite("max_effort", &JointMotor::max_effort,
                     "The most it applies, >= 0. unit: N·m (hinge), N (slider)");

  py::class_<JointSpring>(m, "JointSpring",
                          "A spring-damper on a joint's position, as a frequency (Hz) and a "
                          "damping ratio of the joint's effective mass.")
      .def(py::init([](bool enabled, float hertz, float damping_ratio, float target) {
             return JointSpring{enabled, hertz, damping_ratio, target};
           }),
           py::kw_only(), py::arg("enabled") = JointSpring{}.enabled,
           py::arg("hertz") = JointSpring{}.hertz,
           py::arg("damping_ratio") = JointSpring{}.damping_ratio,
           py::arg("target") = JointSpring{}.target,
           "A spring of hertz (Hz) and damping_ratio (dimensionless) pulling to target (rad or "
           "m); off unless enabled.")
      .def_readwrite("enabled", &JointSpring::enabled, "False: no spring.")
      .def_readwrite("hertz", &JointSpring::hertz,
                     "Its frequency, >= 0; 0 is no stiffness (a distance joint's rope). unit: Hz")
      .def_readwrite("damping_ratio", &JointSpring::damping_ratio,
                     "Its damping ratio, >= 0; 1 is critical damping. unit: dimensionless")
      .def_readwrite("target", &JointSpring::target,
                     "The position it pulls to (hinge, slider; a distance joint's is "
                     "JointDesc.length). unit: rad or m");

  py::class_<JointCone>(m, "JointCone",
                        "A ball joint's swing cone: the angle between the two bodies' axes at "
                        "most.")
      .def(py::init([](bool enabled, float angle) {
             return JointCone{enabled, angle};
           }),
           py::kw_only(), py::arg("enabled") = JointCone{}.enabled,
           py::arg("angle") = JointCone{}.angle,
           "A cone of half-angle `angle` (rad, 0..π); off unless enabled.")
      .def_readwrite("enabled", &JointCone::enabled, "False: any swing.")
      .def_readwrite("angle", &JointCone::angle, "Half-angle of the cone, 0..π. unit: rad");
}

void bind_desc(py::module_& m) {
  py::class_<JointDesc> desc(
      m, "JointDesc",
      "What World.add_joint needs. Anchors and axes are in each body's frame (the world's for "
      "BodyId(), the world). Angles are measured from the bodies' relative orientation when the "
      "joint is added, about body a's axis; a slider's position is the anchors' offset along body "
      "a's axis.");
  desc.def(py::init([](JointType type, BodyId body_a, BodyId body_b, const py::object& anchor_a,
                       const py::object& anchor_b, const py::object& axis_a,
                       const py::object& axis_b, const JointLimit& limit, const JointMotor& motor,
                       const JointSpring& spring, const JointCone& cone, float friction,
                       float length, bool collide_connected) {
             JointDesc d;
             d.type = type;
             d.body_a = body_a;
             d.body_b = body_b;
             d.anchor_a = vec3_from(anchor_a, "anchor_a");
             d.anchor_b = vec3_from(anchor_b, "anchor_b");
             d.axis_a = vec3_from(axis_a, "axis_a");
             d.axis_b = vec3_from(axis_b, "axis_b");
             d.limit = limit;
             d.motor = motor;
             d.spring = spring;
             d.cone = cone;
             d.friction = friction;
             d.length = length;
             d.collide_connected = collide_connected;
             return d;
           }),
           py::kw_only(), py::arg("type") = JointDesc{}.type, py::arg("body_a") = BodyId{},
           py::arg("body_b") = BodyId{}, py::arg("anchor_a") = py::make_tuple(0, 0, 0),
           py::arg("anchor_b") = py::make_tuple(0, 0, 0),
           py::arg("axis_a") = py::make_tuple(1, 0, 0), py::arg("axis_b") = py::make_tuple(1, 0, 0),
           py::arg("limit") = JointLimit{}, py::arg("motor") = JointMotor{},
           py::arg("spring") = JointSpring{}, py::arg("cone") = JointCone{},
           py::arg("friction") = JointDesc{}.friction, py::arg("length") = JointDesc{}.length,
           py::arg("collide_connected") = JointDesc{}.collide_connected,
           "A joint of `type` between body_a and body_b (BodyId() for the world): anchors (m) and "
           "axes in each body's frame, the optional limit, motor, spring and cone, the friction "
           "(N·m or N), a distance joint's length (m), and whether the two bodies still "
           "collide.")
      .def_readwrite("type", &JointDesc::type, "What the joint leaves free (JointType).")
      .def_readwrite("body_a", &JointDesc::body_a,
                     "A body of the world, or BodyId() for the world.")
      .def_readwrite("body_b", &JointDesc::body_b,
                     "A body of the world, or BodyId() for the world.")
      .def_readwrite("limit", &JointDesc::limit,
                     "Hinge: angle; slider: position; ball: twist angle; distance: min and max "
                     "length (JointLimit).")
      .def_readwrite("motor", &JointDesc::motor, "Hinge and slider (JointMotor).")
      .def_readwrite("spring", &JointDesc::spring,
                     "Hinge, slider, distance; a weld's softness, its target unused (JointSpring).")
      .def_readwrite("cone", &JointDesc::cone, "Ball (JointCone).")
      .def_readwrite("friction", &JointDesc::friction,
                     "The most torque (hinge, ball: about every axis) or force (slider) with "
                     "which the joint resists its bodies' relative motion, >= 0; 0 is none. "
                     "unit: N·m or N")
      .def_readwrite("length", &JointDesc::length,
                     "A distance joint's length: its rod's, or its spring's rest length, > 0. "
                     "unit: m")
      .def_readwrite("collide_connected", &JointDesc::collide_connected,
                     "Whether the two bodies' contacts with each other count (off: they pass "
                     "through each other).");
  def_vec3<JointDesc, &JointDesc::anchor_a>(desc, "anchor_a",
                                            "The joint's point on body a, body frame. unit: m");
  def_vec3<JointDesc, &JointDesc::anchor_b>(desc, "anchor_b",
                                            "The joint's point on body b, body frame. unit: m");
  def_vec3<JointDesc, &JointDesc::axis_a>(
      desc, "axis_a",
      "The hinge's, slider's or ball's twist axis on body a, not zero (normalised when added).");
  def_vec3<JointDesc, &JointDesc::axis_b>(desc, "axis_b", "As axis_a, on body b.");

  bind_slot_id<JointTag>(
      m, "JointId",
      "A joint of a world: its slot and the slot's generation. JointId() names no joint.",
      "The joint's slot in its world's joints.",
      "The slot's generation when the joint was added, from 1 (0: the null id).",
      "True for JointId(), which names no joint.");

  py::class_<JointState>(m, "JointState", "What a joint did in the last step that solved it.")
      .def_readonly("position", &JointState::position,
                    "Hinge: angle (rad); slider: position (m); ball: twist angle (rad); "
                    "distance: length (m); weld: 0.")
      .def_readonly("speed", &JointState::speed, "The rate of `position`. unit: rad/s or m/s")
      .def_readonly("gap", &JointState::gap,
                    "How far the joint is from what it holds (the anchors apart, body b's "
                    "anchor off the axis, a length off its rod's or outside its limits). unit: m")
      .def_property_readonly(
          "force", [](const JointState& s) { return vec3_array(s.force); },
          "The force (N, world frame) the joint applied to body b at its anchor; body a took "
          "the opposite.")
      .def_property_readonly(
          "torque", [](const JointState& s) { return vec3_array(s.torque); },
          "The torque (N·m, world frame) it applied to body b besides the force's moment.");
}

// A World method on one joint that changes it: the turn taken, then the world's setter.
template <typename Part, void (World::*set)(JointId, const Part&)>
auto joint_setter() {
  return [](SharedWorld& w, JointId joint, const Part& part) {
    const Turn::Held turn = take_turn(*w.turn);
    (w.world.get()->*set)(joint, part);
  };
}

// A World method that reads one joint: the turn taken, then the world's answer.
template <auto read>
auto joint_reader() {
  return [](const SharedWorld& w, JointId joint) {
    const Turn::Held turn = take_turn(*w.turn);
    return (std::as_const(*w.world).*read)(joint);
  };
}

void bind_world_joints(py::module_& m) {
  auto world = py::reinterpret_borrow<py::class_<SharedWorld>>(m.attr("World"));
  world
      .def(
          "add_joint",
          [](SharedWorld& w, const JointDesc& desc) {
            const Turn::Held turn = take_turn(*w.turn);
            return w.world->add_joint(desc);
          },
          py::arg("desc"),
          "Joins two bodies, or a body and the world (BodyId()), by a joint solved with the "
          "contacts (plausible mode only); its bodies wake. Returns its JointId; sphys.Error "
          "naming the field for bad input.")
      .def(
          "remove_joint",
          [](SharedWorld& w, JointId joint) {
            const Turn::Held turn = take_turn(*w.turn);
            w.world->remove_joint(joint);
          },
          py::arg("joint"),
          "Removes a joint and wakes its bodies; its id names no joint from then on (sphys.Error "
          "for a stale id).")
      .def("joint_alive", joint_reader<&World::joint_alive>(), py::arg("joint"),
           "Whether the id names a joint of the world now.")
      .def("joint", joint_reader<&World::joint>(), py::arg("joint"),
           "The joint's JointDesc as added, with the setters' changes.")
      .def("joint_state", joint_reader<&World::joint_state>(), py::arg("joint"),
           "What the joint did in the last step (JointState): its position, speed, gap, force "
           "and torque.")
      .def("set_joint_motor", joint_setter<JointMotor, &World::set_joint_motor>(), py::arg("joint"),
           py::arg("motor"), "The joint's JointMotor from the next step on; its bodies wake.")
      .def("set_joint_limit", joint_setter<JointLimit, &World::set_joint_limit>(), py::arg("joint"),
           py::arg("limit"), "The joint's JointLimit from the next step on; its bodies wake.")
      .def("set_joint_spring", joint_setter<JointSpring, &World::set_joint_spring>(),
           py::arg("joint"), py::arg("spring"),
           "The joint's JointSpring from the next step on; its bodies wake.")
      .def(
          "joints_removed",
          [](const SharedWorld& w) {
            const Turn::Held turn = take_turn(*w.turn);
            const auto removed = w.world->joints_removed();
            return std::vector<JointId>(removed.begin(), removed.end());
          },
          "The joints the last remove_body removed with its body (stale ids now).");
}

}  // namespace

void bind_joints(py::module_& m) {
  bind_parts(m);
  bind_desc(m);
  bind_world_joints(m);
}

}  // namespace sphys::python
