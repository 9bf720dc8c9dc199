// Hello, world: ten bunnies dropped on the ground plane, 300 steps of 1/60 s, the poses printed.
// Built against an installed sphys: find_package(sphys COMPONENTS tools), sphys::tools.
#include <cstdio>
#include <memory>
#include <sphys/tools/build_tree.h>
#include <sphys/tools/mass_properties.h>
#include <sphys/tools/model.h>
#include <sphys/tools/normalize.h>
#include <sphys/world.h>

int main() {
  namespace tools = sphys::tools;
  // The Stanford bunny, 0.2 m long, its centre of mass at the origin, of water's density.
  const tools::TriangleMesh bunny = tools::normalize(tools::load_model("bunny"), 0.2).mesh;
  const tools::MassProperties mass = tools::compute_mass_properties(bunny);  // 1000 kg/m³
  tools::BuildOptions two_levels;
  two_levels.depth = 2;
  const auto tree =
      std::make_shared<const sphys::SphereTree>(tools::build_sphere_tree(bunny, two_levels));
  sphys::WorldSettings settings;
  settings.collision.ground_plane_height = 0.0f;  // the exact plane y = 0, unit: m
  sphys::World world(settings);
  for (int i = 0; i < 10; ++i) {
    sphys::BodyDesc body;
    body.tree = tree;
    body.mass = static_cast<float>(mass.mass);  // unit: kg
    const auto k = static_cast<float>(i);       // a column, each bunny 0.25 m above the last
    body.pose.translation = sphys::Vec3(i % 2 == 0 ? 0.0f : 0.05f, 0.3f + 0.25f * k, 0.0f);
    body.inertia = mass.inertia.cast<float>();
    world.add_body(body);
  }
  for (int step = 0; step < 300; ++step) world.step(1.0f / 60.0f);  // unit: s
  for (const sphys::Transform& pose : world.bodies().poses()) {
    const sphys::Vec3& p = pose.translation;
    const sphys::Quat& q = pose.rotation;
    std::printf("position %7.3f %7.3f %7.3f m, rotation (x y z w) %6.3f %6.3f %6.3f %6.3f\n", p.x(),
                p.y(), p.z(), q.x(), q.y(), q.z(), q.w());
  }
}
