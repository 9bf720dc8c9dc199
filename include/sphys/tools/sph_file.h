#pragma once

#include <filesystem>
#include <iosfwd>
#include <vector>

#include "sphys/sphere_tree.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// How a .sph file's spheres are placed when read.
struct SphReadOptions {
  // Added to every centre after reading. Bradshaw's toolkit writes centres relative to the
  // input mesh's bounding-box centre; pass that centre (mesh.bounds().center()) here to get the
  // centres back in the mesh's own coordinates. unit: m
  Vec3d shift = Vec3d::Zero();
};

// Reads a sphere-tree in the format of Bradshaw's Sphere-Tree Construction Toolkit (see
// docs/file-formats.md) into a compact SphereTree: the used slots only, so unused slots between
// used children are closed up with the tree unchanged. Throws sphys::Error naming the file and
// line, also for a branching factor above 8 (a flat sphere set: read it with read_sph_spheres).
[[nodiscard]] SphereTree read_sph(const std::filesystem::path& path,
                                  const SphReadOptions& options = {});
// The same from a stream; `name` is used in messages.
[[nodiscard]] SphereTree read_sph(std::istream& in, const std::filesystem::path& name,
                                  const SphReadOptions& options = {});

// The used spheres of a .sph file in breadth-first order, each with its parent's index, for
// measuring rather than simulating: the branching factor may exceed the 8 of a SphereTree. The
// toolkit saves a flat set of N spheres as the header "2 N", a bounding sphere, then the N.
struct SphSpheres {
  int branching = 2;                  // the file's, which may exceed 8
  std::vector<SphereTreeNode> nodes;  // the used spheres, breadth-first, parents by index

  // The spheres of each level, the root's first.
  [[nodiscard]] std::vector<std::vector<Sphere>> levels() const;
};
// Reads a .sph file's used spheres; throws sphys::Error naming the file and line, as read_sph.
[[nodiscard]] SphSpheres read_sph_spheres(const std::filesystem::path& path,
                                          const SphReadOptions& options = {});
// The same from a stream; `name` is used in messages.
[[nodiscard]] SphSpheres read_sph_spheres(std::istream& in, const std::filesystem::path& name,
                                          const SphReadOptions& options = {});

// Writes the tree as a complete B-ary tree in breadth-first order, unused slots with a negative
// radius, centres as stored. The file is written whole or not at all (a temporary file renamed
// into place). Throws sphys::Error if the file cannot be written.
void write_sph(const std::filesystem::path& path, const SphereTree& tree);
// The same to a stream, as it goes. Throws sphys::Error for an empty tree or one too large for
// the format, as the file version does.
void write_sph(std::ostream& out, const SphereTree& tree);

}  // namespace sphys::tools
