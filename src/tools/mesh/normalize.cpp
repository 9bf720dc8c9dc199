#include "sphys/tools/normalize.h"

#include <cmath>
#include <sstream>
#include <string>

#include "sphys/error.h"

namespace sphys::tools {

NormalizedMesh normalize(const TriangleMesh& mesh, double target_size,
                         const MassPropertiesOptions& options) {
  if (!std::isfinite(target_size) || target_size <= 0.0) {
    std::ostringstream problem;
    problem << "target size must be positive and finite, got " << target_size;
    throw Error::in_file(mesh.name, problem.str());
  }
  // An empty mesh has an empty box, whose sizes are negative.
  const double longest = mesh.bounds().sizes().maxCoeff();
  if (!std::isfinite(longest) || longest <= 0.0) {
    throw Error::in_file(mesh.name, "has a flat bounding box, so it cannot be scaled");
  }

  NormalizedMesh result;
  result.scale = target_size / longest;
  result.mesh = mesh;
  for (Vec3d& v : result.mesh.vertices) v *= result.scale;
  // The centre of mass of the scaled mesh, so that the method's grid is the final one.
  result.translation = -compute_mass_properties(result.mesh, options).center_of_mass;
  for (Vec3d& v : result.mesh.vertices) v += result.translation;
  return result;
}

}  // namespace sphys::tools
