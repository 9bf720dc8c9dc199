#pragma once

// From a scene description to a World ready to step: meshes loaded and normalised, mass
// properties computed, sphere-trees built (or read, or taken from the cache) once per shape.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sphys/tools/scene.h"
#include "sphys/tools/triangle_mesh.h"
#include "sphys/world.h"

namespace sphys::tools {

// What build_world may change of a scene, and how it works.
struct BuildWorldOptions {
  // Replaces every body's sphere-tree depth (built trees are built to it, trees read from .sph
  // files are truncated to it). unit: levels including the root
  std::optional<int> tree_depth;
  // Where built sphere-trees are cached; unset builds every time.
  std::optional<std::filesystem::path> cache_dir;
  // Called with the fraction of the shapes prepared (0..1), for progress bars.
  std::function<void(double)> progress;
  // The world's threads (WorldSettings::threads): 0 takes every hardware thread.
  std::uint32_t threads = 1;
  // StepStats' plausibility figures each step (WorldSettings::plausibility_figures).
  bool plausibility_figures = false;
  // The world's broad phase (WorldSettings::broad_phase); unset: the mode's.
  std::optional<BroadPhaseKind> broad_phase = std::nullopt;
};

// A shape shared by bodies with the same mesh, size and tree.
struct BodyShape {
  std::string mesh;  // as the scene names it
  // The mesh in the body frame (metres, centre of mass at the origin), for drawing and export.
  std::shared_ptr<const TriangleMesh> body_mesh;
  double volume = 0.0;                     // unit: m³
  std::shared_ptr<const SphereTree> tree;  // in the body frame, shared by the shape's bodies
  std::string tree_source;                 // e.g. "combined, branching 8, depth 3" or the .sph file
  // Largest distance of a vertex from the centre of mass. unit: m
  double max_vertex_distance = 0.0;
};

// A scene made into a world, with what the tools need to draw and report on its bodies.
struct SimulationSetup {
  std::unique_ptr<World> world;           // the scene's world, its bodies added, not yet stepped
  std::vector<BodyId> bodies;             // the scene's bodies, in order
  std::vector<std::uint32_t> body_shape;  // index into shapes, per scene body
  std::vector<BodyShape> shapes;          // each distinct shape once
  std::optional<BodyId> ground;           // the octree ground's static body, if any
  std::shared_ptr<const SphereTree> ground_tree;  // its sphere-tree
};

// Throws sphys::Error naming the body (its JSON path in the scene, e.g. "/bodies/3") for a mesh
// or tree that cannot be loaded or built, and for impossible values.
[[nodiscard]] SimulationSetup build_world(const Scene& scene,
                                          const BuildWorldOptions& options = {});

}  // namespace sphys::tools
