#include <charconv>
#include <cmath>
#include <numbers>
#include <string>

#include "sphys/error.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/scene_file.h"

namespace sphys::tools {
namespace {

constexpr std::string_view kStacksPrefix = "stacks:";
constexpr double kStackSpacing = 1.5;  // between neighbouring stacks' axes. unit: m
constexpr double kFirstHeight = 1.0;   // centre of mass of the lowest bunny. unit: m
constexpr double kLevelSpacing = 1.2;  // between bunnies of a stack. unit: m
constexpr int kPresetTreeDepth = 3;

// Parses a whole positive integer, or returns 0.
int parse_count(std::string_view text) {
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value <= 0) return 0;
  return value;
}

}  // namespace

std::uint64_t SplitMix64::next() {
  state_ += 0x9E3779B97F4A7C15ull;
  std::uint64_t z = state_;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double SplitMix64::next_unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

Scene bunny_stacks_scene(int stacks, int per_stack, int tree_depth, std::uint64_t seed) {
  if (stacks <= 0 || per_stack <= 0 ||
      static_cast<long long>(stacks) * per_stack > static_cast<long long>(kMaxSceneBodies)) {
    throw Error("stacks: need at least 1 stack of at least 1 bunny and at most " +
                std::to_string(kMaxSceneBodies) + " bunnies, got " + std::to_string(stacks) + "x" +
                std::to_string(per_stack));
  }
  if (tree_depth < 1 || tree_depth > 6) {
    throw Error("stacks: the sphere-tree depth must be 1 to 6, got " + std::to_string(tree_depth));
  }
  Scene scene;
  scene.name = "stacks:" + std::to_string(stacks) + "x" + std::to_string(per_stack);
  scene.ground.kind = GroundSpec::Kind::kOctreeBox;

  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(stacks))));
  const int rows = (stacks + cols - 1) / cols;
  SplitMix64 random(seed);
  scene.bodies.reserve(static_cast<std::size_t>(stacks) * static_cast<std::size_t>(per_stack));
  for (int s = 0; s < stacks; ++s) {
    const double x = (s % cols - (cols - 1) / 2.0) * kStackSpacing;
    const double z = (s / cols - (rows - 1) / 2.0) * kStackSpacing;
    for (int i = 0; i < per_stack; ++i) {
      BodySpec body;
      body.mesh = "bunny";
      body.size = 1.0;
      body.tree.method = BuildMethod::Combined;
      body.tree.branching = 8;
      body.tree.depth = tree_depth;
      body.position =
          Vec3(static_cast<float>(x), static_cast<float>(kFirstHeight + kLevelSpacing * i),
               static_cast<float>(z));
      const double angle = 2.0 * std::numbers::pi * random.next_unit();
      body.orientation = Quat(static_cast<float>(std::cos(angle / 2.0)), 0.0f,
                              static_cast<float>(std::sin(angle / 2.0)), 0.0f);
      scene.bodies.push_back(body);
    }
  }
  return scene;
}

bool is_preset(std::string_view text) { return text.starts_with(kStacksPrefix); }

Scene preset_scene(std::string_view text, std::uint64_t seed) {
  if (is_preset(text)) {
    const std::string_view layout = text.substr(kStacksPrefix.size());
    const std::size_t x = layout.find('x');
    if (x != std::string_view::npos) {
      const int stacks = parse_count(layout.substr(0, x));
      const int per_stack = parse_count(layout.substr(x + 1));
      if (stacks > 0 && per_stack > 0) {
        Scene scene = bunny_stacks_scene(stacks, per_stack, kPresetTreeDepth, seed);
        // The exact plane, not the experiment's 16 m octree: in paper mode bunnies slid off every
        // size of octree ground tried (docs/experiment.md, "The ground"), and nothing may fall
        // off the world in a preset. `--ground octree` gives the paper's ground back.
        scene.ground.kind = GroundSpec::Kind::kPlane;
        return scene;
      }
    }
  }
  throw Error("unknown preset '" + std::string(text) +
              "'; expected stacks:SxN with whole numbers S, N >= 1 (e.g. stacks:4x50)");
}

Scene load_scene(std::string_view preset_or_file) {
  if (is_preset(preset_or_file)) return preset_scene(preset_or_file);
  return read_scene_file(std::filesystem::path(preset_or_file));
}

std::string preset_help() {
  return "  stacks:SxN  S stacks of N Stanford bunnies falling onto the exact plane y = 0 "
         "(e.g. stacks:4x50; --ground octree for the paper's)";
}

}  // namespace sphys::tools
