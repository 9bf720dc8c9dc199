#include <btBulletDynamicsCommon.h>
#include <cmath>
#include <memory>
#include <vector>

#include "engine.h"
#include "principal_axes.h"

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
class BulletEngine final : public Engine {
 public:
  BulletEngine(const BenchScene& bench, bool hull)
      : dt_(static_cast<btScalar>(bench.time_step)),
        dispatcher_(&configuration_),
        world_(&dispatcher_, &broad_phase_, &solver_, &configuration_) {
    world_.setGravity(btVector3(0, -9.81f, 0));
    const PrincipalAxes axes = principal_axes(bench.inertia);
    principal_to_body_ = axes.rotation;
    const Quat body_to_principal = axes.rotation.conjugate();
    if (hull) {
      auto shape = std::make_unique<btConvexHullShape>();
      for (const tools::Vec3d& v : bench.mesh.vertices) {
        shape->addPoint(to_bullet(body_to_principal * v.cast<float>()), false);
      }
      shape->recalcLocalAabb();
      shape->optimizeConvexHull();
      bunny_ = std::move(shape);
    } else {
      auto shape = std::make_unique<btCompoundShape>(true, static_cast<int>(bench.leaves.size()));
      for (const Sphere& leaf : bench.leaves) {
        spheres_.push_back(std::make_unique<btSphereShape>(leaf.radius));
        btTransform place;
        place.setIdentity();
        place.setOrigin(to_bullet(body_to_principal * leaf.center));
        shape->addChildShape(place, spheres_.back().get());
      }
      bunny_ = std::move(shape);
    }
    const btScalar friction = std::sqrt(bench.friction);
    const btScalar restitution = std::sqrt(bench.restitution);

    plane_ = std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0);
    btRigidBody::btRigidBodyConstructionInfo ground(0, nullptr, plane_.get());
    ground.m_friction = friction;
    ground.m_restitution = restitution;
    ground_ = std::make_unique<btRigidBody>(ground);
    world_.addRigidBody(ground_.get());

    for (const Transform& start : bench.start) {
      btTransform pose(to_bullet(start.rotation * axes.rotation), to_bullet(start.translation));
      btRigidBody::btRigidBodyConstructionInfo info(bench.mass, nullptr, bunny_.get(),
                                                    to_bullet(axes.moments));
      info.m_startWorldTransform = pose;
      info.m_friction = friction;
      info.m_restitution = restitution;
      bodies_.push_back(std::make_unique<btRigidBody>(info));
      world_.addRigidBody(bodies_.back().get());
    }
  }

  ~BulletEngine() override {
    for (auto& body : bodies_) world_.removeRigidBody(body.get());
    world_.removeRigidBody(ground_.get());
  }

  void step() override { world_.stepSimulation(dt_, 0, dt_); }

  void read(std::vector<BodyState>& out) const override {
    out.clear();
    const Quat body_to_principal = principal_to_body_.conjugate();
    for (const auto& body : bodies_) {
      const btTransform& pose = body->getCenterOfMassTransform();
      BodyState state;
      state.pose.rotation = (from_bullet(pose.getRotation()) * body_to_principal).normalized();
      state.pose.translation = from_bullet(pose.getOrigin());
      state.linear_velocity = from_bullet(body->getLinearVelocity());
      state.angular_velocity = from_bullet(body->getAngularVelocity());
      out.push_back(state);
    }
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
  btScalar dt_;
  Quat principal_to_body_;
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broad_phase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_;
  std::vector<std::unique_ptr<btSphereShape>> spheres_;
  std::unique_ptr<btCollisionShape> bunny_;
  std::unique_ptr<btCollisionShape> plane_;
  std::unique_ptr<btRigidBody> ground_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
};

}  // namespace

std::unique_ptr<Engine> make_bullet_engine(const BenchScene& scene, bool hull) {
  return std::make_unique<BulletEngine>(scene, hull);
}

}  // namespace sphys::compare
