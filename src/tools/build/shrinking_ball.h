#pragma once

#include <optional>

#include "error_measure.h"
#include "medial_axis.h"

namespace sphys::tools::build {

// The medial sphere that touches the surface at `point` from the inside (the shrinking-ball
// method of Ma, Bae & Choi, "3D medial axis point approximation using nearest neighbors and the
// normal field", The Visual Computer 28(1), 2012): the largest ball tangent to the surface there,
// its centre on the inward normal, that holds no part of the surface. It needs no sampling
// density, so it finds the medial spheres of parts thinner than the spacing of the surface
// samples (a 2 mm plate sampled every centimetre), where no Voronoi vertex of the samples lies
// inside the object. Balls tangent at one point along one normal are nested, so whether one is
// empty is monotone in its radius and a bisection finds the largest. `max_radius` caps the
// search (unit: m). Nothing when no ball of positive radius is empty (a point on a sharp edge)
// or the centre is not inside the object (an open sheet). `generators` are all `point_index`.
[[nodiscard]] std::optional<MedialSphere> shrinking_ball(const Vec3d& point,
                                                         const Vec3d& outward_normal,
                                                         std::uint32_t point_index,
                                                         double max_radius,
                                                         const ErrorMeasure& measure);

}  // namespace sphys::tools::build
