#include "engine.h"

#include "sphys/error.h"

namespace sphys::compare {

std::vector<std::string> engine_names() {
  return {"sphys", "sphys-paper", "bullet-spheres", "bullet-hull", "ode", "mujoco"};
}

std::unique_ptr<Engine> make_engine(const std::string& name, const BenchScene& scene) {
  if (name == "sphys") return make_sphys_engine(scene, false);
  if (name == "sphys-paper") return make_sphys_engine(scene, true);
  if (name == "bullet-spheres") return make_bullet_engine(scene, false);
  if (name == "bullet-hull") return make_bullet_engine(scene, true);
  if (name == "ode") return make_ode_engine(scene);
  if (name == "mujoco") return make_mujoco_engine(scene);
  std::string known;
  for (const std::string& engine : engine_names()) known += (known.empty() ? "" : ", ") + engine;
  throw Error("unknown engine '" + name + "'; the engines: " + known);
}

}  // namespace sphys::compare
