#include <btBulletCollisionCommon.h>
#include <memory>
#include <vector>

#include "other_engines.h"

namespace sphys::query_bench {
namespace {

btVector3 to_bullet(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

struct BulletRays::Impl {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broad_phase;
  btCollisionWorld world{&dispatcher, &broad_phase, &configuration};
  std::vector<std::unique_ptr<btSphereShape>> spheres;
  std::unique_ptr<btCompoundShape> bunny;
  std::vector<std::unique_ptr<btCollisionObject>> bodies;
};

BulletRays::BulletRays(const std::vector<Sphere>& leaves, std::span<const Transform> poses)
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
}

BulletRays::~BulletRays() {
  for (auto& body : impl_->bodies) impl_->world.removeCollisionObject(body.get());
}

BulletRays::Hit BulletRays::cast(const Vec3& origin, const Vec3& direction, float length) const {
  const btVector3 from = to_bullet(origin);
  const btVector3 to = to_bullet(origin + length * direction);
  btCollisionWorld::ClosestRayResultCallback nearest(from, to);
  impl_->world.rayTest(from, to, nearest);
  if (!nearest.hasHit()) return {};
  return {nearest.m_collisionObject->getUserIndex(), nearest.m_closestHitFraction * length};
}

}  // namespace sphys::query_bench
