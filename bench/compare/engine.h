#pragma once

// One physics engine running the benchmark scene, behind the interface the comparison times.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bench_scene.h"

namespace sphys::compare {

struct BodyState {
  Transform pose;  // of the body frame of BenchScene (centre of mass, mesh axes)
  Vec3 linear_velocity = Vec3::Zero();   // unit: m/s
  Vec3 angular_velocity = Vec3::Zero();  // world frame. unit: rad/s
};

class Engine {
 public:
  virtual ~Engine() = default;
  // One step of BenchScene::time_step: the call the comparison times.
  virtual void step() = 0;
  // The bodies now, in the scene's order.
  virtual void read(std::vector<BodyState>& out) const = 0;
  // The last step's contacts as the engine counts them, and the deepest penetration among them
  // (the engine's own measure: its contact depths). unit: m
  [[nodiscard]] virtual std::uint32_t contacts() const = 0;
  [[nodiscard]] virtual float deepest_penetration() const = 0;
  // What went wrong so far that makes the run suspect (e.g. contacts dropped); empty if nothing.
  [[nodiscard]] virtual std::string warnings() const { return {}; }
};

// The engines by name: "sphys", "sphys-paper", "bullet-spheres", "bullet-hull", "ode",
// "mujoco"; "sphys:T" and "sphys-paper:T" step sphys on T threads (0: all). Throws sphys::Error
// for an unknown name.
[[nodiscard]] std::unique_ptr<Engine> make_engine(const std::string& name, const BenchScene& scene);
[[nodiscard]] std::vector<std::string> engine_names();

// Each engine's maker, in its own file.
[[nodiscard]] std::unique_ptr<Engine> make_sphys_engine(const BenchScene& scene, bool paper,
                                                        std::uint32_t threads);
[[nodiscard]] std::unique_ptr<Engine> make_bullet_engine(const BenchScene& scene, bool hull);
[[nodiscard]] std::unique_ptr<Engine> make_ode_engine(const BenchScene& scene);
[[nodiscard]] std::unique_ptr<Engine> make_mujoco_engine(const BenchScene& scene);

}  // namespace sphys::compare
