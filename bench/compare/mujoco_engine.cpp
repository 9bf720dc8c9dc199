#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mujoco/mujoco.h>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine.h"
#include "sphys/tools/text_file.h"

namespace sphys::compare {
namespace {

// The scene as MJCF: y up, the plane's normal +y, each bunny a free body with the bunny's mass
// and full inertia tensor at its centre of mass and its leaf spheres as geoms. MuJoCo has no
// coefficient of restitution: its soft contacts keep their defaults (critically damped, no
// bounce); friction 0.5 (sliding). Its defaults elsewhere: the Newton solver, pyramidal friction
// cones; a sparse Jacobian for the many bodies; no sleeping (MuJoCo 2.2 has none).
std::string mjcf(const BenchScene& bench) {
  std::ostringstream xml;
  xml.precision(9);
  const std::size_t bodies = bench.start.size();
  // Room for the contacts of a pile, 40 per bunny (sphys makes 15 to 20 at depth 3), and for 4
  // constraint rows each (pyramidal cones), up to 12,000: MuJoCo 2.2 allocates an njmax² matrix
  // (1.1 GB at 12,000). More are dropped with a warning, which the comparison reports.
  const std::size_t contacts = std::max<std::size_t>(1000, 40 * bodies);
  const std::size_t rows = std::min<std::size_t>(4 * contacts, 12000);
  xml << "<mujoco model=\"bunnies\">\n"
      << "  <option timestep=\"" << bench.time_step
      << "\" gravity=\"0 -9.81 0\" jacobian=\"sparse\"/>\n"
      << "  <size nconmax=\"" << contacts << "\" njmax=\"" << rows << "\"/>\n"
      << "  <default><geom friction=\"" << bench.friction << " 0.005 0.0001\"/></default>\n"
      << "  <worldbody>\n"
      << "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" zaxis=\"0 1 0\"/>\n";
  const Mat3& I = bench.inertia;
  for (const Transform& start : bench.start) {
    const Vec3& p = start.translation;
    const Quat& q = start.rotation;
    xml << "    <body pos=\"" << p.x() << ' ' << p.y() << ' ' << p.z() << "\" quat=\"" << q.w()
        << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << "\">\n"
        << "      <freejoint/>\n"
        << "      <inertial pos=\"0 0 0\" mass=\"" << bench.mass << "\" fullinertia=\"" << I(0, 0)
        << ' ' << I(1, 1) << ' ' << I(2, 2) << ' ' << I(0, 1) << ' ' << I(0, 2) << ' ' << I(1, 2)
        << "\"/>\n";
    for (const Sphere& leaf : bench.leaves) {
      xml << "      <geom type=\"sphere\" size=\"" << leaf.radius << "\" pos=\"" << leaf.center.x()
          << ' ' << leaf.center.y() << ' ' << leaf.center.z() << "\"/>\n";
    }
    xml << "    </body>\n";
  }
  xml << "  </worldbody>\n</mujoco>\n";
  return xml.str();
}

class MujocoEngine final : public Engine {
 public:
  explicit MujocoEngine(const BenchScene& bench) {
    // MuJoCo 2.2 reads models from files; the model goes through a temporary one.
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / "sphys-compare-mujoco.xml";
    tools::write_text_file(file, mjcf(bench));
    std::array<char, 1000> error{};
    model_ = mj_loadXML(file.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
    std::filesystem::remove(file);
    if (model_ == nullptr) throw std::runtime_error(std::string("MuJoCo: ") + error.data());
    data_ = mj_makeData(model_);
    mj_forward(model_, data_);
  }
  ~MujocoEngine() override {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  MujocoEngine(const MujocoEngine&) = delete;
  MujocoEngine& operator=(const MujocoEngine&) = delete;

  void step() override { mj_step(model_, data_); }

  void read(std::vector<BodyState>& out) const override {
    out.clear();
    for (int body = 1; body < model_->nbody; ++body) {  // body 0 is the world
      const mjtNum* p = data_->xpos + 3 * body;
      const mjtNum* q = data_->xquat + 4 * body;
      const mjtNum* r = data_->xmat + 9 * body;  // row-major body-to-world rotation
      const int dof = model_->jnt_dofadr[model_->body_jntadr[body]];
      const mjtNum* v = data_->qvel + dof;  // linear velocity (world), then angular (body frame)
      BodyState state;
      state.pose.translation =
          Vec3(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]));
      state.pose.rotation = Quat(static_cast<float>(q[0]), static_cast<float>(q[1]),
                                 static_cast<float>(q[2]), static_cast<float>(q[3]));
      state.linear_velocity =
          Vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
      for (int row = 0; row < 3; ++row) {
        state.angular_velocity[row] =
            static_cast<float>(r[3 * row] * v[3] + r[3 * row + 1] * v[4] + r[3 * row + 2] * v[5]);
      }
      out.push_back(state);
    }
  }

  [[nodiscard]] std::uint32_t contacts() const override {
    return static_cast<std::uint32_t>(data_->ncon);
  }
  [[nodiscard]] float deepest_penetration() const override {
    mjtNum deepest = 0;
    for (int i = 0; i < data_->ncon; ++i) deepest = std::max(deepest, -data_->contact[i].dist);
    return static_cast<float>(deepest);
  }
  [[nodiscard]] std::string warnings() const override {
    if (data_->warning[mjWARN_CONTACTFULL].number > 0) return "contact list full: contacts dropped";
    if (data_->warning[mjWARN_CNSTRFULL].number > 0)
      return "constraint rows full: contacts dropped";
    return "";
  }

 private:
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
};

}  // namespace

std::unique_ptr<Engine> make_mujoco_engine(const BenchScene& scene) {
  return std::make_unique<MujocoEngine>(scene);
}

}  // namespace sphys::compare
