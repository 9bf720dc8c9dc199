#include <btBulletDynamicsCommon.h>
#include <cmath>
#include <memory>
#include <vector>

#include "engine.h"
#include "jointed_scenes.h"
#include "principal_axes.h"
#include "sphys/error.h"

namespace sphys::compare {
namespace {

btVector3 to_bullet(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Vec3 from_bullet(const btVector3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}
btQuaternion to_bullet(const Quat& q) { return {q.x(), q.y(), q.z(), q.w()}; }
Quat from_bullet(const btQuaternion& q) {
  return Quat(static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()),
              static_cast<float>(q.z()));
}

// Bullet with its defaults where the scene is silent: a dynamic AABB tree broad phase, the
// sequential-impulse solver (10 iterations), split impulse off. Friction and restitution are
// combined by product, so each body gets √0.5 and √0.3 and every pair exactly 0.5 and 0.3.
// Hinges are btHingeConstraint with the scene's angle limits; ball joints btConeTwistConstraint,
// its twist axis the joint's axis, both swing spans the cone's angle and the twist span its
// limit; both with Bullet's defaults otherwise, a joint's bodies not colliding with each other.
class BulletEngine final : public Engine {
 public:
  BulletEngine(const BenchScene& bench, bool hull)
      : dt_(static_cast<btScalar>(bench.time_step)),
        dispatcher_(&configuration_),
        world_(&dispatcher_, &broad_phase_, &solver_, &configuration_) {
    world_.setGravity(btVector3(0, -9.81f, 0));
    for (const BenchShape& shape : bench.shapes) add_shape(shape, hull);
    const btScalar friction = std::sqrt(bench.friction);
    const btScalar restitution = std::sqrt(bench.restitution);

    plane_ = std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0);
    btRigidBody::btRigidBodyConstructionInfo ground(0, nullptr, plane_.get());
    ground.m_friction = friction;
    ground.m_restitution = restitution;
    ground_ = std::make_unique<btRigidBody>(ground);
    world_.addRigidBody(ground_.get());

    for (std::size_t b = 0; b < bench.start.size(); ++b) {
      const std::uint32_t shape = bench.shape_of[b];
      const PrincipalAxes& axes = axes_[shape];
      const Transform& start = bench.start[b];
      btTransform pose(to_bullet(start.rotation * axes.rotation), to_bullet(start.translation));
      btRigidBody::btRigidBodyConstructionInfo info(bench.shapes[shape].mass, nullptr,
                                                    shapes_[shape].get(), to_bullet(axes.moments));
      info.m_startWorldTransform = pose;
      info.m_friction = friction;
      info.m_restitution = restitution;
      bodies_.push_back(std::make_unique<btRigidBody>(info));
      body_axes_.push_back(axes.rotation);
      world_.addRigidBody(bodies_.back().get());
    }
    for (const tools::JointSpec& joint : bench.joints) add_joint(joint);
  }

  ~BulletEngine() override {
    for (auto& joint : joints_) world_.removeConstraint(joint.get());
    for (auto& body : bodies_) world_.removeRigidBody(body.get());
    world_.removeRigidBody(ground_.get());
  }

  void step() override { world_.stepSimulation(dt_, 0, dt_); }

  void read(std::vector<BodyState>& out) const override {
    out.clear();
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const btRigidBody* body = bodies_[b].get();
      const btTransform& pose = body->getCenterOfMassTransform();
      BodyState state;
      state.pose.rotation =
          (from_bullet(pose.getRotation()) * body_axes_[b].conjugate()).normalized();
      state.pose.translation = from_bullet(pose.getOrigin());
      state.linear_velocity = from_bullet(body->getLinearVelocity());
      state.angular_velocity = from_bullet(body->getAngularVelocity());
      out.push_back(state);
    }
  }

  [[nodiscard]] std::uint32_t joints() const override {
    return static_cast<std::uint32_t>(world_.getNumConstraints());
  }

  [[nodiscard]] std::uint32_t contacts() const override {
    std::uint32_t count = 0;
    const btDispatcher* dispatcher = world_.getDispatcher();
    for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
      count += static_cast<std::uint32_t>(
          const_cast<btDispatcher*>(dispatcher)->getManifoldByIndexInternal(i)->getNumContacts());
    }
    return count;
  }

  [[nodiscard]] float deepest_penetration() const override {
    btScalar deepest = 0;
    btDispatcher* dispatcher = const_cast<btDiscreteDynamicsWorld&>(world_).getDispatcher();
    for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
      const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(i);
      for (int c = 0; c < manifold->getNumContacts(); ++c) {
        deepest = std::max(deepest, -manifold->getContactPoint(c).getDistance());
      }
    }
    return static_cast<float>(deepest);
  }

  [[nodiscard]] std::optional<std::uint32_t> asleep() const override {
    std::uint32_t count = 0;
    for (const auto& body : bodies_) {
      const int state = body->getActivationState();
      count += state == ISLAND_SLEEPING || state == DISABLE_SIMULATION ? 1 : 0;
    }
    return count;
  }

 private:
  // Bullet's body frame is the shape's principal frame (a diagonal inertia).
  void add_shape(const BenchShape& shape, bool hull) {
    const PrincipalAxes axes = principal_axes(shape.inertia);
    const Quat body_to_principal = axes.rotation.conjugate();
    axes_.push_back(axes);
    if (hull && shape.mesh) {
      auto convex = std::make_unique<btConvexHullShape>();
      for (const tools::Vec3d& v : shape.mesh->vertices) {
        convex->addPoint(to_bullet(body_to_principal * v.cast<float>()), false);
      }
      convex->recalcLocalAabb();
      convex->optimizeConvexHull();
      shapes_.push_back(std::move(convex));
      return;
    }
    auto compound = std::make_unique<btCompoundShape>(true, static_cast<int>(shape.leaves.size()));
    for (const Sphere& leaf : shape.leaves) {
      spheres_.push_back(std::make_unique<btSphereShape>(leaf.radius));
      btTransform place;
      place.setIdentity();
      place.setOrigin(to_bullet(body_to_principal * leaf.center));
      compound->addChildShape(place, spheres_.back().get());
    }
    shapes_.push_back(std::move(compound));
  }

  // A joint's body (Bullet's fixed body for the world) and a point or direction of the scene's
  // body frame in Bullet's.
  btRigidBody& body(std::optional<std::size_t> index) {
    return index ? *bodies_[*index] : btTypedConstraint::getFixedBody();
  }
  btVector3 in_bullet(std::optional<std::size_t> index, const Vec3& v) const {
    return to_bullet(index ? body_axes_[*index].conjugate() * v : v);
  }

  void add_joint(const tools::JointSpec& joint) {
    btRigidBody& a = body(joint.body_a);
    btRigidBody& b = body(joint.body_b);
    const JointDesc& desc = joint.desc;
    const btVector3 pivot_a = in_bullet(joint.body_a, desc.anchor_a);
    const btVector3 pivot_b = in_bullet(joint.body_b, desc.anchor_b);
    if (desc.type == JointType::kHinge) {
      auto hinge = std::make_unique<btHingeConstraint>(a, b, pivot_a, pivot_b,
                                                       in_bullet(joint.body_a, desc.axis_a),
                                                       in_bullet(joint.body_b, desc.axis_b));
      if (desc.limit.enabled) hinge->setLimit(desc.limit.lower, desc.limit.upper);
      joints_.push_back(std::move(hinge));
    } else if (desc.type == JointType::kBall) {
      // The cone's frames: x along the twist axis, body b's the same as body a's at the start.
      btTransform frame_a(
          shortestArcQuat(btVector3(1, 0, 0), in_bullet(joint.body_a, desc.axis_a).normalized()),
          pivot_a);
      const btTransform frame_b =
          b.getCenterOfMassTransform().inverse() * a.getCenterOfMassTransform() * frame_a;
      auto cone = std::make_unique<btConeTwistConstraint>(a, b, frame_a, frame_b);
      const btScalar swing = desc.cone.enabled ? desc.cone.angle : SIMD_PI;
      cone->setLimit(swing, swing, twist_span(desc));
      joints_.push_back(std::move(cone));
    } else {
      throw Error("bullet: the comparison builds hinges and ball joints only");
    }
    world_.addConstraint(joints_.back().get(), true);  // no contacts between its bodies
  }

  btScalar dt_;
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broad_phase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_;
  std::vector<PrincipalAxes> axes_;  // per shape
  std::vector<std::unique_ptr<btSphereShape>> spheres_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::unique_ptr<btCollisionShape> plane_;
  std::unique_ptr<btRigidBody> ground_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<Quat> body_axes_;  // per body: its shape's principal axes in its body frame
  std::vector<std::unique_ptr<btTypedConstraint>> joints_;
};

}  // namespace

std::unique_ptr<Engine> make_bullet_engine(const BenchScene& scene, bool hull) {
  return std::make_unique<BulletEngine>(scene, hull);
}

}  // namespace sphys::compare
