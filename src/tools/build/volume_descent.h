#pragma once

// The Tight method's coordinate descent over the balls of one node (ours, not the toolkit's):
// each ball in turn moves to where the smallest ball around the points no other ball holds adds
// the least outside volume to the others', never reaching farther out than a limit.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "ball.h"
#include "exterior_lattice.h"

namespace sphys::tools::build {

// What a cover costs: first the points of its balls' boundaries (at the checked directions)
// farther out than the limit, a constraint; then the outside lattice points its union holds.
struct DescentCost {
  std::size_t beyond = 0;
  std::size_t outside = 0;

  [[nodiscard]] bool operator<(const DescentCost& other) const {
    return beyond != other.beyond ? beyond < other.beyond : outside < other.outside;
  }
};

// How long a descent goes on: at most max_rounds rounds over the balls (fewer once a round
// changes nothing), each ball's pattern search ending when its step falls below last_step
// lattice spacings. Less than the default ranks starts; the default settles a cover.
struct DescentEffort {
  int max_rounds = 20;
  double last_step = 0.25;
};

// The lattice points a ball's candidates are counted against: outside the mesh, held by no other
// ball, within a ball around the candidates. Kept as flat arrays so that each count is one loop
// the compiler vectorises.
struct FreePoints {
  Ball reach;
  std::vector<float> x;
  std::vector<float> y;
  std::vector<float> z;

  void clear(const Ball& around);
  void add(const Vec3d& p);
  [[nodiscard]] bool reaches(const Ball& ball) const;
  // How many lie in the ball; nullopt once the count reaches `limit`.
  [[nodiscard]] std::optional<std::size_t> count_inside(const Ball& ball, std::size_t limit) const;
};

// Coordinate descent over the balls of one node. Each ball in turn is asked to cover only the
// points no other ball holds; its centre moves by pattern search to where the smallest ball
// around those points adds the least outside volume to the others'. Balls left with nothing of
// their own are re-placed by splitting the costliest ball. Copies are independent descents.
class VolumeDescent {
 public:
  // `directions`: the unit directions at which a ball's boundary is checked against `limit`
  // (unit: m, a signed distance from the surface); they must outlive the descent.
  VolumeDescent(const ExteriorLattice& lattice, std::span<const Vec3d> directions,
                std::vector<Vec3d> points, std::vector<Ball> balls, double limit,
                DescentEffort effort = {});

  // Rounds over the balls until one changes nothing (or the effort's limit).
  void run();
  // Grows the balls so that every point lies in one: each point no ball holds goes to the ball
  // it lies least far outside of. For balls placed against other points than this descent's.
  void grow_to_cover();

  [[nodiscard]] DescentCost total() const;
  [[nodiscard]] const std::vector<Ball>& balls() const { return balls_; }

 private:
  // How many of the ball's boundary points (at the checked directions) lie farther out than the
  // limit.
  [[nodiscard]] std::size_t beyond(const Ball& ball) const;
  void gather_free(const Ball& ball);
  void add(const Ball& ball, int sign);
  [[nodiscard]] std::vector<Vec3d> uncovered() const;
  [[nodiscard]] std::optional<std::pair<Ball, DescentCost>> fit(const Vec3d& center,
                                                                const std::vector<Vec3d>& own,
                                                                const DescentCost& bound) const;
  bool search(Ball& ball, const std::vector<Vec3d>& own);
  bool split_costliest_into(std::size_t idle);

  const ExteriorLattice* lattice_;
  std::span<const Vec3d> directions_;
  std::vector<Vec3d> points_;
  std::vector<Ball> balls_;
  double limit_;  // unit: m
  DescentEffort effort_;
  std::vector<std::uint16_t> holders_;  // balls holding each lattice point (outside ones)
  std::vector<std::uint16_t> covered_;  // balls holding each point
  FreePoints free_;
};

}  // namespace sphys::tools::build
