#include "plan_arm/ompl_arm.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <stdexcept>
#include <string>

#include "sphys/error.h"
#include "sphys/tools/robot_model_file.h"

namespace sphys::examples {

namespace ob = ompl::base;
namespace og = ompl::geometric;

std::vector<double> values_of(const ob::State* state, std::size_t joints) {
  const auto* real = state->as<ob::RealVectorStateSpace::StateType>();
  return {real->values, real->values + joints};
}

std::vector<std::vector<double>> steps_between(const std::vector<double>& a,
                                               const std::vector<double>& b, double step) {
  double length = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) length += (b[j] - a[j]) * (b[j] - a[j]);
  const int count = std::max(1, static_cast<int>(std::ceil(std::sqrt(length) / step)));
  std::vector<std::vector<double>> out;
  for (int k = 0; k <= count; ++k) {
    std::vector<double> v(a.size());
    for (std::size_t j = 0; j < a.size(); ++j) v[j] = a[j] + (b[j] - a[j]) * k / count;
    out.push_back(std::move(v));
  }
  return out;
}

RobotModel model_of(const RobotArm& arm) {
  RobotModel model = tools::robot_model(arm.robot, arm.links);
  model.base = Eigen::Isometry3d::Identity();
  model.base.translate(arm.base.translation.cast<double>());
  model.base.rotate(arm.base.rotation.cast<double>());
  for (std::size_t j = 0; j < arm.joints.size(); ++j) {
    if (j >= model.joints.size() || model.joints[j].name != arm.joints[j]) {
      throw Error("the arm's joint " + arm.joints[j] + " is not the model's joint " +
                  std::to_string(j));
    }
  }
  return model;
}

ArmChecker::ArmChecker(const RobotArm& arm, const WorldQuery& query, RobotCheckSettings settings)
    : checker_(query, model_of(arm), std::move(settings)) {}

bool ArmChecker::free_one(const std::vector<double>& configuration) {
  checker_.check(configuration, result_);
  ++configurations_;
  return result_.front().free;
}

MotionResult ArmChecker::motion(const std::vector<double>& a, const std::vector<double>& b) {
  ++motions_;
  return checker_.check_motion(a, b, kMotionStep);
}

bool SphysMotionValidator::checkMotion(const ob::State* a, const ob::State* b) const {
  const bool free = checker_.motion(values_of(a, joints_), values_of(b, joints_)).free;
  ++(free ? valid_ : invalid_);
  return free;
}

bool SphysMotionValidator::checkMotion(const ob::State* a, const ob::State* b,
                                       std::pair<ob::State*, double>& last_valid) const {
  const MotionResult motion = checker_.motion(values_of(a, joints_), values_of(b, joints_));
  if (motion.free) {
    ++valid_;
    return true;
  }
  ++invalid_;
  if (last_valid.first != nullptr) {
    si_->getStateSpace()->interpolate(a, b, motion.last_free, last_valid.first);
  }
  last_valid.second = motion.last_free;
  return false;
}

ArmProblem blocked_problem(const RobotArm& arm, ArmChecker& checker, std::mt19937& rng) {
  const std::size_t joints = arm.joints.size();
  const auto random_free = [&] {
    for (;;) {
      std::vector<double> v(joints);
      for (std::size_t j = 0; j < joints; ++j) {
        v[j] = std::uniform_real_distribution<double>(arm.limits[j][0], arm.limits[j][1])(rng);
      }
      if (checker.free_one(v)) return v;
    }
  };
  for (int tries = 0; tries < 1000; ++tries) {
    ArmProblem problem{random_free(), random_free()};
    if (!checker.motion(problem.start, problem.goal).free) return problem;
  }
  throw Error("no start and goal blocked from each other found");
}

std::shared_ptr<ob::RealVectorStateSpace> arm_space(const RobotArm& arm) {
  const auto joints = static_cast<unsigned>(arm.joints.size());
  auto space = std::make_shared<ob::RealVectorStateSpace>(joints);
  ob::RealVectorBounds bounds(joints);
  for (unsigned j = 0; j < joints; ++j) {
    bounds.setLow(j, arm.limits[j][0]);
    bounds.setHigh(j, arm.limits[j][1]);
  }
  space->setBounds(bounds);
  return space;
}

std::map<std::string, std::string> example_options(int argc, char** argv,
                                                   std::initializer_list<std::string_view> names) {
  std::map<std::string, std::string> options;
  for (int i = 1; i < argc; ++i) {
    const std::string name = argv[i];
    if (std::ranges::find(names, name) == names.end()) throw Error("unknown option " + name);
    if (i + 1 >= argc) throw Error(name + ": needs a value");
    options[name] = argv[++i];
  }
  return options;
}

int run_example(const char* name, const std::function<int()>& run) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  try {
    return run();
  } catch (const Error& error) {
    std::fprintf(stderr, "%s: error: %s\n", name, error.what());
  } catch (const std::invalid_argument& error) {
    std::fprintf(stderr, "%s: error: a number was expected (%s)\n", name, error.what());
  }
  return 2;
}

std::vector<std::vector<double>> plan_path(const RobotArm& arm, ArmChecker& checker,
                                           const std::vector<double>& start,
                                           const std::vector<double>& goal, double seconds) {
  const std::size_t joints = arm.joints.size();
  const auto space = arm_space(arm);
  og::SimpleSetup setup(space);
  const ob::SpaceInformationPtr si = setup.getSpaceInformation();
  setup.setStateValidityChecker(
      [&](const ob::State* state) { return checker.free_one(values_of(state, joints)); });
  si->setMotionValidator(std::make_shared<SphysMotionValidator>(si, checker, joints));
  ob::ScopedState<> start_state(space);
  ob::ScopedState<> goal_state(space);
  for (std::size_t j = 0; j < joints; ++j) {
    start_state[static_cast<unsigned>(j)] = start[j];
    goal_state[static_cast<unsigned>(j)] = goal[j];
  }
  setup.setStartAndGoalStates(start_state, goal_state);
  setup.setPlanner(std::make_shared<og::RRTConnect>(si));
  setup.setup();
  if (setup.solve(seconds) != ob::PlannerStatus::EXACT_SOLUTION) return {};
  setup.simplifySolution();
  const og::PathGeometric& path = setup.getSolutionPath();
  std::vector<std::vector<double>> waypoints;
  for (std::size_t w = 0; w < path.getStateCount(); ++w) {
    waypoints.push_back(values_of(path.getState(static_cast<unsigned>(w)), joints));
  }
  return waypoints;
}

}  // namespace sphys::examples
