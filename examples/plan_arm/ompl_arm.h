#pragma once

// The test robot's arm as OMPL plans it with sphys's checks: its model in the arm's joint order,
// the checks counted, OMPL's motion validator on RobotChecker::check_motion, and the problems the
// planning example and the planning benchmark pose (free start and goal, no free straight motion
// between them).

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "robot_arm/robot_arm.h"
#include "sphys/robot_check.h"
#include "sphys/world_query.h"

namespace sphys::examples {

// Largest change of the joint values (their Euclidean norm) between two states a motion is checked
// at: OMPL's motion validators check motions at discrete steps too. unit: rad (m for the fingers)
inline constexpr double kMotionStep = 0.02;
// A returned path is checked again at steps this many times finer.
inline constexpr int kFinerChecks = 10;

[[nodiscard]] std::vector<double> values_of(const ompl::base::State* state, std::size_t joints);

// The configurations from a to b at steps of at most `step` (the Euclidean norm of the joint
// values' change, as RobotChecker::check_motion steps), both ends included.
[[nodiscard]] std::vector<std::vector<double>> steps_between(const std::vector<double>& a,
                                                             const std::vector<double>& b,
                                                             double step);

// The arm as sphys's robot checks take it: its URDF's chain with the links' spheres, in the same
// joint order as the arm's (the order OMPL's states hold the values in).
[[nodiscard]] RobotModel model_of(const RobotArm& arm);

// sphys's checks from joint values, counted.
class ArmChecker {
 public:
  ArmChecker(const RobotArm& arm, const WorldQuery& query, RobotCheckSettings settings = {});
  [[nodiscard]] bool free_one(const std::vector<double>& configuration);
  [[nodiscard]] MotionResult motion(const std::vector<double>& a, const std::vector<double>& b);
  [[nodiscard]] std::size_t configurations() const { return configurations_; }
  [[nodiscard]] std::size_t motions() const { return motions_; }

 private:
  RobotChecker checker_;
  std::vector<ConfigurationResult> result_ = std::vector<ConfigurationResult>(1);
  std::size_t configurations_ = 0;
  std::size_t motions_ = 0;
};

// OMPL's motion validator: RobotChecker::check_motion, its states coarse to fine.
class SphysMotionValidator final : public ompl::base::MotionValidator {
 public:
  SphysMotionValidator(const ompl::base::SpaceInformationPtr& si, ArmChecker& checker,
                       std::size_t joints)
      : ompl::base::MotionValidator(si), checker_(checker), joints_(joints) {}
  bool checkMotion(const ompl::base::State* a, const ompl::base::State* b) const override;
  bool checkMotion(const ompl::base::State* a, const ompl::base::State* b,
                   std::pair<ompl::base::State*, double>& last_valid) const override;

 private:
  ArmChecker& checker_;
  std::size_t joints_;
};

// A planning problem: a free start and a free goal that no free straight motion joins, drawn
// within the arm's limits. Throws sphys::Error when 1,000 draws find none.
struct ArmProblem {
  std::vector<double> start;
  std::vector<double> goal;
};
[[nodiscard]] ArmProblem blocked_problem(const RobotArm& arm, ArmChecker& checker,
                                         std::mt19937& rng);

// OMPL's real vector space over the arm's joints, within their limits.
[[nodiscard]] std::shared_ptr<ompl::base::RealVectorStateSpace> arm_space(const RobotArm& arm);

// The examples' command lines: "--name value" pairs, each name one of `names`, by name. Throws
// sphys::Error for another name or a name without a value.
[[nodiscard]] std::map<std::string, std::string> example_options(
    int argc, char** argv, std::initializer_list<std::string_view> names);

// An example's main: `run`'s exit code, or 2 after printing "<name>: error: ..." for a
// sphys::Error or a number that does not read.
int run_example(const char* name, const std::function<int()>& run);

// RRT-Connect from `start` to `goal` with `checker` as OMPL's state-validity checker and motion
// validator, for at most `seconds`, the path simplified: its waypoints, start and goal included;
// none when no exact solution was found.
[[nodiscard]] std::vector<std::vector<double>> plan_path(const RobotArm& arm, ArmChecker& checker,
                                                         const std::vector<double>& start,
                                                         const std::vector<double>& goal,
                                                         double seconds);

}  // namespace sphys::examples
