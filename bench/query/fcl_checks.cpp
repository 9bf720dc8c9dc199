#include <fcl/fcl.h>
#include <memory>
#include <vector>

#include "other_engines.h"

namespace sphys::query_bench {
namespace {

using Model = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<Model> model_of(const tools::TriangleMesh& mesh) {
  auto model = std::make_shared<Model>();
  std::vector<fcl::Vector3d> vertices(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  for (const tools::Triangle& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel();
  model->addSubModel(vertices, triangles);
  model->endModel();
  return model;
}

fcl::Transform3d to_fcl(const Transform& pose) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  out.linear() = pose.rotation.cast<double>().toRotationMatrix();
  out.translation() = pose.translation.cast<double>();
  return out;
}

}  // namespace

struct FclScene::Impl {
  std::shared_ptr<Model> bunny;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> bunnies;
  fcl::DynamicAABBTreeCollisionManagerd manager;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> links;
};

FclScene::FclScene(const tools::TriangleMesh& bunny, std::span<const Transform> poses,
                   const std::vector<tools::TriangleMesh>& link_meshes)
    : impl_(std::make_unique<Impl>()) {
  impl_->bunny = model_of(bunny);
  std::vector<fcl::CollisionObjectd*> objects;
  for (const Transform& pose : poses) {
    impl_->bunnies.push_back(std::make_unique<fcl::CollisionObjectd>(impl_->bunny, to_fcl(pose)));
    objects.push_back(impl_->bunnies.back().get());
  }
  impl_->manager.registerObjects(objects);
  impl_->manager.setup();
  for (const tools::TriangleMesh& mesh : link_meshes) {
    impl_->links.push_back(std::make_unique<fcl::CollisionObjectd>(model_of(mesh)));
  }
}

FclScene::~FclScene() = default;

bool FclScene::collides(std::span<const Transform> link_poses) const {
  for (std::size_t l = 0; l < impl_->links.size(); ++l) {
    fcl::CollisionObjectd& link = *impl_->links[l];
    link.setTransform(to_fcl(link_poses[l]));
    link.computeAABB();
    fcl::DefaultCollisionData<double> data;
    impl_->manager.collide(&link, &data, fcl::DefaultCollisionFunction);
    if (data.result.isCollision()) return true;
  }
  return false;
}

}  // namespace sphys::query_bench
