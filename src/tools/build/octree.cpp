#include "octree.h"

#include <array>

namespace sphys::tools::build {
namespace {

using Polygon = std::vector<Vec3d>;

// Sutherland-Hodgman: the part of a convex polygon on the side coordinate[axis] >= bound
// (sign +1) or <= bound (sign -1).
Polygon clip(const Polygon& in, int axis, double bound, double sign) {
  Polygon out;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Vec3d& a = in[i];
    const Vec3d& b = in[(i + 1) % in.size()];
    const double da = sign * (a[axis] - bound);
    const double db = sign * (b[axis] - bound);
    if (da >= 0) out.push_back(a);
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

Polygon clip_to_box(Polygon polygon, const Box3d& box) {
  for (int axis = 0; axis < 3 && !polygon.empty(); ++axis) {
    polygon = clip(polygon, axis, box.min()[axis], +1.0);
    if (!polygon.empty()) polygon = clip(polygon, axis, box.max()[axis], -1.0);
  }
  return polygon;
}

struct Cell {
  Box3d box;
  std::vector<std::uint32_t> triangles;  // those meeting the cell
};

Box3d octant(const Box3d& box, int k) {
  const Vec3d half = 0.5 * box.sizes();
  Vec3d lo = box.min();
  for (int axis = 0; axis < 3; ++axis) {
    if ((k >> axis) & 1) lo[axis] += half[axis];
  }
  return {lo, lo + half};
}

// The child cell for octant k, with the ball around the solid's part of it; false when the
// octant holds no solid.
bool make_child(const MeshQuery& query, const Cell& parent, int k, Cell& child, Ball& ball) {
  const TriangleMesh& mesh = query.mesh();
  child.box = octant(parent.box, k);
  child.triangles.clear();
  std::vector<Vec3d> points;
  for (std::uint32_t t : parent.triangles) {
    const Polygon piece =
        clip_to_box({mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)}, child.box);
    if (piece.empty()) continue;
    child.triangles.push_back(t);
    points.insert(points.end(), piece.begin(), piece.end());
  }
  // With no surface in the cell, it is wholly inside or wholly outside.
  if (child.triangles.empty() && !query.inside(child.box.center())) return false;
  for (int c = 0; c < 8; ++c) {
    const Vec3d corner = child.box.corner(static_cast<Box3d::CornerType>(c));
    if (query.inside(corner)) points.push_back(corner);
  }
  ball = min_enclosing_ball(points);
  return true;
}

}  // namespace

std::vector<BallNode> build_octree(const MeshQuery& query, int depth,
                                   const std::function<void(double)>& progress) {
  const TriangleMesh& mesh = query.mesh();
  const Box3d bounds = mesh.bounds();
  // A cube a hair larger than the bounds, so no surface lies on its faces.
  const double side = bounds.sizes().maxCoeff() * (1.0 + 1e-6);
  const Vec3d half = Vec3d::Constant(0.5 * side);
  Cell root{Box3d(bounds.center() - half, bounds.center() + half), {}};
  root.triangles.resize(mesh.triangles.size());
  for (std::uint32_t t = 0; t < root.triangles.size(); ++t) root.triangles[t] = t;

  std::vector<BallNode> nodes{{min_enclosing_ball(mesh.vertices), -1}};
  std::vector<Cell> level{root};
  for (int l = 1; l < depth; ++l) {
    const auto level_start = static_cast<std::int32_t>(nodes.size() - level.size());
    std::vector<Cell> next;
    for (std::size_t i = 0; i < level.size(); ++i) {
      for (int k = 0; k < 8; ++k) {
        Cell child;
        Ball ball;
        if (!make_child(query, level[i], k, child, ball)) continue;
        nodes.push_back({ball, level_start + static_cast<std::int32_t>(i)});
        next.push_back(std::move(child));
      }
      if (progress) {
        progress((l - 1 + static_cast<double>(i + 1) / static_cast<double>(level.size())) /
                 (depth - 1));
      }
    }
    level = std::move(next);
  }
  return nodes;
}

}  // namespace sphys::tools::build
