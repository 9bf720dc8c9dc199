#pragma once

#include <vector>

#include "ball.h"

namespace sphys::tools::build {

// Grows balls, as little as it can, until every point of every triangle of the mesh lies inside
// at least one ball: a certificate for the whole surface, not only for sample points. Each
// triangle is split recursively until each piece lies inside a single ball (a triangle is in a
// ball exactly when its three corners are, the ball being convex); a piece that stays uncovered
// once it is smaller than `resolution` makes the ball that needs the least growth grow to hold
// it. Returns how many balls grew. Requires at least one ball.
std::size_t ensure_coverage(std::vector<Ball>& balls, const TriangleMesh& mesh, double resolution);

}  // namespace sphys::tools::build
