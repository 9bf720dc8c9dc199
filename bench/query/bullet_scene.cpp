#include <btBulletCollisionCommon.h>
#include <memory>
#include <vector>

#include "other_engines.h"

namespace sphys::query_bench {
namespace {

btVector3 to_bullet(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Stops listening after the first contact (Bullet still visits the rest of the pairs).
struct AnyContact final : btCollisionWorld::ContactResultCallback {
  bool found = false;
  btScalar addSingleResult(btManifoldPoint& /*point*/, const btCollisionObjectWrapper* /*a*/,
                           int /*part_a*/, int /*index_a*/, const btCollisionObjectWrapper* /*b*/,
                           int /*part_b*/, int /*index_b*/) override {
    found = true;
    return 0;
  }
  [[nodiscard]] bool needsCollision(btBroadphaseProxy* proxy) const override {
    return !found && btCollisionWorld::ContactResultCallback::needsCollision(proxy);
  }
};

}  // namespace

struct BulletScene::Impl {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broad_phase;
  btCollisionWorld world{&dispatcher, &broad_phase, &configuration};
  std::vector<std::unique_ptr<btSphereShape>> spheres;
  std::unique_ptr<btCompoundShape> bunny;
  std::vector<std::unique_ptr<btCollisionObject>> bodies;
  std::unique_ptr<btCompoundShape> robot_shape;
  std::unique_ptr<btCollisionObject> robot;  // not in the world: contactTest asks about it
};

BulletScene::BulletScene(const std::vector<Sphere>& leaves, std::span<const Transform> poses,
                         std::span<const float> robot_radii)
    : impl_(std::make_unique<Impl>()) {
  // The compound's own dynamic AABB tree over its children, as sphys-compare's bullet-spheres.
  impl_->bunny = std::make_unique<btCompoundShape>(true, static_cast<int>(leaves.size()));
  for (const Sphere& leaf : leaves) {
    impl_->spheres.push_back(std::make_unique<btSphereShape>(leaf.radius));
    btTransform place;
    place.setIdentity();
    place.setOrigin(to_bullet(leaf.center));
    impl_->bunny->addChildShape(place, impl_->spheres.back().get());
  }
  for (std::size_t i = 0; i < poses.size(); ++i) {
    auto body = std::make_unique<btCollisionObject>();
    body->setCollisionShape(impl_->bunny.get());
    const Quat& q = poses[i].rotation;
    body->setWorldTransform(
        btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), to_bullet(poses[i].translation)));
    body->setUserIndex(static_cast<int>(i));
    impl_->world.addCollisionObject(body.get());
    impl_->bodies.push_back(std::move(body));
  }
  impl_->world.updateAabbs();
  impl_->robot_shape =
      std::make_unique<btCompoundShape>(true, static_cast<int>(robot_radii.size()));
  for (const float radius : robot_radii) {
    impl_->spheres.push_back(std::make_unique<btSphereShape>(radius));
    btTransform place;
    place.setIdentity();
    impl_->robot_shape->addChildShape(place, impl_->spheres.back().get());
  }
  impl_->robot = std::make_unique<btCollisionObject>();
  impl_->robot->setCollisionShape(impl_->robot_shape.get());
}

BulletScene::~BulletScene() {
  for (auto& body : impl_->bodies) impl_->world.removeCollisionObject(body.get());
}

BulletScene::Hit BulletScene::cast(const Vec3& origin, const Vec3& direction, float length) const {
  const btVector3 from = to_bullet(origin);
  const btVector3 to = to_bullet(origin + length * direction);
  btCollisionWorld::ClosestRayResultCallback nearest(from, to);
  impl_->world.rayTest(from, to, nearest);
  if (!nearest.hasHit()) return {};
  return {nearest.m_collisionObject->getUserIndex(), nearest.m_closestHitFraction * length};
}

bool BulletScene::touches(std::span<const float> spheres) const {
  btCompoundShape& robot = *impl_->robot_shape;
  for (int i = 0; i < robot.getNumChildShapes(); ++i) {
    btTransform place;
    place.setIdentity();
    const float* s = spheres.data() + 4 * static_cast<std::size_t>(i);
    place.setOrigin(btVector3(s[0], s[1], s[2]));
    robot.updateChildTransform(i, place, false);
  }
  robot.recalculateLocalAabb();
  AnyContact contact;
  impl_->world.contactTest(impl_->robot.get(), contact);
  return contact.found;
}

}  // namespace sphys::query_bench
