#include "sphys/tools/ground.h"

#include <cmath>

#include "sphys/error.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/primitives.h"

namespace sphys::tools {

TriangleMesh make_ground_box(const GroundOptions& options) {
  if (!(options.size > 0.0) || !std::isfinite(options.size) || !(options.thickness > 0.0) ||
      !std::isfinite(options.thickness)) {
    throw Error("the ground needs a positive, finite size and thickness");
  }
  TriangleMesh box = make_box({options.size, options.thickness, options.size});
  for (Vec3d& v : box.vertices) v.y() -= 0.5 * options.thickness;
  box.name = "ground";
  return box;
}

SphereTree build_ground_tree(const GroundOptions& options) {
  BuildOptions build;
  build.method = BuildMethod::Octree;
  build.branching = 8;
  build.depth = options.depth;
  return build_sphere_tree(make_ground_box(options), build);
}

}  // namespace sphys::tools
