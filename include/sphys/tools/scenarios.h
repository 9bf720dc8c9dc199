#pragma once

// Built-in scenes. "stacks:SxN" is the paper's experiment (§5) as the benchmark specification
// fixes it: S stacks of N bunnies, over the exact plane (the experiment itself keeps the paper's
// octree ground; see docs/experiment.md).

#include <cstdint>
#include <string>
#include <string_view>

#include "sphys/tools/scene.h"

namespace sphys::tools {

// The SplitMix64 generator (Steele, Lea & Flood 2014) that draws the bunnies' yaw angles: a
// fixed, documented sequence, so every engine can rebuild the same layout.
class SplitMix64 {
 public:
  // The sequence that starts from `seed`.
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  // The next 64 random bits of the sequence.
  std::uint64_t next();
  // Uniform in [0, 1) with 53 random bits.
  double next_unit();

 private:
  std::uint64_t state_;
};

// Seed of the stacks' yaw angles.
inline constexpr std::uint64_t kStacksSeed = 2008;

// S stacks of N bunnies with sphere-trees of the given depth (Combined, branching 8) over the
// 5-level octree ground, with the runtime's default response (plausible; run_experiment_row sets
// the paper's). `seed` draws the bunnies' yaw angles: another seed, another pile of the same
// layout (sweeps over seeds). Throws sphys::Error when a count or the depth is out of range.
[[nodiscard]] Scene bunny_stacks_scene(int stacks, int per_stack, int tree_depth,
                                       std::uint64_t seed = kStacksSeed);

// True when `text` names a preset ("stacks:..."), whether or not it is well formed.
[[nodiscard]] bool is_preset(std::string_view text);
// The scene of a preset, e.g. "stacks:4x50" (tree depth 3 unless the caller changes it, the exact
// plane y = 0 as its ground), its yaw angles drawn from `seed`. Throws sphys::Error naming the
// preset and listing the valid forms.
[[nodiscard]] Scene preset_scene(std::string_view text, std::uint64_t seed = kStacksSeed);
// A preset name, else a scene file.
[[nodiscard]] Scene load_scene(std::string_view preset_or_file);

// One line per preset form, for --help.
[[nodiscard]] std::string preset_help();

}  // namespace sphys::tools
