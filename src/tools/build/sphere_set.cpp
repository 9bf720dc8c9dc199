#include "sphys/tools/sphere_set.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "coverage.h"
#include "error_measure.h"
#include "reducer.h"
#include "sphys/error.h"
#include "sphys/tools/mesh_query.h"
#include "surface_samples.h"

namespace sphys::tools {
namespace {

// A sphere of the set and the surface samples it answers for.
struct Leaf {
  build::Ball ball;
  std::vector<std::uint32_t> samples;
  double error = 0.0;  // Bradshaw's. unit: m
};

}  // namespace

struct SphereSetBuilder::Impl {
  Impl(const TriangleMesh& mesh_in, BuildMethod method, std::uint64_t seed)
      : mesh(mesh_in),
        query(mesh),
        measure(query),
        samples(build::sample_surface(mesh, build::kBuildSurfaceSamples)),
        context{mesh, query, samples, seed},
        reducer(build::make_reducer(method, context)) {}

  void add(build::Cover cover) {
    for (std::size_t i = 0; i < cover.balls.size(); ++i) {
      leaves.push_back(
          {cover.balls[i], std::move(cover.samples[i]), measure.error(cover.balls[i])});
    }
  }

  TriangleMesh mesh;
  MeshQuery query;
  build::ErrorMeasure measure;
  build::SurfaceSamples samples;
  build::BuildContext context;
  std::unique_ptr<build::Reducer> reducer;
  std::vector<Leaf> leaves;
};

SphereSetBuilder::SphereSetBuilder(const TriangleMesh& mesh, BuildMethod method,
                                   std::uint64_t seed) {
  if (mesh.triangles.empty()) throw Error::in_file(mesh.name, "the mesh has no triangles");
  impl_ = std::make_unique<Impl>(mesh, method, seed);
  std::vector<std::uint32_t> all(impl_->samples.points.size());
  std::iota(all.begin(), all.end(), 0U);
  impl_->add(impl_->reducer->cover(all, 1));
}

SphereSetBuilder::~SphereSetBuilder() = default;

std::size_t SphereSetBuilder::size() const { return impl_->leaves.size(); }

bool SphereSetBuilder::refine(int max_children) {
  if (max_children < 2 || max_children > 8) {
    throw Error("a sphere splits into 2..8 children, not " + std::to_string(max_children));
  }
  std::vector<Leaf>& leaves = impl_->leaves;
  auto worst = leaves.end();
  for (auto leaf = leaves.begin(); leaf != leaves.end(); ++leaf) {
    if (leaf->samples.size() > 1 && (worst == leaves.end() || leaf->error > worst->error)) {
      worst = leaf;
    }
  }
  if (worst == leaves.end()) return false;
  const std::vector<std::uint32_t> samples = std::move(worst->samples);
  leaves.erase(worst);
  impl_->add(impl_->reducer->cover(samples, max_children));
  return true;
}

std::vector<Sphere> SphereSetBuilder::spheres() const {
  std::vector<build::Ball> balls;
  balls.reserve(impl_->leaves.size());
  for (const Leaf& leaf : impl_->leaves) balls.push_back(leaf.ball);
  return build::certified_spheres(std::move(balls), impl_->mesh);
}

}  // namespace sphys::tools
