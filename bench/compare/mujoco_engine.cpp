#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mujoco/mujoco.h>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine.h"
#include "sphys/error.h"
#include "sphys/tools/text_file.h"

namespace sphys::compare {
namespace {

// The name of the joint that holds body `body` to its parent.
std::string joint_name(std::size_t body) {
  std::string name = "j";  // appended to: GCC 12 warns falsely of "j" + a string
  name += std::to_string(body);
  return name;
}

// One body of the MJCF and, nested in it, the bodies its joints hold: its pose from its parent's
// (the world's for none), the joint to its parent at its anchor (a free joint for a body without
// one, none for the robot's fixed root), its mass and full inertia tensor at its centre of mass
// (MuJoCo's from the geoms for a static body without mass) and its leaf spheres as geoms.
void body_xml(std::ostringstream& xml, const BenchScene& bench,
              const std::vector<std::vector<std::size_t>>& children,
              const std::vector<const tools::JointSpec*>& parent_joint, std::size_t body,
              int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  const tools::JointSpec* joint = parent_joint[body];
  const Transform parent = joint && joint->body_a ? bench.start[*joint->body_a] : Transform{};
  const Transform& start = bench.start[body];
  const Vec3 p = parent.rotation.conjugate() * (start.translation - parent.translation);
  const Quat q = (parent.rotation.conjugate() * start.rotation).normalized();
  const BenchShape& shape = bench.shape(body);
  const Mat3& I = shape.inertia;
  xml << pad << "<body name=\"b" << body << "\" pos=\"" << p.x() << ' ' << p.y() << ' ' << p.z()
      << "\" quat=\"" << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << "\">\n";
  const bool fixed = bench.robot && body == bench.robot->first_body;
  if (joint == nullptr && !fixed) {
    xml << pad << "  <freejoint/>\n";
  } else if (joint != nullptr) {
    const JointDesc& desc = joint->desc;
    const Vec3& at = desc.anchor_b;
    const Vec3& axis = desc.axis_b;
    xml << pad << "  <joint name=\"" << joint_name(body) << "\" pos=\"" << at.x() << ' ' << at.y()
        << ' ' << at.z() << '"';
    if (desc.type == JointType::kHinge || desc.type == JointType::kSlider) {
      xml << " type=\"" << (desc.type == JointType::kHinge ? "hinge" : "slide") << "\" axis=\""
          << axis.x() << ' ' << axis.y() << ' ' << axis.z() << '"';
      if (desc.limit.enabled) {
        xml << " limited=\"true\" range=\"" << desc.limit.lower << ' ' << desc.limit.upper << '"';
      }
    } else if (desc.type == JointType::kBall) {
      xml << " type=\"ball\"";
      if (desc.cone.enabled) xml << " limited=\"true\" range=\"0 " << desc.cone.angle << '"';
    } else {
      throw Error("mujoco: the comparison builds hinges, sliders and ball joints only");
    }
    xml << "/>\n";
  }
  if (shape.mass > 0.0f) {
    xml << pad << "  <inertial pos=\"0 0 0\" mass=\"" << shape.mass << "\" fullinertia=\""
        << I(0, 0) << ' ' << I(1, 1) << ' ' << I(2, 2) << ' ' << I(0, 1) << ' ' << I(0, 2) << ' '
        << I(1, 2) << "\"/>\n";
  }
  for (const Sphere& leaf : shape.leaves) {
    xml << pad << "  <geom type=\"sphere\" size=\"" << leaf.radius << "\" pos=\"" << leaf.center.x()
        << ' ' << leaf.center.y() << ' ' << leaf.center.z() << "\"/>\n";
  }
  for (const std::size_t child : children[body]) {
    body_xml(xml, bench, children, parent_joint, child, indent + 2);
  }
  xml << pad << "</body>\n";
}

// The robot's link pairs that do not collide: those its joints join (MuJoCo's parent filter
// leaves out the root's children, the root being welded to the world) and the model's allowed
// pairs; and a position servo on each of its joints: a general actuator with an
// affine bias whose gains the engine sets once the model is loaded (MujocoEngine::set_gains), its
// force bounded by the joint's effort.
void robot_xml(std::ostringstream& xml, const BenchScene& bench) {
  const BenchRobot& robot = *bench.robot;
  xml << "  <contact>\n";
  const auto exclude = [&](std::size_t a, std::size_t b) {
    xml << "    <exclude body1=\"b" << a << "\" body2=\"b" << b << "\"/>\n";
  };
  for (std::size_t j = robot.first_joint; j < bench.joints.size(); ++j) {
    exclude(*bench.joints[j].body_a, *bench.joints[j].body_b);
  }
  for (const auto& [a, b] : robot.apart) exclude(a, b);
  xml << "  </contact>\n  <actuator>\n";
  for (std::size_t j = 0; j < robot.model.joints.size(); ++j) {
    const double effort = robot.model.joints[j].effort;
    xml << "    <general joint=\"" << joint_name(*bench.joints[robot.first_joint + j].body_b)
        << "\" biastype=\"affine\"";
    if (std::isfinite(effort)) {
      xml << " forcelimited=\"true\" forcerange=\"" << -effort << ' ' << effort << '"';
    }
    xml << "/>\n";
  }
  xml << "  </actuator>\n";
}

// The scene as MJCF: y up, the plane's normal +y, its bodies as kinematic trees, each joint's
// body b a child of its body a (of the world for none): hinges with their angle range, ball
// joints whose range is the cone's angle (MuJoCo's ball range bounds the whole rotation angle,
// swing and twist together; there is no separate twist limit). MuJoCo has no coefficient of
// restitution: its soft contacts keep their defaults (critically damped, no bounce); friction
// 0.5 (sliding). Its defaults elsewhere: the Newton solver, pyramidal friction cones, a parent's
// and its child's geoms not colliding; a sparse Jacobian for the many bodies; no sleeping
// (MuJoCo 2.2 has none).
// Room for the contacts of a pile, 40 per bunny (sphys makes 15 to 20 at depth 3). unit: contacts
std::size_t contact_room(const BenchScene& bench) {
  return std::max<std::size_t>(1000, 40 * bench.start.size());
}

// `rows`: MuJoCo's njmax, its room for constraint rows.
std::string mjcf(const BenchScene& bench, std::size_t rows) {
  std::ostringstream xml;
  xml.precision(9);
  const std::size_t bodies = bench.start.size();
  const std::size_t contacts = contact_room(bench);
  xml << "<mujoco model=\"" << bench.name << "\">\n"
      << "  <compiler angle=\"radian\"/>\n"
      << "  <option timestep=\"" << bench.time_step
      << "\" gravity=\"0 -9.81 0\" jacobian=\"sparse\"/>\n"
      << "  <size nconmax=\"" << contacts << "\" njmax=\"" << rows << "\"/>\n"
      << "  <default><geom friction=\"" << bench.friction << " 0.005 0.0001\"/></default>\n"
      << "  <worldbody>\n"
      << "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" zaxis=\"0 1 0\"/>\n";
  std::vector<std::vector<std::size_t>> children(bodies);
  std::vector<const tools::JointSpec*> parent_joint(bodies, nullptr);
  for (const tools::JointSpec& joint : bench.joints) {
    const std::size_t child = joint.body_b.value();
    if (parent_joint[child] != nullptr) {
      throw Error("mujoco: body " + std::to_string(child) + " is the child of two joints");
    }
    parent_joint[child] = &joint;
    if (joint.body_a) children[*joint.body_a].push_back(child);
  }
  for (std::size_t body = 0; body < bodies; ++body) {
    const tools::JointSpec* joint = parent_joint[body];
    if (joint == nullptr || !joint->body_a) body_xml(xml, bench, children, parent_joint, body, 4);
  }
  xml << "  </worldbody>\n";
  if (bench.robot) robot_xml(xml, bench);
  xml << "</mujoco>\n";
  return xml.str();
}

class MujocoEngine final : public Engine {
 public:
  explicit MujocoEngine(const BenchScene& bench) {
    // MuJoCo 2.2 reads models from files; the model goes through a temporary one.
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / "sphys-compare-mujoco.xml";
    std::array<char, 1000> error{};
    // Room for 4 constraint rows per contact (pyramidal cones), up to 12,000: MuJoCo 2.2
    // allocates an njmax² matrix (1.1 GB at 12,000), and with many degrees of freedom (1,100
    // limbs) cannot make its data at all; the room is then halved until it can, down to 1,500
    // rows. More rows than the room are dropped with a warning, which the comparison reports.
    for (std::size_t rows = std::min<std::size_t>(4 * contact_room(bench), 12000);
         model_ == nullptr && rows >= 1500; rows /= 2) {
      tools::write_text_file(file, mjcf(bench, rows));
      model_ = mj_loadXML(file.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
    }
    std::filesystem::remove(file);
    if (model_ == nullptr) throw std::runtime_error(std::string("MuJoCo: ") + error.data());
    data_ = mj_makeData(model_);
    if (bench.robot) start_robot(bench);
    mj_forward(model_, data_);
    for (std::size_t b = 0; b < bench.start.size(); ++b) {
      std::string name = "b";  // as body_xml names it
      name += std::to_string(b);
      body_ids_.push_back(mj_name2id(model_, mjOBJ_BODY, name.c_str()));
    }
  }
  ~MujocoEngine() override {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  MujocoEngine(const MujocoEngine&) = delete;
  MujocoEngine& operator=(const MujocoEngine&) = delete;

  void step() override {
    if (robot_ != nullptr) {
      targets_->next();
      for (std::size_t j = 0; j < speed_share_.size(); ++j) {
        data_->ctrl[j] = targets_->positions()[j] + speed_share_[j] * targets_->speeds()[j];
      }
    }
    mj_step(model_, data_);
  }

  [[nodiscard]] std::vector<double> robot_positions() const override {
    std::vector<double> positions;
    for (const int address : robot_qpos_) positions.push_back(data_->qpos[address]);
    return positions;
  }

  void read(std::vector<BodyState>& out) const override {
    // mj_step leaves the poses and velocities of the positions before its integration: they are
    // computed afresh for the state it reached.
    mj_kinematics(model_, data_);
    mj_comPos(model_, data_);
    mj_comVel(model_, data_);
    out.clear();
    for (const int body : body_ids_) {
      const mjtNum* p = data_->xpos + 3 * body;
      const mjtNum* q = data_->xquat + 4 * body;
      std::array<mjtNum, 6> v{};  // angular, then linear velocity, world frame, at the body's
      mj_objectVelocity(model_, data_, mjOBJ_BODY, body, v.data(), 0);  // centre of mass
      BodyState state;
      state.pose.translation =
          Vec3(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]));
      state.pose.rotation = Quat(static_cast<float>(q[0]), static_cast<float>(q[1]),
                                 static_cast<float>(q[2]), static_cast<float>(q[3]));
      state.angular_velocity =
          Vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
      state.linear_velocity =
          Vec3(static_cast<float>(v[3]), static_cast<float>(v[4]), static_cast<float>(v[5]));
      out.push_back(state);
    }
  }

  [[nodiscard]] std::uint32_t joints() const override {
    std::uint32_t count = 0;
    for (int j = 0; j < model_->njnt; ++j) count += model_->jnt_type[j] != mjJNT_FREE ? 1 : 0;
    return count;
  }

  [[nodiscard]] std::uint32_t contacts() const override {
    return static_cast<std::uint32_t>(data_->ncon);
  }
  [[nodiscard]] float deepest_penetration() const override {
    mjtNum deepest = 0;
    for (int i = 0; i < data_->ncon; ++i) deepest = std::max(deepest, -data_->contact[i].dist);
    return static_cast<float>(deepest);
  }
  [[nodiscard]] std::string warnings() const override {
    // MuJoCo resets a simulation whose accelerations blew up, and goes on from the start.
    if (data_->warning[mjWARN_BADQACC].number > 0) {
      return "unstable: MuJoCo reset the simulation (resets: " +
             std::to_string(data_->warning[mjWARN_BADQACC].number) + ")";
    }
    if (data_->warning[mjWARN_CONTACTFULL].number > 0) return "contact list full: contacts dropped";
    if (data_->warning[mjWARN_CNSTRFULL].number > 0)
      return "constraint rows full: contacts dropped";
    return "";
  }

 private:
  // The robot at its motion's start, and its servos' gains: sphys's position law per unit of
  // inertia as a PD's stiffness and damping. The law closes the share position_gain of the
  // position error and velocity_gain of the speed error in a step of dt, the PD's
  // kp = m position_gain / dt² and kv = m velocity_gain / dt, with m the joint's own entry of
  // MuJoCo's mass matrix at the start. The actuator's force, kp ctrl − kp q − kv q̇, is then
  // kp (q* − q) + kv (q̇* − q̇) for ctrl = q* + kv / kp q̇*.
  void start_robot(const BenchScene& bench) {
    robot_ = &*bench.robot;
    targets_.emplace(robot_->motion, model_->opt.timestep);
    const std::vector<double>& start = robot_->motion.waypoints.front();
    std::vector<int> dofs;
    for (std::size_t j = 0; j < start.size(); ++j) {
      const std::size_t body = *bench.joints[robot_->first_joint + j].body_b;
      const int joint = mj_name2id(model_, mjOBJ_JOINT, joint_name(body).c_str());
      robot_qpos_.push_back(model_->jnt_qposadr[joint]);
      dofs.push_back(model_->jnt_dofadr[joint]);
      data_->qpos[robot_qpos_.back()] = start[j];
    }
    mj_forward(model_, data_);
    const double dt = model_->opt.timestep;
    for (std::size_t j = 0; j < start.size(); ++j) {
      const mjtNum mass = data_->qM[model_->dof_Madr[dofs[j]]];
      const double kp = mass * robot_->gains.position_gain / (dt * dt);
      const double kv = mass * robot_->gains.velocity_gain / dt;
      model_->actuator_gainprm[j * mjNGAIN] = kp;
      model_->actuator_biasprm[j * mjNBIAS + 1] = -kp;
      model_->actuator_biasprm[j * mjNBIAS + 2] = -kv;
      speed_share_.push_back(kv / kp);
    }
  }

  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  std::vector<int> body_ids_;           // per scene body: MuJoCo's, in the trees' order
  const BenchRobot* robot_ = nullptr;   // the scene's, if it has one
  std::vector<int> robot_qpos_;         // per robot joint: its address in qpos
  std::vector<double> speed_share_;     // per robot joint: kv / kp. unit: s
  std::optional<MotionSteps> targets_;  // the robot's, step by step
};

}  // namespace

std::unique_ptr<Engine> make_mujoco_engine(const BenchScene& scene) {
  return std::make_unique<MujocoEngine>(scene);
}

}  // namespace sphys::compare
