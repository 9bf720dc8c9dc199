#include <algorithm>
#include <memory>
#include <ode/ode.h>
#include <vector>

#include "engine.h"

namespace sphys::compare {
namespace {

// ODE with its defaults where the scene is silent: QuickStep (20 iterations), ERP 0.2, CFM 1e-5,
// a hash space of one simple space per bunny, auto-disable (sleep) on. Each bunny is one body
// carrying its leaf spheres as sphere geoms at their offsets, in its own space, so that they are
// tested against other bunnies' only.
class OdeEngine final : public Engine {
 public:
  explicit OdeEngine(const BenchScene& bench)
      : dt_(bench.time_step), friction_(bench.friction), restitution_(bench.restitution) {
    dInitODE2(0);
    world_ = dWorldCreate();
    dWorldSetGravity(world_, 0, -9.81, 0);
    dWorldSetAutoDisableFlag(world_, 1);
    space_ = dHashSpaceCreate(nullptr);
    contacts_group_ = dJointGroupCreate(0);
    dCreatePlane(space_, 0, 1, 0, 0);
    const Mat3& I = bench.inertia;
    for (const Transform& start : bench.start) {
      const dBodyID body = dBodyCreate(world_);
      dMass mass;
      dMassSetParameters(&mass, bench.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2),
                         I(1, 2));
      dBodySetMass(body, &mass);
      const dSpaceID body_space = dSimpleSpaceCreate(space_);
      for (const Sphere& leaf : bench.leaves) {
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
  [[nodiscard]] float deepest_penetration() const override { return static_cast<float>(deepest_); }
  // Auto-disable: a disabled body is ODE's sleeping one.
  [[nodiscard]] std::optional<std::uint32_t> asleep() const override {
    std::uint32_t count = 0;
    for (const dBodyID body : bodies_) count += dBodyIsEnabled(body) == 0 ? 1 : 0;
    return count;
  }

 private:
  using Vec3d = Eigen::Vector3d;

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
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_group_ = nullptr;
  std::vector<dBodyID> bodies_;
  std::uint32_t contacts_ = 0;
  dReal deepest_ = 0.0;
};

}  // namespace

std::unique_ptr<Engine> make_ode_engine(const BenchScene& scene) {
  return std::make_unique<OdeEngine>(scene);
}

}  // namespace sphys::compare
