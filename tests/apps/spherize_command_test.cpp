// `sphys spherize` as a user meets it: the three files it writes are read back with the parsers
// the planners use (yaml-cpp, tinyxml2, urdfdom), and the spheres are checked against the robot's
// true geometry, sampled by the test itself (support/test_robot.h).

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tinyxml2.h>
#include <unistd.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>
#include <vector>
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "apps/cli.h"
#include "support/temp_file.h"
#include "support/test_robot.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;
using test::sphys_cli;
using testing::HasSubstr;
using testing::StartsWith;

// The command promises coverage, so a true surface point may lie outside every sphere by no more
// than rounding. unit: m
constexpr double kCoverageTolerance = 1e-6;
// The same spheres in two files: equal to this fraction of the larger of the two numbers and the
// link's size.
constexpr double kSameSphereTolerance = 1e-6;
constexpr int kSphereBudget = 60;
constexpr double kMaxProtrusion = 0.01;  // unit: m
const std::vector<std::string> kFormats = {"curobo", "srdf", "urdf"};

struct Ball {
  Vector3d center = Vector3d::Zero();  // unit: m, in the link's frame
  double radius = 0.0;                 // unit: m
};
using LinkBalls = std::map<std::string, std::vector<Ball>>;

std::string ball_text(const Ball& b) {
  std::ostringstream out;
  out.precision(17);
  out << "{center [" << b.center.x() << ", " << b.center.y() << ", " << b.center.z() << "], radius "
      << b.radius << "}";
  return out.str();
}

// --- The three files, read back independently ----------------------------------------------------

Ball yaml_ball(const YAML::Node& node) {
  const YAML::Node center = node["center"];
  if (!center.IsSequence() || center.size() != 3) {
    throw std::runtime_error("a sphere's center is not a list of three numbers");
  }
  return {{center[0].as<double>(), center[1].as<double>(), center[2].as<double>()},
          node["radius"].as<double>()};
}

struct CuroboFile {
  LinkBalls spheres;                     // collision_spheres
  std::map<std::string, Ball> bounding;  // bounding_spheres
};

CuroboFile read_curobo(const fs::path& path) {
  const YAML::Node root = YAML::LoadFile(path.string());
  CuroboFile file;
  const YAML::Node spheres = root["collision_spheres"];
  if (!spheres.IsMap()) throw std::runtime_error(path.string() + ": no collision_spheres map");
  for (const auto& link : spheres) {
    std::vector<Ball>& balls = file.spheres[link.first.as<std::string>()];
    if (!link.second.IsSequence()) throw std::runtime_error(path.string() + ": not a list");
    for (const auto& sphere : link.second) balls.push_back(yaml_ball(sphere));
  }
  const YAML::Node bounding = root["bounding_spheres"];
  if (!bounding.IsMap()) throw std::runtime_error(path.string() + ": no bounding_spheres map");
  for (const auto& link : bounding) {
    file.bounding[link.first.as<std::string>()] = yaml_ball(link.second);
  }
  return file;
}

Vector3d parse_triple(const char* text) {
  if (text == nullptr) throw std::runtime_error("a sphere has no center");
  std::istringstream in(text);
  Vector3d v = Vector3d::Zero();
  in >> v.x() >> v.y() >> v.z();
  std::string rest;
  if (in.fail() || (in >> rest)) {
    throw std::runtime_error(std::string("a center is not three numbers: ") + text);
  }
  return v;
}

// MoveIt's SRDF: <robot name><link_sphere_approximation link><sphere center radius/>.
LinkBalls read_srdf(const fs::path& path, std::string* robot_name) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw std::runtime_error(path.string() + ": " + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) throw std::runtime_error(path.string() + ": no <robot> element");
  if (robot_name != nullptr) *robot_name = robot->Attribute("name") ? robot->Attribute("name") : "";
  LinkBalls links;
  for (const tinyxml2::XMLElement* approximation =
           robot->FirstChildElement("link_sphere_approximation");
       approximation != nullptr;
       approximation = approximation->NextSiblingElement("link_sphere_approximation")) {
    const char* link = approximation->Attribute("link");
    if (link == nullptr) throw std::runtime_error(path.string() + ": an approximation has no link");
    std::vector<Ball>& balls = links[link];
    for (const tinyxml2::XMLElement* sphere = approximation->FirstChildElement("sphere");
         sphere != nullptr; sphere = sphere->NextSiblingElement("sphere")) {
      Ball ball;
      ball.center = parse_triple(sphere->Attribute("center"));
      if (sphere->QueryDoubleAttribute("radius", &ball.radius) != tinyxml2::XML_SUCCESS) {
        throw std::runtime_error(path.string() + ": a sphere of " + link + " has no radius");
      }
      balls.push_back(ball);
    }
  }
  return links;
}

urdf::ModelInterfaceSharedPtr parse_urdf_file(const fs::path& path) {
  urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(test::read_whole(path));
  if (!model) throw std::runtime_error(path.string() + ": urdfdom cannot parse it");
  return model;
}

// The spherized URDF: each link's collision elements, every one of which must be a sphere at an
// unrotated origin. Links without collision elements are left out.
LinkBalls read_spherized_urdf(const fs::path& path) {
  const urdf::ModelInterfaceSharedPtr model = parse_urdf_file(path);
  std::vector<urdf::LinkSharedPtr> links;
  model->getLinks(links);
  LinkBalls out;
  for (const urdf::LinkSharedPtr& link : links) {
    for (const urdf::CollisionSharedPtr& collision : link->collision_array) {
      const auto sphere = std::dynamic_pointer_cast<urdf::Sphere>(collision->geometry);
      if (!sphere) throw std::runtime_error(link->name + ": a collision element is not a sphere");
      const urdf::Rotation& q = collision->origin.rotation;
      if (std::abs(std::abs(q.w) - 1.0) > 1e-12) {
        throw std::runtime_error(link->name + ": a collision sphere's origin is rotated");
      }
      const urdf::Vector3& p = collision->origin.position;
      out[link->name].push_back({{p.x, p.y, p.z}, sphere->radius});
    }
  }
  return out;
}

LinkBalls read_spheres(const std::string& format, const fs::path& path) {
  if (format == "curobo") return read_curobo(path).spheres;
  if (format == "srdf") return read_srdf(path, nullptr);
  return read_spherized_urdf(path);
}

// --- Geometry checks -----------------------------------------------------------------------------

struct CoverageGap {
  double worst = 0.0;       // the farthest a sample lies outside every sphere. unit: m
  std::size_t outside = 0;  // samples outside by more than kCoverageTolerance
  Vector3d where = Vector3d::Zero();
};

CoverageGap coverage_gap(const std::vector<Vector3d>& samples, const std::vector<Ball>& balls) {
  CoverageGap gap;
  for (const Vector3d& p : samples) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Ball& b : balls) nearest = std::min(nearest, (p - b.center).norm() - b.radius);
    if (nearest > gap.worst) {
      gap.worst = nearest;
      gap.where = p;
    }
    if (nearest > kCoverageTolerance) ++gap.outside;
  }
  return gap;
}

// Every ground-truth sample of every link lies inside one of the link's spheres.
void expect_covered(const test::TestRobot& robot, const LinkBalls& balls, const std::string& what,
                    const nlohmann::json* report = nullptr) {
  for (const auto& [link, truth] : robot.truth) {
    const auto found = balls.find(link);
    if (found == balls.end() || found->second.empty()) {
      ADD_FAILURE() << what << ": no spheres for " << link;
      continue;
    }
    const CoverageGap gap = coverage_gap(truth.samples, found->second);
    std::string reported;
    if (report != nullptr && report->contains("links")) {
      for (const auto& entry : (*report)["links"]) {
        if (entry.value("link", "") == link) reported = entry.dump();
      }
    }
    EXPECT_LE(gap.worst, kCoverageTolerance)
        << what << ": " << link << ": " << gap.outside << " of " << truth.samples.size()
        << " true surface samples lie outside every sphere, the farthest by " << gap.worst
        << " m at (" << gap.where.transpose() << "); reported: " << reported;
  }
}

double diagonal(const test::LinkTruth& truth) { return truth.bounds.diagonal().norm(); }

// A lower bound on how far a sphere reaches out of the link's geometry: its extreme point along
// an axis lies at least this far beyond the true geometry's bounding box (and the command's mesh
// lies inside the true geometry, so at least as far from it). unit: m
double box_overshoot(const Eigen::AlignedBox3d& box, const Ball& b) {
  double overshoot = 0.0;
  for (int k = 0; k < 3; ++k) {
    overshoot = std::max({overshoot, b.center[k] + b.radius - box.max()[k],
                          box.min()[k] - (b.center[k] - b.radius)});
  }
  return overshoot;
}

double nearest_sample_distance(const test::LinkTruth& truth, const Vector3d& p) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Vector3d& s : truth.samples) nearest = std::min(nearest, (s - p).norm());
  return nearest;
}

// Spheres that have no business with their link: a centre farther from the geometry than its
// radius plus the link's size, a radius beyond the link's size (a sphere that large covers the
// link alone).
void expect_spheres_near_their_links(const test::TestRobot& robot, const LinkBalls& balls) {
  for (const auto& [link, spheres] : balls) {
    const auto found = robot.truth.find(link);
    if (found == robot.truth.end()) continue;
    const double size = diagonal(found->second);
    for (const Ball& b : spheres) {
      EXPECT_TRUE(std::isfinite(b.radius) && b.radius > 0.0) << link << ": " << ball_text(b);
      EXPECT_LE(b.radius, size) << link << ": " << ball_text(b);
      EXPECT_LE(nearest_sample_distance(found->second, b.center), b.radius + size)
          << link << ": " << ball_text(b);
    }
  }
}

bool same_number(double a, double b, double size) {
  return std::abs(a - b) <= kSameSphereTolerance * std::max({std::abs(a), std::abs(b), size});
}

bool same_ball(const Ball& a, const Ball& b, double size) {
  return same_number(a.radius, b.radius, size) && same_number(a.center.x(), b.center.x(), size) &&
         same_number(a.center.y(), b.center.y(), size) &&
         same_number(a.center.z(), b.center.z(), size);
}

// The same spheres per link, in any order.
void expect_same_spheres(const test::TestRobot& robot, const LinkBalls& a, const LinkBalls& b,
                         const std::string& what) {
  std::set<std::string> links_a;
  std::set<std::string> links_b;
  for (const auto& entry : a) links_a.insert(entry.first);
  for (const auto& entry : b) links_b.insert(entry.first);
  EXPECT_EQ(links_a, links_b) << what;
  for (const auto& [link, balls_a] : a) {
    const auto found = b.find(link);
    if (found == b.end()) continue;
    const std::vector<Ball>& balls_b = found->second;
    ASSERT_EQ(balls_a.size(), balls_b.size()) << what << ": " << link;
    const auto truth = robot.truth.find(link);
    const double size = truth == robot.truth.end() ? 1.0 : diagonal(truth->second);
    std::vector<bool> used(balls_b.size(), false);
    for (const Ball& ball : balls_a) {
      bool matched = false;
      for (std::size_t i = 0; i < balls_b.size() && !matched; ++i) {
        if (!used[i] && same_ball(ball, balls_b[i], size)) {
          used[i] = true;
          matched = true;
        }
      }
      EXPECT_TRUE(matched) << what << ": " << link << ": " << ball_text(ball)
                           << " of the first file is not in the second";
    }
  }
}

std::size_t total_spheres(const LinkBalls& balls) {
  std::size_t total = 0;
  for (const auto& entry : balls) total += entry.second.size();
  return total;
}

// --- Running the command -------------------------------------------------------------------------

struct SpherizeRun {
  test::CommandResult result;
  fs::path output;
  nlohmann::json report;  // discarded when standard output is not JSON
};

std::vector<std::string> spherize_args(const test::TestRobot& robot, const std::string& format,
                                       const fs::path& output,
                                       const std::vector<std::string>& options) {
  std::vector<std::string> args = {
      "spherize", robot.urdf.string(), "--package", robot.package_option, "--format", format,
      "-o",       output.string()};
  args.insert(args.end(), options.begin(), options.end());
  return args;
}

SpherizeRun run_spherize(const test::TestRobot& robot, const std::string& format,
                         const fs::path& output, const std::vector<std::string>& options) {
  SpherizeRun run;
  run.output = output;
  run.result = sphys_cli(spherize_args(robot, format, output, options));
  run.report = nlohmann::json::parse(run.result.out, nullptr, false);
  return run;
}

// The standard robot and the runs several tests read, each made once per test program (when a
// test first asks for it) in a scratch folder removed when the program ends.
class StandardRobotRuns {
 public:
  StandardRobotRuns()
      : dir_(fs::temp_directory_path() / ("sphys_spherize_test_" + std::to_string(getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    robot_ = test::write_test_robot(dir_, test::standard_test_robot());
  }
  ~StandardRobotRuns() {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  StandardRobotRuns(const StandardRobotRuns&) = delete;
  StandardRobotRuns& operator=(const StandardRobotRuns&) = delete;

  [[nodiscard]] const test::TestRobot& robot() const { return robot_; }
  [[nodiscard]] const fs::path& dir() const { return dir_; }

  // --spheres 60 --json, written in `format`.
  const SpherizeRun& with_budget(const std::string& format) {
    const std::string key = "budget " + format;
    if (!runs_.contains(key)) {
      runs_[key] = run_spherize(robot_, format, dir_ / ("budget_" + format + ".out"),
                                {"--spheres", std::to_string(kSphereBudget), "--json"});
    }
    return runs_[key];
  }

  // --max-protrusion 0.01 --json, as cuRobo YAML.
  const SpherizeRun& with_max_protrusion() {
    const std::string key = "protrusion";
    if (!runs_.contains(key)) {
      runs_[key] = run_spherize(robot_, "curobo", dir_ / "protrusion.yml",
                                {"--max-protrusion", "0.01", "--json"});
    }
    return runs_[key];
  }

 private:
  fs::path dir_;
  test::TestRobot robot_;
  std::map<std::string, SpherizeRun> runs_;
};

StandardRobotRuns& standard_runs() {
  static StandardRobotRuns runs;
  return runs;
}

std::set<std::string> link_set(const std::vector<std::string>& links) {
  return {links.begin(), links.end()};
}

// The keys of a map by link name.
template <typename Value>
std::set<std::string> link_set(const std::map<std::string, Value>& by_link) {
  std::set<std::string> links;
  for (const auto& entry : by_link) links.insert(entry.first);
  return links;
}

const nlohmann::json* report_link(const nlohmann::json& report, const std::string& link) {
  if (!report.is_object() || !report.contains("links")) return nullptr;
  for (const auto& entry : report["links"]) {
    if (entry.value("link", "") == link) return &entry;
  }
  return nullptr;
}

// --- The standard robot, --spheres 60 ------------------------------------------------------------

TEST(SpherizeCommand, EveryFormatGivesEveryLinkWithGeometrySpheresWithinTheBudget) {
  StandardRobotRuns& runs = standard_runs();
  const test::TestRobot& robot = runs.robot();
  ASSERT_EQ(robot.links_with_geometry.size(), 7U);
  for (const std::string& format : kFormats) {
    SCOPED_TRACE(format);
    const SpherizeRun& run = runs.with_budget(format);
    ASSERT_EQ(run.result.exit_code, 0) << run.result.out << run.result.err;
    ASSERT_TRUE(fs::exists(run.output));
    const LinkBalls balls = read_spheres(format, run.output);
    // Every link with geometry, none without (tool0).
    EXPECT_EQ(link_set(balls), link_set(robot.links_with_geometry));
    for (const auto& [link, spheres] : balls) EXPECT_FALSE(spheres.empty()) << link;
    EXPECT_LE(total_spheres(balls), static_cast<std::size_t>(kSphereBudget));
    EXPECT_GE(total_spheres(balls), robot.links_with_geometry.size());
  }
}

TEST(SpherizeCommand, TheThreeFormatsHoldTheSameSpheres) {
  StandardRobotRuns& runs = standard_runs();
  std::map<std::string, LinkBalls> balls;
  for (const std::string& format : kFormats) {
    const SpherizeRun& run = runs.with_budget(format);
    ASSERT_EQ(run.result.exit_code, 0) << format << ": " << run.result.err;
    balls[format] = read_spheres(format, run.output);
  }
  expect_same_spheres(runs.robot(), balls["curobo"], balls["srdf"], "curobo vs srdf");
  expect_same_spheres(runs.robot(), balls["curobo"], balls["urdf"], "curobo vs urdf");
  std::string robot_name;
  (void)read_srdf(runs.with_budget("srdf").output, &robot_name);
  EXPECT_EQ(robot_name, "test_robot");
}

TEST(SpherizeCommand, SpheresCoverTheTrueSurfaceOfEveryLinkInEveryFormat) {
  StandardRobotRuns& runs = standard_runs();
  for (const std::string& format : kFormats) {
    const SpherizeRun& run = runs.with_budget(format);
    ASSERT_EQ(run.result.exit_code, 0) << format << ": " << run.result.err;
    expect_covered(runs.robot(), read_spheres(format, run.output), format, &run.report);
  }
}

TEST(SpherizeCommand, BoundingSpheresHoldTheirLinksSpheres) {
  StandardRobotRuns& runs = standard_runs();
  const SpherizeRun& run = runs.with_budget("curobo");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const CuroboFile file = read_curobo(run.output);
  EXPECT_EQ(link_set(file.bounding), link_set(file.spheres));
  for (const auto& [link, spheres] : file.spheres) {
    const auto bounding = file.bounding.find(link);
    if (bounding == file.bounding.end()) continue;
    const Ball& outer = bounding->second;
    const double tolerance = kSameSphereTolerance * diagonal(runs.robot().truth.at(link));
    for (const Ball& b : spheres) {
      EXPECT_LE((b.center - outer.center).norm() + b.radius, outer.radius + tolerance)
          << link << ": " << ball_text(b) << " sticks out of " << ball_text(outer);
    }
    // The report's bounding sphere is the file's.
    const nlohmann::json* entry = report_link(run.report, link);
    ASSERT_NE(entry, nullptr) << link;
    ASSERT_TRUE(entry->contains("bounding_sphere")) << entry->dump();
    const nlohmann::json& reported = (*entry)["bounding_sphere"];
    const Ball from_report{
        {reported["center"][0].get<double>(), reported["center"][1].get<double>(),
         reported["center"][2].get<double>()},
        reported["radius"].get<double>()};
    EXPECT_TRUE(same_ball(from_report, outer, diagonal(runs.robot().truth.at(link))))
        << link << ": report " << ball_text(from_report) << ", file " << ball_text(outer);
  }
}

TEST(SpherizeCommand, CheckUrdfAcceptsTheSpherizedUrdf) {
  StandardRobotRuns& runs = standard_runs();
  const SpherizeRun& run = runs.with_budget("urdf");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const fs::path check_urdf = "/usr/bin/check_urdf";
  if (!fs::exists(check_urdf)) GTEST_SKIP() << "check_urdf (liburdfdom-tools) is not installed";
  const test::CommandResult checked = test::run_command(check_urdf.string(), {run.output.string()});
  EXPECT_EQ(checked.exit_code, 0) << checked.out << checked.err;
  EXPECT_THAT(checked.out, HasSubstr("robot name is: test_robot"));
}

TEST(SpherizeCommand, SpherizedUrdfKeepsLinksJointsAndVisuals) {
  StandardRobotRuns& runs = standard_runs();
  const SpherizeRun& run = runs.with_budget("urdf");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const urdf::ModelInterfaceSharedPtr input = parse_urdf_file(runs.robot().urdf);
  const urdf::ModelInterfaceSharedPtr output = parse_urdf_file(run.output);
  EXPECT_EQ(output->getName(), input->getName());
  EXPECT_EQ(output->getRoot()->name, input->getRoot()->name);

  ASSERT_EQ(output->joints_.size(), input->joints_.size());
  for (const auto& [name, joint] : input->joints_) {
    const auto found = output->joints_.find(name);
    ASSERT_NE(found, output->joints_.end()) << name;
    const urdf::JointSharedPtr& copy = found->second;
    EXPECT_EQ(copy->type, joint->type) << name;
    EXPECT_EQ(copy->parent_link_name, joint->parent_link_name) << name;
    EXPECT_EQ(copy->child_link_name, joint->child_link_name) << name;
    const urdf::Pose& a = joint->parent_to_joint_origin_transform;
    const urdf::Pose& b = copy->parent_to_joint_origin_transform;
    EXPECT_NEAR(a.position.x, b.position.x, 1e-9) << name;
    EXPECT_NEAR(a.position.y, b.position.y, 1e-9) << name;
    EXPECT_NEAR(a.position.z, b.position.z, 1e-9) << name;
    EXPECT_NEAR(std::abs(a.rotation.w * b.rotation.w + a.rotation.x * b.rotation.x +
                         a.rotation.y * b.rotation.y + a.rotation.z * b.rotation.z),
                1.0, 1e-9)
        << name;
    EXPECT_NEAR(copy->axis.x, joint->axis.x, 1e-12) << name;
    EXPECT_NEAR(copy->axis.y, joint->axis.y, 1e-12) << name;
    EXPECT_NEAR(copy->axis.z, joint->axis.z, 1e-12) << name;
  }

  std::vector<urdf::LinkSharedPtr> links;
  input->getLinks(links);
  ASSERT_EQ(links.size(), runs.robot().links.size());
  for (const urdf::LinkSharedPtr& link : links) {
    SCOPED_TRACE(link->name);
    const urdf::LinkConstSharedPtr copy = output->getLink(link->name);
    ASSERT_TRUE(copy);
    // Visual elements as they were.
    ASSERT_EQ(copy->visual_array.size(), link->visual_array.size());
    for (std::size_t i = 0; i < link->visual_array.size(); ++i) {
      const urdf::Visual& a = *link->visual_array[i];
      const urdf::Visual& b = *copy->visual_array[i];
      ASSERT_TRUE(a.geometry && b.geometry);
      EXPECT_EQ(b.geometry->type, a.geometry->type);
      EXPECT_NEAR(b.origin.position.x, a.origin.position.x, 1e-9);
      EXPECT_NEAR(b.origin.position.y, a.origin.position.y, 1e-9);
      EXPECT_NEAR(b.origin.position.z, a.origin.position.z, 1e-9);
      if (const auto mesh_a = std::dynamic_pointer_cast<urdf::Mesh>(a.geometry)) {
        const auto mesh_b = std::dynamic_pointer_cast<urdf::Mesh>(b.geometry);
        ASSERT_TRUE(mesh_b);
        EXPECT_EQ(mesh_b->filename, mesh_a->filename);
        EXPECT_NEAR(mesh_b->scale.x, mesh_a->scale.x, 1e-12);
        EXPECT_NEAR(mesh_b->scale.y, mesh_a->scale.y, 1e-12);
        EXPECT_NEAR(mesh_b->scale.z, mesh_a->scale.z, 1e-12);
      }
    }
    // Collision elements: spheres for a link with geometry, none for the others.
    const bool has_geometry = runs.robot().truth.contains(link->name);
    EXPECT_EQ(copy->collision_array.empty(), !has_geometry);
  }
}

TEST(SpherizeCommand, JsonReportDescribesEveryLink) {
  StandardRobotRuns& runs = standard_runs();
  const test::TestRobot& robot = runs.robot();
  const SpherizeRun& run = runs.with_budget("curobo");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const nlohmann::json& report = run.report;
  ASSERT_FALSE(report.is_discarded()) << "not JSON: " << run.result.out;
  ASSERT_TRUE(report.is_object()) << run.result.out;
  EXPECT_EQ(report.value("robot", ""), "test_robot");
  EXPECT_EQ(report.value("format", ""), "curobo");
  ASSERT_TRUE(report.contains("urdf") && report["urdf"].is_string()) << report.dump();
  EXPECT_TRUE(fs::equivalent(report["urdf"].get<std::string>(), robot.urdf)) << report["urdf"];
  ASSERT_TRUE(report.contains("output") && report["output"].is_string()) << report.dump();
  EXPECT_TRUE(fs::equivalent(report["output"].get<std::string>(), run.output)) << report["output"];
  ASSERT_TRUE(report.contains("seconds") && report["seconds"].is_number()) << report.dump();
  EXPECT_GE(report["seconds"].get<double>(), 0.0);

  const LinkBalls file = read_curobo(run.output).spheres;
  ASSERT_TRUE(report.contains("links") && report["links"].is_array()) << report.dump();
  EXPECT_EQ(report["links"].size(), robot.links_with_geometry.size());
  std::set<std::string> named;
  int sphere_sum = 0;
  double worst = 0.0;
  double outside_sum = 0.0;
  for (const nlohmann::json& entry : report["links"]) {
    const std::string link = entry.value("link", "");
    SCOPED_TRACE(entry.dump());
    EXPECT_TRUE(named.insert(link).second) << "named twice";
    const auto truth = robot.truth.find(link);
    ASSERT_NE(truth, robot.truth.end()) << "not a link with geometry";
    for (const char* key : {"spheres", "coverage", "worst_protrusion_m", "outside_volume_m3",
                            "tessellation_error_m"}) {
      ASSERT_TRUE(entry.contains(key) && entry[key].is_number()) << key;
    }
    const int spheres = entry["spheres"].get<int>();
    EXPECT_GE(spheres, 1);
    EXPECT_EQ(static_cast<std::size_t>(spheres), file.count(link) ? file.at(link).size() : 0U);
    sphere_sum += spheres;
    const double coverage = entry["coverage"].get<double>();
    EXPECT_GE(coverage, 0.9999);
    EXPECT_LE(coverage, 1.0);
    const double protrusion = entry["worst_protrusion_m"].get<double>();
    EXPECT_TRUE(std::isfinite(protrusion));
    EXPECT_GE(protrusion, 0.0);
    worst = std::max(worst, protrusion);
    const double outside = entry["outside_volume_m3"].get<double>();
    EXPECT_TRUE(std::isfinite(outside));
    EXPECT_GE(outside, 0.0);
    outside_sum += outside;
    ASSERT_TRUE(entry.contains("from_visual") && entry["from_visual"].is_boolean());
    EXPECT_EQ(entry["from_visual"].get<bool>(), truth->second.from_visual);
    // Boxes and meshes are exact; cylinders and spheres are meshed.
    const double tessellation = entry["tessellation_error_m"].get<double>();
    if (truth->second.curved_primitive) {
      EXPECT_GT(tessellation, 0.0);
      EXPECT_LT(tessellation, 0.01 * diagonal(truth->second));
    } else {
      EXPECT_EQ(tessellation, 0.0);
    }
    ASSERT_TRUE(entry.contains("sources") && entry["sources"].is_array());
    ASSERT_EQ(entry["sources"].size(), truth->second.sources.size());
    for (std::size_t i = 0; i < truth->second.sources.size(); ++i) {
      ASSERT_TRUE(entry["sources"][i].is_string());
      EXPECT_THAT(entry["sources"][i].get<std::string>(), HasSubstr(truth->second.sources[i]));
    }
  }
  EXPECT_TRUE(robot.truth.at("hand_link").from_visual);
  ASSERT_TRUE(report.contains("total") && report["total"].is_object()) << report.dump();
  const nlohmann::json& total = report["total"];
  EXPECT_EQ(total.value("spheres", -1), sphere_sum);
  EXPECT_LE(sphere_sum, kSphereBudget);
  EXPECT_NEAR(total.value("worst_protrusion_m", -1.0), worst, 1e-12 * std::max(worst, 1.0));
  EXPECT_NEAR(total.value("outside_volume_m3", -1.0), outside_sum,
              1e-9 * std::max(outside_sum, 1e-9));
}

TEST(SpherizeCommand, SpheresStayNearTheirLinksAndTheReportedProtrusionIsNoLessThanSeen) {
  StandardRobotRuns& runs = standard_runs();
  const test::TestRobot& robot = runs.robot();
  const SpherizeRun& run = runs.with_budget("curobo");
  ASSERT_EQ(run.result.exit_code, 0) << run.result.err;
  const LinkBalls balls = read_curobo(run.output).spheres;
  expect_spheres_near_their_links(robot, balls);
  for (const auto& [link, spheres] : balls) {
    const nlohmann::json* entry = report_link(run.report, link);
    ASSERT_NE(entry, nullptr) << link;
    const double reported = entry->value("worst_protrusion_m", 0.0);
    const double tessellation = entry->value("tessellation_error_m", 0.0);
    for (const Ball& b : spheres) {
      // The report measures on samples: allow it to miss a sphere's extreme point by a little.
      EXPECT_LE(box_overshoot(robot.truth.at(link).bounds, b),
                reported + tessellation + 0.02 * b.radius + 1e-6)
          << link << ": " << ball_text(b) << " reaches out of the link's bounding box farther "
          << "than the reported worst protrusion " << reported << " m";
    }
  }
}

// --- The standard robot, --max-protrusion 0.01 ---------------------------------------------------

TEST(SpherizeCommand, MaxProtrusionBoundsEveryLinkAndStillCovers) {
  StandardRobotRuns& runs = standard_runs();
  const test::TestRobot& robot = runs.robot();
  const SpherizeRun& run = runs.with_max_protrusion();
  ASSERT_EQ(run.result.exit_code, 0) << run.result.out << run.result.err;
  ASSERT_TRUE(run.report.is_object()) << run.result.out;
  ASSERT_TRUE(run.report.contains("links"));
  EXPECT_EQ(run.report["links"].size(), robot.links_with_geometry.size());
  for (const nlohmann::json& entry : run.report["links"]) {
    SCOPED_TRACE(entry.dump());
    ASSERT_TRUE(entry.contains("worst_protrusion_m") && entry["worst_protrusion_m"].is_number());
    const double protrusion = entry["worst_protrusion_m"].get<double>();
    EXPECT_TRUE(std::isfinite(protrusion));
    EXPECT_GE(protrusion, 0.0);
    EXPECT_LE(protrusion, kMaxProtrusion);
    EXPECT_GE(entry.value("coverage", 0.0), 0.9999);
  }
  const LinkBalls balls = read_curobo(run.output).spheres;
  EXPECT_EQ(link_set(balls), link_set(robot.links_with_geometry));
  expect_covered(robot, balls, "--max-protrusion 0.01", &run.report);
  expect_spheres_near_their_links(robot, balls);
  // Independently: no sphere reaches beyond its link's bounding box by more than the bound (and
  // what the sampled measure and the tessellation may miss).
  for (const auto& [link, spheres] : balls) {
    const nlohmann::json* entry = report_link(run.report, link);
    const double tessellation = entry ? entry->value("tessellation_error_m", 0.0) : 0.0;
    for (const Ball& b : spheres) {
      EXPECT_LE(box_overshoot(robot.truth.at(link).bounds, b),
                kMaxProtrusion + tessellation + 0.02 * b.radius + 1e-6)
          << link << ": " << ball_text(b);
    }
  }
}

// --- Text report, determinism -------------------------------------------------------------------

TEST(SpherizeCommand, TheSameCommandWritesTheSameBytesTwice) {
  StandardRobotRuns& runs = standard_runs();
  const test::TestRobot& robot = runs.robot();
  const SpherizeRun& first = runs.with_budget("urdf");
  ASSERT_EQ(first.result.exit_code, 0) << first.result.out << first.result.err;
  const std::string first_bytes = test::read_whole(first.output);
  ASSERT_FALSE(first_bytes.empty());
  // The same options but the text report instead of JSON, to another file.
  const fs::path output = runs.dir() / "twice.urdf";
  const test::CommandResult second =
      sphys_cli(spherize_args(robot, "urdf", output, {"--spheres", std::to_string(kSphereBudget)}));
  ASSERT_EQ(second.exit_code, 0) << second.out << second.err;
  EXPECT_TRUE(test::read_whole(output) == first_bytes) << "the two files differ";
  // The text report names every link with geometry.
  for (const std::string& link : robot.links_with_geometry) {
    EXPECT_THAT(second.out, HasSubstr(link));
  }
}

// --- Defective meshes ----------------------------------------------------------------------------

// A robot of a box base and one link made of `defective`, spherized: it must succeed, and the
// spheres must cover the link's surface as it is.
// A box base and one link, "defect_link", made of `geometry`.
test::RobotSpec two_link_robot(const test::RobotGeometry& geometry) {
  test::RobotSpec spec;
  spec.name = "defect_robot";
  spec.links = {{"base_link", {test::box_geometry({0.2, 0.2, 0.05}, {0.0, 0.0, 0.025})}, {}},
                {"defect_link", {geometry}, {}}};
  spec.joints = {{"joint_1",
                  "revolute",
                  "base_link",
                  "defect_link",
                  {0.0, 0.0, 0.05},
                  {0.0, 0.0, 0.0},
                  {0.0, 0.0, 1.0},
                  -1.0,
                  1.0}};
  return spec;
}

void expect_defective_link_covered(const test::RobotGeometry& defective) {
  const test::TempDir dir;
  const test::TestRobot robot = test::write_test_robot(dir.path(), two_link_robot(defective));
  const SpherizeRun run =
      run_spherize(robot, "curobo", dir.path() / "spheres.yml", {"--spheres", "16", "--json"});
  ASSERT_EQ(run.result.exit_code, 0) << run.result.out << run.result.err;
  const LinkBalls balls = read_curobo(run.output).spheres;
  EXPECT_EQ(link_set(balls), link_set(robot.links_with_geometry));
  EXPECT_LE(total_spheres(balls), 16U);
  expect_covered(robot, balls, "defective mesh", &run.report);
  expect_spheres_near_their_links(robot, balls);
  const nlohmann::json* entry = report_link(run.report, "defect_link");
  ASSERT_NE(entry, nullptr) << run.result.out;
  EXPECT_GE(entry->value("coverage", 0.0), 0.9999) << entry->dump();
  ASSERT_TRUE(entry->contains("worst_protrusion_m") && (*entry)["worst_protrusion_m"].is_number())
      << entry->dump();
  EXPECT_TRUE(std::isfinite((*entry)["worst_protrusion_m"].get<double>())) << entry->dump();
}

TEST(SpherizeCommand, AnOpenMeshIsCovered) {
  // A box without its top face.
  test::RobotMesh open = test::box_mesh({0.08, 0.06, 0.12});
  open.triangles.resize(open.triangles.size() - 2);
  expect_defective_link_covered(
      test::mesh_geometry(open, "open_box.stl", test::MeshFileType::AsciiStl,
                          test::MeshReference::Relative, {0.01, 0.02, 0.06}, {0.1, 0.2, 0.3}));
}

TEST(SpherizeCommand, DuplicateAndFlippedFacesAreCovered) {
  test::RobotMesh messy = test::capsule_mesh(0.03, 0.06, 16, 4);
  const std::size_t count = messy.triangles.size();
  for (std::size_t i = 0; i < count; i += 5)
    std::swap(messy.triangles[i][1], messy.triangles[i][2]);
  for (std::size_t i = 0; i < 30; ++i) {
    const auto t = messy.triangles[i];
    messy.triangles.push_back(t);
  }
  for (std::size_t i = 30; i < 50; ++i) {
    const auto t = messy.triangles[i];
    messy.triangles.push_back({t[0], t[2], t[1]});
  }
  expect_defective_link_covered(test::mesh_geometry(messy, "messy.obj", test::MeshFileType::Obj,
                                                    test::MeshReference::Package, {0.0, 0.0, 0.09},
                                                    {0.0, 0.3, 0.0}));
}

TEST(SpherizeCommand, AMeshInMillimetresScaledByTheUrdfIsCovered) {
  // A torus 1000 times too big, as a CAD export in millimetres, brought to metres by the scale.
  const test::RobotMesh millimetres =
      test::scaled_mesh(test::torus_mesh(0.07, 0.025, 32, 12), 1000.0);
  expect_defective_link_covered(test::mesh_geometry(
      millimetres, "torus_mm.stl", test::MeshFileType::BinaryStl, test::MeshReference::Relative,
      {0.0, 0.0, 0.1}, {0.0, 1.5707963267948966, 0.0}, Vector3d(0.001, 0.001, 0.001)));
}

TEST(SpherizeCommand, AMeshInMillimetresWithoutAScaleIsCoveredAndNoted) {
  // The same export without the scale: a link 346 m across. It is spherized all the same, and a
  // note on standard error points at the units.
  const test::TempDir dir;
  const test::TestRobot robot = test::write_test_robot(
      dir.path(),
      two_link_robot(test::mesh_geometry(
          test::scaled_mesh(test::torus_mesh(0.07, 0.025, 32, 12), 1000.0), "torus_mm.obj",
          test::MeshFileType::Obj, test::MeshReference::Relative, {0.0, 0.0, 0.1})));
  const SpherizeRun run =
      run_spherize(robot, "curobo", dir.path() / "spheres.yml", {"--spheres", "16"});
  ASSERT_EQ(run.result.exit_code, 0) << run.result.out << run.result.err;
  EXPECT_THAT(run.result.err, HasSubstr("sphys: note: link \"defect_link\" is "));
  EXPECT_THAT(run.result.err, HasSubstr("m across: check the mesh's units"));
  EXPECT_THAT(run.result.err, testing::Not(HasSubstr("base_link")));
  expect_covered(robot, read_curobo(run.output).spheres, "millimetres without a scale");
}

// --- Bad input -----------------------------------------------------------------------------------

// Exit code 2, one message starting "sphys: error:" that names each of `named`, and no output
// file.
void expect_refused(const std::vector<std::string>& args, const std::vector<std::string>& named,
                    const fs::path& output) {
  std::string command;
  for (const std::string& arg : args) command += arg + " ";
  SCOPED_TRACE(command);
  const test::CommandResult r = sphys_cli(args);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_THAT(r.err, StartsWith("sphys: error:"));
  for (const std::string& name : named) EXPECT_THAT(r.err, HasSubstr(name));
  EXPECT_FALSE(fs::exists(output)) << "an output file was written";
}

std::vector<std::string> spherize_file_args(const fs::path& urdf, const fs::path& output,
                                            const std::vector<std::string>& options = {}) {
  std::vector<std::string> args = {"spherize", urdf.string(), "--spheres", "60",
                                   "--format", "curobo",      "-o",        output.string()};
  args.insert(args.end(), options.begin(), options.end());
  return args;
}

// `text` with every `from` replaced by `to` (there must be one).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  std::size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("no \"" + from + "\" in the URDF");
  for (; at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

TEST(SpherizeCommand, BadRobotFilesExitWithCode2) {
  const test::TempDir dir;
  const test::TestRobot robot = test::write_test_robot(dir.path(), test::standard_test_robot());
  const fs::path out = dir.path() / "out.yml";
  const std::string package_option = robot.package_option;
  const fs::path robot_dir = robot.urdf.parent_path();
  const std::string urdf_text = test::read_whole(robot.urdf);

  const fs::path missing = dir.path() / "missing.urdf";
  expect_refused(spherize_file_args(missing, out, {"--package", package_option}),
                 {missing.string()}, out);

  const fs::path not_xml = dir.write("not_xml.urdf", "this is { not XML <robot");
  expect_refused(spherize_file_args(not_xml, out, {"--package", package_option}),
                 {not_xml.string()}, out);

  const fs::path dangling = dir.write(
      "dangling.urdf",
      "<robot name=\"r\"><link name=\"a\"><collision><geometry><box size=\"1 1 1\"/></geometry>"
      "</collision></link><joint name=\"j\" type=\"fixed\"><parent link=\"a\"/>"
      "<child link=\"nowhere\"/></joint></robot>");
  expect_refused(spherize_file_args(dangling, out), {dangling.string()}, out);

  const fs::path no_geometry = dir.write(
      "no_geometry.urdf",
      "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" type=\"fixed\">"
      "<parent link=\"a\"/><child link=\"b\"/></joint></robot>");
  expect_refused(spherize_file_args(no_geometry, out), {no_geometry.string()}, out);

  // A mesh file that does not exist: the link and the file are named.
  test::RobotSpec spec = test::standard_test_robot();
  spec.links[2].collisions[0].file_name = "missing_arm.stl";
  const fs::path missing_mesh = robot_dir / "missing_mesh.urdf";
  {
    std::ofstream file(missing_mesh);
    file << test::test_robot_urdf(dir.path(), spec);
  }
  expect_refused(spherize_file_args(missing_mesh, out, {"--package", package_option}),
                 {"upper_arm_link", "missing_arm.stl"}, out);

  // A package that --package does not name.
  const fs::path unknown_package = robot_dir / "unknown_package.urdf";
  {
    std::ofstream file(unknown_package);
    file << replaced(urdf_text, "package://test_robot_pkg/", "package://unknown_pkg/");
  }
  expect_refused(spherize_file_args(unknown_package, out), {"unknown_pkg"}, out);
  expect_refused(spherize_file_args(unknown_package, out, {"--package", package_option}),
                 {"unknown_pkg"}, out);
  // The robot's own package, not given.
  expect_refused(spherize_file_args(robot.urdf, out), {"test_robot_pkg"}, out);

  // A mesh scale of zero: the link is named.
  const fs::path zero_scale = robot_dir / "zero_scale.urdf";
  {
    std::ofstream file(zero_scale);
    file << replaced(urdf_text, "scale=\"1.2 1 0.8\"", "scale=\"0 1 0.8\"");
  }
  expect_refused(spherize_file_args(zero_scale, out, {"--package", package_option}),
                 {"upper_arm_link"}, out);
}

TEST(SpherizeCommand, BadOptionsExitWithCode2) {
  const test::TempDir dir;
  const test::TestRobot robot = test::write_test_robot(dir.path(), test::standard_test_robot());
  const fs::path out = dir.path() / "out.yml";
  const auto command = [&](const std::vector<std::string>& options) {
    std::vector<std::string> args = {
        "spherize", robot.urdf.string(), "--package", robot.package_option, "-o", out.string()};
    args.insert(args.end(), options.begin(), options.end());
    return args;
  };
  // Fewer spheres than the 7 links with geometry.
  expect_refused(command({"--spheres", "2", "--format", "curobo"}), {"spheres"}, out);
  expect_refused(command({"--spheres", "0", "--format", "curobo"}), {"spheres"}, out);
  expect_refused(command({"--spheres", "abc", "--format", "curobo"}), {"spheres"}, out);
  expect_refused(command({"--spheres", "60", "--max-protrusion", "0.01", "--format", "curobo"}),
                 {"--spheres", "--max-protrusion"}, out);
  expect_refused(command({"--format", "curobo"}), {"--spheres", "--max-protrusion"}, out);
  expect_refused(command({"--spheres", "60", "--format", "bogus"}), {"bogus"}, out);
  expect_refused(command({"--max-protrusion", "-1", "--format", "curobo"}), {"max-protrusion"},
                 out);
  expect_refused(command({"--max-protrusion", "0", "--format", "curobo"}), {"max-protrusion"}, out);
  expect_refused(command({"--max-protrusion", "nan", "--format", "curobo"}), {"max-protrusion"},
                 out);
  expect_refused(command({"--spheres", "60", "--format", "curobo", "--package", "no_equals_sign"}),
                 {"package"}, out);
  expect_refused(command({"--spheres", "60", "--format", "curobo", "--package", "=/tmp"}),
                 {"package"}, out);
  // An output file in a folder that does not exist.
  const fs::path nowhere = dir.path() / "no_such_folder" / "out.yml";
  expect_refused({"spherize", robot.urdf.string(), "--package", robot.package_option, "--spheres",
                  "60", "--format", "curobo", "-o", nowhere.string()},
                 {nowhere.string()}, nowhere);
  // No output file at all.
  expect_refused({"spherize", robot.urdf.string(), "--package", robot.package_option, "--spheres",
                  "60", "--format", "curobo"},
                 {}, out);
}

}  // namespace
}  // namespace sphys
