#include "sphys/tools/decimate.h"

#include <limits>
#include <string>

#include <meshoptimizer.h>

#include "sphys/error.h"
#include "sphys/tools/check_mesh.h"

namespace sphys::tools {
namespace {

// Keeps the vertices the simplified triangles use, in first-use order.
TriangleMesh compact(const TriangleMesh& source, const std::vector<std::uint32_t>& indices) {
  constexpr auto kUnset = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> remap(source.vertices.size(), kUnset);
  TriangleMesh out;
  out.name = source.name;
  out.triangles.reserve(indices.size() / 3);
  for (std::size_t i = 0; i < indices.size(); i += 3) {
    Triangle t{};
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint32_t& slot = remap[indices[i + k]];
      if (slot == kUnset) {
        slot = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(source.vertices[indices[i + k]]);
      }
      t[k] = slot;
    }
    out.triangles.push_back(t);
  }
  return out;
}

}  // namespace

TriangleMesh decimate(const TriangleMesh& mesh, std::size_t target_triangles) {
  // A tetrahedron is the smallest closed surface: fewer triangles enclose nothing.
  constexpr std::size_t kFewestClosed = 4;
  if (target_triangles < kFewestClosed) {
    throw Error::in_file(mesh.name, "cannot decimate to " + std::to_string(target_triangles) +
                                        " triangles: a closed surface needs at least 4");
  }
  if (target_triangles >= mesh.triangles.size()) return mesh;

  std::vector<float> positions;
  positions.reserve(mesh.vertices.size() * 3);
  for (const Vec3d& v : mesh.vertices) {
    for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(v[k]));
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const Triangle& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());

  // The error bound is relative to the mesh's extent: 1 means "reach the count whatever it
  // costs"; the triangle count is the user's real request. Locking the border keeps open meshes'
  // holes from growing and leaves closed meshes unaffected.
  constexpr float kUnboundedError = 1.0f;
  std::vector<std::uint32_t> simplified(indices.size());
  const std::size_t index_count =
      meshopt_simplify(simplified.data(), indices.data(), indices.size(), positions.data(),
                       mesh.vertices.size(), 3 * sizeof(float), target_triangles * 3,
                       kUnboundedError, meshopt_SimplifyLockBorder, nullptr);
  simplified.resize(index_count);
  if (index_count == 0) throw Error::in_file(mesh.name, "decimation removed every triangle");

  TriangleMesh out = compact(mesh, simplified);
  if (check_mesh(mesh).watertight() && !check_mesh(out).watertight()) {
    throw Error::in_file(mesh.name, "decimating to " + std::to_string(target_triangles) +
                                        " triangles would break the closed surface; ask for "
                                        "more triangles");
  }
  return out;
}

}  // namespace sphys::tools
