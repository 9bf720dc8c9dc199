#include "engine.h"

#include <charconv>

#include "sphys/error.h"

namespace sphys::compare {
namespace {

// "sphys:T" runs sphys on T threads (0: every hardware thread); plain "sphys" on one.
std::uint32_t sphys_threads(const std::string& name, std::size_t prefix) {
  if (name.size() == prefix) return 1;
  std::uint32_t threads = 0;
  const char* begin = name.data() + prefix + 1;
  const char* end = name.data() + name.size();
  const auto [rest, error] = std::from_chars(begin, end, threads);
  if (name[prefix] != ':' || error != std::errc{} || rest != end || threads > 1024) {
    throw Error("engine '" + name + "': threads after the colon must be a number up to 1024");
  }
  return threads;
}

bool has_prefix(const std::string& name, const std::string& prefix) {
  return name.starts_with(prefix) && (name.size() == prefix.size() || name[prefix.size()] == ':');
}

}  // namespace

std::vector<std::string> engine_names() {
  return {"sphys", "sphys-paper", "sphys-sap", "bullet-spheres", "bullet-hull", "ode", "mujoco"};
}

std::unique_ptr<Engine> make_engine(const std::string& name, const BenchScene& scene) {
  if (scene.robot && !(has_prefix(name, "sphys") || name == "mujoco")) {
    throw Error("engine '" + name + "' has no robot for the scene's (sphys and mujoco have)");
  }
  if (has_prefix(name, "sphys")) return make_sphys_engine(scene, false, sphys_threads(name, 5));
  if (has_prefix(name, "sphys-paper")) {
    return make_sphys_engine(scene, true, sphys_threads(name, 11));
  }
  // Plausible mode with the paper's one Sweep & Prune instead of the cells: the same run, for
  // timing the broad phases against each other.
  if (has_prefix(name, "sphys-sap")) {
    return make_sphys_engine(scene, false, sphys_threads(name, 9), BroadPhaseKind::kSweepAndPrune);
  }
  if (name == "bullet-spheres") return make_bullet_engine(scene, false);
  if (name == "bullet-hull") return make_bullet_engine(scene, true);
  if (name == "ode") return make_ode_engine(scene);
  if (name == "mujoco") return make_mujoco_engine(scene);
  std::string known;
  for (const std::string& engine : engine_names()) known += (known.empty() ? "" : ", ") + engine;
  throw Error("unknown engine '" + name + "'; the engines: " + known);
}

}  // namespace sphys::compare
