#include "sphys/tools/model.h"

#include <cstdlib>

#include "sphys/error.h"
#include "sphys/tools/decimate.h"
#include "sphys/tools/load_mesh.h"

namespace sphys::tools {

std::filesystem::path bunny_path() {
  if (const char* overridden = std::getenv("SPHYS_BUNNY"); overridden && *overridden) {
    return overridden;
  }
  return "/usr/share/glmark2/models/bunny.obj";
}

TriangleMesh load_model(std::string_view spec, std::optional<std::size_t> triangles) {
  if (spec == kBunnyName) {
    const std::filesystem::path path = bunny_path();
    if (!std::filesystem::exists(path)) {
      throw Error::in_file(path,
                           "the default model 'bunny' is missing; install Debian's glmark2-data "
                           "(scripts/setup does) or set SPHYS_BUNNY to a copy of bunny.obj");
    }
    TriangleMesh mesh = load_mesh(path);
    const std::size_t target = triangles.value_or(kBunnyDefaultTriangles);
    if (target != 0) mesh = decimate(mesh, target);
    mesh.name = std::string(kBunnyName);
    return mesh;
  }
  TriangleMesh mesh = load_mesh(std::filesystem::path(spec));
  if (triangles && *triangles != 0) mesh = decimate(mesh, *triangles);
  return mesh;
}

}  // namespace sphys::tools
