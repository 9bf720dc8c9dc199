#include "robot_view.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <algorithm>
#include <cstdint>
#include <string>

#include <Eigen/Geometry>

#include "camera.h"
#include "renderer.h"
#include "sphys/error.h"
#include "sphys/tools/primitives.h"
#include "sphys/tools/spherize.h"
#include "window.h"

namespace sphys::viewer {
namespace {

const Eigen::Vector3f kLinkColour(0.80f, 0.80f, 0.82f);
const Eigen::Vector3f kVisualLinkColour(0.86f, 0.72f, 0.52f);  // drawn from its visual geometry
const Eigen::Vector3f kSphereColour(0.25f, 0.55f, 0.95f);
constexpr float kSphereAlpha = 0.3f;

// URDF robots stand on z; the viewer's world has y up.
Eigen::Matrix4f z_up_to_y_up() {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<3, 3>(0, 0) =
      Eigen::AngleAxisf(-0.5f * static_cast<float>(EIGEN_PI), Eigen::Vector3f::UnitX())
          .toRotationMatrix();
  return m;
}

struct PlacedLink {
  std::uint32_t mesh = 0;
  Eigen::Matrix4f model;
  bool from_visual = false;
  std::vector<Sphere> spheres;  // in the link's frame
};

class RobotScene {
 public:
  RobotScene(Renderer& renderer, const tools::Robot& robot,
             const std::map<std::string, tools::Pose3d>& poses,
             const std::map<std::string, std::vector<Sphere>>& spheres) {
    for (const tools::LinkGeometry& link : robot.links) {
      const auto pose = poses.find(link.link);
      if (pose == poses.end()) continue;  // not connected to the root
      PlacedLink placed;
      placed.mesh = renderer.add_mesh(link.mesh);
      placed.model = z_up_to_y_up() * pose->second.matrix().cast<float>();
      placed.from_visual = link.from_visual;
      if (const auto s = spheres.find(link.link); s != spheres.end()) placed.spheres = s->second;
      for (const tools::Vec3d& v : link.mesh.vertices) {
        bounds_.extend((placed.model * v.cast<float>().homogeneous()).head<3>());
      }
      links_.push_back(std::move(placed));
    }
    sphere_ = renderer.add_mesh(tools::make_icosphere(1.0, 3));
  }

  // Looks at the robot from the front and a little above, far enough to see it whole.
  [[nodiscard]] OrbitCamera camera() const {
    OrbitCamera camera;
    camera.target = bounds_.center();
    camera.distance = std::max(1.1f * bounds_.diagonal().norm(), 0.5f);
    return camera;
  }

  void draw(Renderer& renderer, const OrbitCamera& camera, float aspect, bool shadows) const {
    if (shadows) {
      renderer.begin_shadows(camera.target, camera.distance);
      for (const PlacedLink& link : links_) renderer.cast_shadow(link.mesh, link.model);
      renderer.end_shadows();
    }
    renderer.begin(camera.view(), camera.projection(aspect), camera.eye());
    for (const PlacedLink& link : links_) {
      renderer.draw(link.mesh, link.model, link.from_visual ? kVisualLinkColour : kLinkColour);
    }
    // See-through spheres last, so that they do not hide what lies behind them.
    for (const PlacedLink& link : links_) {
      for (const Sphere& s : link.spheres) {
        Eigen::Matrix4f placed = Eigen::Matrix4f::Identity();
        placed.block<3, 3>(0, 0) *= s.radius;
        placed.block<3, 1>(0, 3) = s.center;
        renderer.draw(sphere_, link.model * placed, kSphereColour, kSphereAlpha);
      }
    }
  }

 private:
  std::vector<PlacedLink> links_;
  std::uint32_t sphere_ = 0;
  Eigen::AlignedBox3f bounds_;
};

// The spheres of the file, by link; every link must be the robot's.
std::map<std::string, std::vector<Sphere>> read_spheres(const std::filesystem::path& file,
                                                        const tools::Robot& robot) {
  std::map<std::string, std::vector<Sphere>> spheres;
  for (tools::LinkSpheres& link : tools::read_robot_spheres(file)) {
    const bool known =
        std::any_of(robot.links.begin(), robot.links.end(),
                    [&](const tools::LinkGeometry& g) { return g.link == link.link; });
    if (!known) {
      throw Error::in_file(file, "has spheres for link \"" + link.link + "\", which " +
                                     robot.file.string() + " has not (or it has no geometry)");
    }
    spheres[link.link] = std::move(link.spheres);
  }
  return spheres;
}

}  // namespace

void run_robot_viewer(const RobotViewOptions& options) {
  check_window_size(options.width, options.height);
  // Everything read and checked before a window opens, so that bad input fails fast.
  const tools::Robot robot = tools::load_robot(options.urdf, options.packages);
  const std::map<std::string, tools::Pose3d> poses = tools::link_poses(robot, options.joints);
  const std::map<std::string, std::vector<Sphere>> spheres =
      options.spheres_from ? read_spheres(*options.spheres_from, robot)
                           : std::map<std::string, std::vector<Sphere>>{};
  const Window window(options.width, options.height, options.msaa);
  Renderer renderer;
  const RobotScene scene(renderer, robot, poses, spheres);
  OrbitCamera camera = scene.camera();
  if (options.screenshot) {
    glViewport(0, 0, window.width(), window.height());
    scene.draw(renderer, camera, window.aspect(), options.shadows);
    glFinish();
    write_png(*options.screenshot, window.width(), window.height());
    return;
  }
  const Gui gui(window);
  Input input(window);
  glfwSwapInterval(1);
  while (!window.should_close()) {
    glfwPollEvents();
    input.update(window, gui, camera);
    glViewport(0, 0, window.width(), window.height());
    scene.draw(renderer, camera, window.aspect(), options.shadows);
    glfwSwapBuffers(window.handle());
  }
}

}  // namespace sphys::viewer
