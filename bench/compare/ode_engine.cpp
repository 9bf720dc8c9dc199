#include <algorithm>
#include <array>
#include <memory>
#include <ode/ode.h>
#include <vector>

#include "engine.h"
#include "jointed_scenes.h"
#include "sphys/error.h"

namespace sphys::compare {
namespace {

// ODE with its defaults where the scene is silent: QuickStep (20 iterations), ERP 0.2, CFM 1e-5,
// a hash space of one simple space per body, auto-disable (sleep) on. Each body carries its
// shape's leaf spheres as sphere geoms at their offsets, in its own space, so that they are
// tested against other bodies' only. Hinges are dJointCreateHinge with the scene's angle limits
// as stops; ball joints dJointCreateBall, which has no cone or twist limit in ODE 0.16, with an
// angular motor in Euler mode beside it for the limits (ODE's way for a ragdoll): stops at ± the
// cone's angle about two axes across the joint's axis and ± the twist span about it, a box of
// swing angles around the cone (as wide across, √2 wider along the diagonals). A joint's bodies
// make no contacts with each other.
class OdeEngine final : public Engine {
 public:
  explicit OdeEngine(const BenchScene& bench)
      : dt_(bench.time_step),
        friction_(bench.friction),
        restitution_(bench.restitution),
        jointed_(!bench.joints.empty()) {
    dInitODE2(0);
    world_ = dWorldCreate();
    dWorldSetGravity(world_, 0, -9.81, 0);
    dWorldSetAutoDisableFlag(world_, 1);
    space_ = dHashSpaceCreate(nullptr);
    contacts_group_ = dJointGroupCreate(0);
    dCreatePlane(space_, 0, 1, 0, 0);
    for (std::size_t b = 0; b < bench.start.size(); ++b) {
      const BenchShape& shape = bench.shape(b);
      const Transform& start = bench.start[b];
      const Mat3& I = shape.inertia;
      const dBodyID body = dBodyCreate(world_);
      dMass mass;
      dMassSetParameters(&mass, shape.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2),
                         I(1, 2));
      dBodySetMass(body, &mass);
      const dSpaceID body_space = dSimpleSpaceCreate(space_);
      for (const Sphere& leaf : shape.leaves) {
        const dGeomID geom = dCreateSphere(body_space, leaf.radius);
        dGeomSetBody(geom, body);
        dGeomSetOffsetPosition(geom, leaf.center.x(), leaf.center.y(), leaf.center.z());
      }
      dBodySetPosition(body, start.translation.x(), start.translation.y(), start.translation.z());
      const dQuaternion q = {start.rotation.w(), start.rotation.x(), start.rotation.y(),
                             start.rotation.z()};
      dBodySetQuaternion(body, q);
      bodies_.push_back(body);
    }
    for (const tools::JointSpec& joint : bench.joints) add_joint(bench, joint);
  }

  ~OdeEngine() override {
    dJointGroupDestroy(contacts_group_);
    dSpaceDestroy(space_);
    dWorldDestroy(world_);
    dCloseODE();
  }
  OdeEngine(const OdeEngine&) = delete;
  OdeEngine& operator=(const OdeEngine&) = delete;

  void step() override {
    contacts_ = 0;
    deepest_ = 0.0;
    dSpaceCollide(space_, this, &OdeEngine::near);
    dWorldQuickStep(world_, dt_);
    dJointGroupEmpty(contacts_group_);
  }

  void read(std::vector<BodyState>& out) const override {
    out.clear();
    for (const dBodyID body : bodies_) {
      const dReal* p = dBodyGetPosition(body);
      const dReal* q = dBodyGetQuaternion(body);
      const dReal* v = dBodyGetLinearVel(body);
      const dReal* w = dBodyGetAngularVel(body);
      BodyState state;
      state.pose.translation = Vec3d(p[0], p[1], p[2]).cast<float>();
      state.pose.rotation = Quat(static_cast<float>(q[0]), static_cast<float>(q[1]),
                                 static_cast<float>(q[2]), static_cast<float>(q[3]));
      state.linear_velocity = Vec3d(v[0], v[1], v[2]).cast<float>();
      state.angular_velocity = Vec3d(w[0], w[1], w[2]).cast<float>();
      out.push_back(state);
    }
  }

  [[nodiscard]] std::uint32_t contacts() const override { return contacts_; }
  [[nodiscard]] std::uint32_t joints() const override { return joints_; }
  [[nodiscard]] float deepest_penetration() const override { return static_cast<float>(deepest_); }
  // Auto-disable: a disabled body is ODE's sleeping one.
  [[nodiscard]] std::optional<std::uint32_t> asleep() const override {
    std::uint32_t count = 0;
    for (const dBodyID body : bodies_) count += dBodyIsEnabled(body) == 0 ? 1 : 0;
    return count;
  }

 private:
  using Vec3d = Eigen::Vector3d;

  // Euler angles: axis 0 across the joint's axis on body a, axis 2 the joint's axis on body b,
  // their angles 0 at the start.
  void add_swing_limits(dBodyID a, dBodyID b, const Vec3& axis, const JointDesc& ball) {
    const dJointID motor = dJointCreateAMotor(world_, nullptr);
    dJointAttach(motor, a, b);
    dJointSetAMotorMode(motor, dAMotorEuler);
    const Vec3 across = axis.unitOrthogonal();
    dJointSetAMotorAxis(motor, 0, 1, across.x(), across.y(), across.z());
    dJointSetAMotorAxis(motor, 2, 2, axis.x(), axis.y(), axis.z());
    const std::array<dReal, 3> spans = {ball.cone.angle, ball.cone.angle, twist_span(ball)};
    for (int i = 0; i < 3; ++i) {
      dJointSetAMotorParam(motor, dParamLoStop + i * dParamGroup, -spans[i]);
      dJointSetAMotorParam(motor, dParamHiStop + i * dParamGroup, spans[i]);
    }
  }

  // ODE takes a joint's anchor and axis in the world, at the bodies' start poses.
  void add_joint(const BenchScene& bench, const tools::JointSpec& joint) {
    const dBodyID a = joint.body_a ? bodies_[*joint.body_a] : nullptr;
    const dBodyID b = bodies_[joint.body_b.value()];
    const Transform& start_b = bench.start[*joint.body_b];
    const Vec3 anchor = start_b.apply(joint.desc.anchor_b);
    const Vec3 axis = start_b.rotation * joint.desc.axis_b;
    dJointID id = nullptr;
    if (joint.desc.type == JointType::kHinge) {
      id = dJointCreateHinge(world_, nullptr);
      dJointAttach(id, a, b);
      dJointSetHingeAnchor(id, anchor.x(), anchor.y(), anchor.z());
      dJointSetHingeAxis(id, axis.x(), axis.y(), axis.z());
      if (joint.desc.limit.enabled) {
        dJointSetHingeParam(id, dParamLoStop, joint.desc.limit.lower);
        dJointSetHingeParam(id, dParamHiStop, joint.desc.limit.upper);
      }
    } else if (joint.desc.type == JointType::kBall) {
      id = dJointCreateBall(world_, nullptr);
      dJointAttach(id, a, b);
      dJointSetBallAnchor(id, anchor.x(), anchor.y(), anchor.z());
      if (joint.desc.cone.enabled && a != nullptr) add_swing_limits(a, b, axis, joint.desc);
    } else {
      throw Error("ode: the comparison builds hinges and ball joints only");
    }
    ++joints_;
  }

  static void near(void* data, dGeomID a, dGeomID b) {
    if (dGeomIsSpace(a) != 0 || dGeomIsSpace(b) != 0) {
      dSpaceCollide2(a, b, data, &OdeEngine::near);  // a bunny's space: its leaves
      return;
    }
    auto* engine = static_cast<OdeEngine*>(data);
    const dBodyID body_a = dGeomGetBody(a);
    const dBodyID body_b = dGeomGetBody(b);
    // Sleeping bodies and the plane: nothing to do.
    const bool a_still = body_a == nullptr || dBodyIsEnabled(body_a) == 0;
    const bool b_still = body_b == nullptr || dBodyIsEnabled(body_b) == 0;
    if (body_a == body_b || (a_still && b_still)) return;
    if (engine->jointed_ && body_a != nullptr && body_b != nullptr &&
        dAreConnectedExcluding(body_a, body_b, dJointTypeContact) != 0) {
      return;
    }
    dContact contact{};
    if (dCollide(a, b, 1, &contact.geom, sizeof(dContact)) == 0) return;
    contact.surface.mode = dContactBounce | dContactApprox1;
    contact.surface.mu = engine->friction_;
    contact.surface.bounce = engine->restitution_;
    contact.surface.bounce_vel = 1.0;  // as sphys's restitution threshold
    const dJointID joint = dJointCreateContact(engine->world_, engine->contacts_group_, &contact);
    dJointAttach(joint, body_a, body_b);
    ++engine->contacts_;
    engine->deepest_ = std::max(engine->deepest_, contact.geom.depth);
  }

  dReal dt_;
  dReal friction_;
  dReal restitution_;
  bool jointed_;  // whether contacts between joined bodies must be left out
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_group_ = nullptr;
  std::vector<dBodyID> bodies_;
  std::uint32_t contacts_ = 0;
  std::uint32_t joints_ = 0;  // created between the bodies
  dReal deepest_ = 0.0;
};

}  // namespace

std::unique_ptr<Engine> make_ode_engine(const BenchScene& scene) {
  return std::make_unique<OdeEngine>(scene);
}

}  // namespace sphys::compare
