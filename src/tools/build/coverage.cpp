#include "coverage.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

namespace sphys::tools::build {
namespace {

using Piece = std::array<Vec3d, 3>;

// Splitting stops here whatever the resolution: 4^8 pieces per triangle at most.
constexpr int kMaxSplits = 8;

// The relative slack forgives rounding for points exactly on a sphere (a cube's corners on its
// circumscribed ball); the float conversion of the finished tree adds a larger margin.
bool holds(const Ball& ball, const Piece& piece) {
  const double slack = 1e-12 * ball.radius;
  return std::all_of(piece.begin(), piece.end(),
                     [&](const Vec3d& p) { return ball.contains(p, slack); });
}

double longest_edge(const Piece& p) {
  return std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
}

// Balls whose bounding box meets the triangle's: the only ones that can hold any of its pieces.
std::vector<std::uint32_t> candidates(const std::vector<Ball>& balls, const Piece& triangle) {
  Box3d box;
  for (const Vec3d& p : triangle) box.extend(p);
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < balls.size(); ++i) {
    const Box3d ball_box(balls[i].center.array() - balls[i].radius,
                         balls[i].center.array() + balls[i].radius);
    if (ball_box.intersects(box)) out.push_back(i);
  }
  return out;
}

// A float sphere that contains the double ball despite rounding the centre and radius.
Sphere to_sphere(const Ball& ball) {
  const Vec3 center = ball.center.cast<float>();
  const double rounding = (center.cast<double>() - ball.center).norm();
  const double margin = 4.0 * std::numeric_limits<float>::epsilon() *
                        (ball.radius + ball.center.cwiseAbs().maxCoeff());
  return {center, static_cast<float>(ball.radius + rounding + margin)};
}

}  // namespace

std::size_t ensure_coverage(std::vector<Ball>& balls, const TriangleMesh& mesh, double resolution) {
  // Growth is judged from the original radii: judging it from the grown ones would let a ball
  // that grew once win every later piece nearby and snowball.
  std::vector<double> original(balls.size());
  for (std::size_t i = 0; i < balls.size(); ++i) original[i] = balls[i].radius;
  std::vector<bool> grown(balls.size(), false);
  std::vector<std::pair<Piece, int>> stack;  // a piece and how often it was split
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Piece triangle{mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)};
    std::vector<std::uint32_t> near = candidates(balls, triangle);
    if (near.empty()) {  // far from every ball: the nearest one must reach it
      near.resize(balls.size());
      for (std::uint32_t i = 0; i < balls.size(); ++i) near[i] = i;
    }
    stack.assign(1, {triangle, 0});
    while (!stack.empty()) {
      const auto [piece, splits] = stack.back();
      stack.pop_back();
      if (std::any_of(near.begin(), near.end(),
                      [&](std::uint32_t i) { return holds(balls[i], piece); })) {
        continue;
      }
      if (longest_edge(piece) > resolution && splits < kMaxSplits) {
        const Vec3d ab = 0.5 * (piece[0] + piece[1]);
        const Vec3d bc = 0.5 * (piece[1] + piece[2]);
        const Vec3d ca = 0.5 * (piece[2] + piece[0]);
        for (const Piece& half : {Piece{piece[0], ab, ca}, Piece{ab, piece[1], bc},
                                  Piece{ca, bc, piece[2]}, Piece{ab, bc, ca}}) {
          stack.emplace_back(half, splits + 1);
        }
        continue;
      }
      // Small and still uncovered: grow the ball that needs the least.
      std::uint32_t best = near.front();
      double best_growth = std::numeric_limits<double>::infinity();
      double best_radius = 0.0;
      for (std::uint32_t i : near) {
        double needed = 0.0;
        for (const Vec3d& p : piece) needed = std::max(needed, (p - balls[i].center).norm());
        if (needed - original[i] < best_growth) {
          best = i;
          best_growth = needed - original[i];
          best_radius = needed;
        }
      }
      balls[best].radius = std::max(balls[best].radius, best_radius);
      grown[best] = true;
    }
  }
  return static_cast<std::size_t>(std::count(grown.begin(), grown.end(), true));
}

std::vector<Sphere> certified_spheres(std::vector<Ball> balls, const TriangleMesh& mesh) {
  ensure_coverage(balls, mesh, kCoverageResolution * mesh.bounds().diagonal().norm());
  std::vector<Sphere> spheres;
  spheres.reserve(balls.size());
  for (const Ball& ball : balls) spheres.push_back(to_sphere(ball));
  return spheres;
}

}  // namespace sphys::tools::build
