#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "ball.h"
#include "error_measure.h"

namespace sphys::tools::build {

// One sphere of the medial-axis approximation: a Voronoi vertex of the surface points that lies
// inside the object, with the radius that reaches its four generating points (the circumsphere
// of a Delaunay tetrahedron, empty of points).
struct MedialSphere {
  Ball ball;
  // Radius minus the centre's distance to the surface: how far the sphere pokes out of the
  // object (Bradshaw & O'Sullivan 2004, §3.2). unit: m
  double error = 0.0;
  // The tetrahedron's corners, as indices into MedialAxis::points.
  std::array<std::uint32_t, 4> generators{};
};

struct MedialAxisOptions {
  // Adaptive refinement (Bradshaw §3.3): at most this many surface points are added...
  int max_added_points = 0;
  // ...and none once every sphere's error is at most this. unit: m
  double tolerance = 0.0;
};

// The medial-axis approximation of the part of an object's surface that `points[0, focus)`
// sample. The remaining points sample the rest of the surface coarsely, so that Voronoi vertices
// near the edge of the region are true medial vertices rather than artefacts of a cut-off point
// set. Only spheres that touch a focus point are kept.
struct MedialAxis {
  std::vector<Vec3d> points;  // the input points, then the points refinement added
  std::vector<MedialSphere> spheres;
  // Per focus point (the first `focus` points), the spheres it lies on (indices into `spheres`).
  std::vector<std::vector<std::uint32_t>> point_spheres;
};

// Voronoi vertices via the dual Delaunay tetrahedralisation (CGAL); signed distances (inside or
// not, and how deep) from `measure`. Deterministic: points are inserted in a fixed spatial order.
[[nodiscard]] MedialAxis approximate_medial_axis(std::span<const Vec3d> points, std::size_t focus,
                                                 const ErrorMeasure& measure,
                                                 const MedialAxisOptions& options);

}  // namespace sphys::tools::build
