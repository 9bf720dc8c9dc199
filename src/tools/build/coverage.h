#pragma once

#include <vector>

#include "ball.h"
#include "sphys/sphere_tree.h"

namespace sphys::tools::build {

// Grows balls, as little as it can, until every point of every triangle of the mesh lies inside
// at least one ball: a certificate for the whole surface, not only for sample points. Each
// triangle is split recursively until each piece lies inside a single ball (a triangle is in a
// ball exactly when its three corners are, the ball being convex); a piece that stays uncovered
// once it is smaller than `resolution` makes the ball that needs the least growth grow to hold
// it. Returns how many balls grew. Requires at least one ball.
std::size_t ensure_coverage(std::vector<Ball>& balls, const TriangleMesh& mesh, double resolution);

// Pieces of the surface smaller than this (relative to the bounding-box diagonal) make a ball
// grow in the coverage pass instead of being split further.
constexpr double kCoverageResolution = 1e-4;

// The builders' last step: ensure_coverage at kCoverageResolution of the mesh's diagonal, then
// float spheres that still contain the double balls despite rounding the centres and radii.
[[nodiscard]] std::vector<Sphere> certified_spheres(std::vector<Ball> balls,
                                                    const TriangleMesh& mesh);

}  // namespace sphys::tools::build
