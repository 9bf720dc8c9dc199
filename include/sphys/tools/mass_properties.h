#pragma once

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// How the volume integrals were taken. See docs/mass-properties.md.
enum class MassMethod {
  // Exact surface integrals of a closed mesh via the divergence theorem (Eberly, "Polyhedral
  // Mass Properties (Revisited)", 2002, after Mirtich 1996). Used for watertight meshes: every
  // edge shared by exactly two triangles running it opposite ways.
  Polyhedral,
  // The solid is the region where the generalized winding number is >= 1/2, integrated along y
  // in columns on a square x–z grid: exact along each column, O(cell) error across the
  // silhouette (about 1e-4 relative at 160 columns), exact for boxes aligned with the grid.
  // Holes are closed by fans ("caps") that the region's boundary is taken to follow there: exact
  // for planar holes, good for small ones; a large hole can lose a few percent (the level set
  // bulges past the caps sideways). Cost grows with columns² and with the boundary edges.
  WindingNumber,
};

// How compute_mass_properties integrates.
struct MassPropertiesOptions {
  double density = 1000.0;  // unit: kg/m³ (mesh units taken as metres)
  // Polyhedral when the mesh is watertight, WindingNumber otherwise (holes, non-manifold or
  // misoriented edges); true uses WindingNumber always.
  bool force_winding_number = false;
  // Columns along the longer of the x and z sides for the WindingNumber method, 1 to 8192; the
  // cells are square. unit: count
  int columns = 160;
};

// Mass properties of a homogeneous solid, in the mesh's frame.
struct MassProperties {
  double volume = 0.0;                         // unit: m³
  double mass = 0.0;                           // unit: kg
  Vec3d center_of_mass = Vec3d::Zero();        // unit: m
  Mat3d inertia = Mat3d::Zero();               // about the centre of mass, mesh axes. unit: kg·m²
  Vec3d principal_moments = Vec3d::Zero();     // ascending. unit: kg·m²
  Mat3d principal_axes = Mat3d::Identity();    // columns, right-handed, matching principal_moments
  MassMethod method = MassMethod::Polyhedral;  // how the integrals were taken
};

// Throws sphys::Error, naming the mesh, when the density is not positive and finite, the column
// count is out of range, a vertex is not finite, a triangle refers to a missing vertex, or the
// mesh encloses no volume (no triangles, zero or negative volume: an inside-out mesh is reported,
// not flipped).
[[nodiscard]] MassProperties compute_mass_properties(const TriangleMesh& mesh,
                                                     const MassPropertiesOptions& options = {});

}  // namespace sphys::tools
