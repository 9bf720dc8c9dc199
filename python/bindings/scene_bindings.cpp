// Scenes (JSON files and presets), simulations built from them, and recordings as arrays.

#include <Python.h>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/run_summary.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/scene_file.h"
#include "sphys/tools/scene_robots.h"
#include "sphys/tools/tree_cache.h"
#include "sphys/world.h"

namespace sphys::python {
namespace {

using tools::Scene;

// A scene stepped frame by frame: its world, the scene's bodies in order, and the totals
// `sphys simulate` reports.
struct Simulation {
  Scene scene;
  tools::SimulationSetup setup;
  tools::RunTotals totals;
  int frame = 0;
  // The turn of every call on the simulation and on its world, and the world's robots: the
  // scene's, then those World.add_robot adds (bindings.h).
  std::shared_ptr<Turn> turn = std::make_shared<Turn>();
  std::shared_ptr<WorldRobots> robots = std::make_shared<WorldRobots>();
};

// What Simulation() accepts as its scene: a Scene, a dict in the scene-file format, a preset's
// name or a scene file's path.
Scene scene_from(const py::handle& value) {
  if (py::isinstance<Scene>(value)) return value.cast<Scene>();
  if (py::isinstance<py::dict>(value)) {
    return tools::parse_scene(to_json_text(value), "scene.json");
  }
  if (!py::isinstance<py::str>(value) && !py::hasattr(value, "__fspath__")) {
    throw Error(
        "scene must be a Scene, a dict in the scene-file format, a preset's name or a "
        "scene file's path, got " +
        py::repr(value).cast<std::string>());
  }
  return tools::load_scene(spec_from(value, "scene"));
}

// Poses of the scene's bodies, in scene order: (B, 7) position then (x, y, z, w).
py::array_t<float> scene_poses(const Simulation& sim) {
  const auto n = static_cast<py::ssize_t>(sim.setup.bodies.size());
  py::array_t<float> array({n, py::ssize_t{7}});
  auto out = array.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const Transform& pose =
        sim.setup.world->bodies().poses()[sim.setup.bodies[static_cast<std::size_t>(i)].index];
    for (int k = 0; k < 3; ++k) out(i, k) = pose.translation[k];
    for (int k = 0; k < 4; ++k) out(i, 3 + k) = pose.rotation.coeffs()[k];
  }
  return array;
}

// The simulation's world as Python's World holds one, not owning it: whoever holds it keeps the
// simulation alive.
SharedWorld simulation_world(const Simulation& sim) {
  return SharedWorld{std::shared_ptr<World>(std::shared_ptr<World>(), sim.setup.world.get()),
                     sim.turn, sim.robots};
}

// Steps `frames` frames in the caller's turn, without the GIL.
StepStats step_frames(Simulation& sim, int frames) {
  const auto dt = static_cast<float>(sim.scene.time_step);
  StepStats stats;
  for (int i = 0; i < frames; ++i) {
    {
      py::gil_scoped_release unlocked;
      const auto start = std::chrono::steady_clock::now();
      stats = sim.setup.world->step(dt);
      sim.totals.wall_s +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    ++sim.frame;
    if (stats.non_finite_body) {
      throw Error(tools::non_finite_message(sim.setup, *stats.non_finite_body, sim.frame));
    }
    sim.totals.add(stats, sim.setup);
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  return stats;
}

// Steps in one turn: other threads' calls on the simulation or its world wait for all the frames.
StepStats step_simulation(Simulation& sim, int frames) {
  if (frames < 1) throw Error("frames must be at least 1, got " + std::to_string(frames));
  const Turn::Held turn = take_turn(*sim.turn);
  return step_frames(sim, frames);
}

// Read-only strided views of one member of every BodyPose (positions or orientations): no copy.
py::array_t<float> pose_member_view(const py::object& self, bool orientations, py::ssize_t width) {
  const auto& recording = self.cast<const tools::Recording&>();
  const auto frames = static_cast<py::ssize_t>(recording.frame_count);
  const auto bodies = static_cast<py::ssize_t>(recording.body_count);
  constexpr auto stride = static_cast<py::ssize_t>(sizeof(tools::BodyPose));
  static const tools::BodyPose empty;
  const tools::BodyPose& first = recording.poses.empty() ? empty : recording.poses.front();
  py::array_t<float> array(
      {frames, bodies, width}, {stride * bodies, stride, py::ssize_t{sizeof(float)}},
      orientations ? first.orientation.coeffs().data() : first.position.data(), self);
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

// What a recording of a world (RecordingWriter(path, simulation or world)) reads every frame:
// the bodies in order, and the robots some of them belong to, which must stay the world's.
struct RecordedWorld {
  SharedWorld world;
  std::vector<BodyId> bodies;
  std::vector<RobotId> robots;  // in the order the world added them
};

// The Python RecordingWriter: the file, and what its frames are read from when it records a
// world rather than poses it is handed.
struct PythonRecordingWriter {
  std::unique_ptr<tools::RecordingWriter> file;
  std::optional<RecordedWorld> source;
};

// The world's robots still in it, in the order it added them (on the world's turn).
std::vector<RobotId> live_robots(const SharedWorld& world) {
  std::vector<RobotId> robots;
  for (const auto& [id, files] : world.robots->added) {
    if (world.world->robot_alive(id)) robots.push_back(id);
  }
  return robots;
}

// A writer recording `world` as `sphys simulate` records a scene's: `bodies` (the scene's, in
// scene order) with the scene's joints, then every robot's bodies and joints, the robots in the
// order the world added them; the scene it embeds names the robots in that order (their files
// and bases), so that a viewer adds them as the recording keeps them.
std::unique_ptr<PythonRecordingWriter> world_writer(const std::filesystem::path& path,
                                                    const SharedWorld& world, tools::Scene scene,
                                                    std::vector<BodyId> bodies, double time_step) {
  const Turn::Held turn = take_turn(*world.turn);
  RecordedWorld source{world, std::move(bodies), {}};
  std::vector<tools::RecordedJoint> joints = tools::recorded_joints(scene);
  scene.robots.clear();
  for (const auto& [id, files] : world.robots->added) {
    if (!world.world->robot_alive(id)) continue;
    source.robots.push_back(id);
    tools::append_recorded_robot(*world.world, id, source.bodies, joints);
    scene.robots.push_back(files);
  }
  auto writer = std::make_unique<PythonRecordingWriter>();
  writer->file = std::make_unique<tools::RecordingWriter>(
      path, static_cast<std::uint32_t>(source.bodies.size()), time_step,
      tools::recorded_scene_json(scene), joints);
  writer->source = std::move(source);
  return writer;
}

// The scene a recording of a World embeds: no bodies of its own (a World's bodies are not a
// scene's), its settings and ground plane, and its time step between frames.
tools::Scene bare_world_scene(const SharedWorld& world, double time_step) {
  tools::Scene scene;
  scene.name = "world";
  const Turn::Held turn = take_turn(*world.turn);
  const WorldSettings& settings = world.world->settings();
  tools::set_world_settings(scene, settings);
  const std::optional<float> plane = settings.collision.ground_plane_height;
  scene.ground.kind = plane ? tools::GroundSpec::Kind::kPlane : tools::GroundSpec::Kind::kNone;
  scene.ground.height = plane.value_or(0.0F);
  scene.time_step = time_step;
  // A scene's frame count is a run's length, which a world stepped by hand has not: the least a
  // scene allows (the recording's own count is Recording.frame_count).
  scene.frames = 1;
  return scene;
}

// One frame of the recorded world, read on its turn.
void add_world_frame(PythonRecordingWriter& writer) {
  const RecordedWorld& source = *writer.source;
  std::vector<tools::BodyPose> poses;
  {
    const Turn::Held turn = take_turn(*source.world.turn);
    const std::vector<RobotId> robots = live_robots(source.world);
    if (robots != source.robots) {
      throw Error("the world's robots changed since the recording began (" +
                  std::to_string(source.robots.size()) + " then, " + std::to_string(robots.size()) +
                  " now): a recording keeps the bodies it began with; start another one");
    }
    poses = tools::recorded_poses(*source.world.world, source.bodies);
  }
  writer.file->add_frame(poses);
}

// One frame of poses handed over: (B, 7) rows of position then (x, y, z, w).
void add_given_frame(PythonRecordingWriter& writer, const py::handle& value) {
  using Floats = py::array_t<float, py::array::c_style | py::array::forcecast>;
  const Floats poses = Floats::ensure(value);
  if (!poses || poses.ndim() != 2 || poses.shape(1) != 7) {
    throw Error("poses must be an array of shape (B, 7)");
  }
  std::vector<tools::BodyPose> frame(static_cast<std::size_t>(poses.shape(0)));
  const auto p = poses.unchecked<2>();
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const auto row = static_cast<py::ssize_t>(i);
    frame[i].position = Vec3(p(row, 0), p(row, 1), p(row, 2));
    frame[i].orientation = Quat(p(row, 6), p(row, 3), p(row, 4), p(row, 5));
  }
  writer.file->add_frame(frame);
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Scene, std::shared_ptr<Scene>>(
      m, "Scene",
      "What a simulation starts from: bodies, ground and world settings (docs/scenes.md). From "
      "load_scene(), a JSON file, or a dict in the scene-file format (Scene.from_dict).")
      .def_static(
          "from_json",
          [](const std::string& text, const std::string& name) {
            return tools::parse_scene(text, name);
          },
          py::arg("text"), py::arg("name") = "scene.json",
          "A scene from JSON text; relative mesh paths resolve against the folder of `name`.")
      .def_static(
          "from_dict",
          [](const py::dict& scene, const std::string& name) {
            return tools::parse_scene(to_json_text(scene), name);
          },
          py::arg("scene"), py::arg("name") = "scene.json",
          "A scene from a dict of the scene-file format (docs/scenes.md).")
      .def("to_json", &tools::scene_to_json, "The scene as a scene file, every key written out.")
      .def(
          "to_dict", [](const Scene& scene) { return from_json_text(tools::scene_to_json(scene)); },
          "The scene as a dict of the scene-file format: edit it, then Scene.from_dict().")
      .def_readonly("name", &Scene::name,
                    "What the scene is called in messages: its file or preset.")
      .def_property(
          "frames", [](const Scene& s) { return s.frames; },
          [](Scene& s, int frames) {
            if (frames < 1) throw Error("frames must be at least 1, got " + std::to_string(frames));
            s.frames = frames;
          },
          "Frames a run takes, one step each.")
      .def_property_readonly(
          "time_step", [](const Scene& s) { return s.time_step; }, "unit: s")
      .def(
          "__len__", [](const Scene& s) { return s.bodies.size(); }, "The number of bodies.")
      .def_property_readonly(
          "settings", [](const Scene& s) { return settings_dict(tools::world_settings(s)); },
          "The world settings the scene carries, by dotted field.")
      .def(
          "set_settings",
          [](Scene& s, const py::dict& settings) {
            tools::set_world_settings(s, settings_from(settings, tools::world_settings(s)));
          },
          py::arg("settings"),
          "Changes world settings, given as World() takes them ({'solver.soft_substeps': ...}).")
      .def("__repr__", [](const Scene& s) {
        return "<sphys.Scene '" + s.name + "': " + std::to_string(s.bodies.size()) + " bodies, " +
               std::to_string(s.frames) + " frames>";
      });

  m.def(
      "load_scene",
      [](const py::object& spec_object, const std::optional<std::uint64_t>& seed) {
        const std::string spec = spec_from(spec_object, "spec");
        if (!seed) return tools::load_scene(spec);
        if (!tools::is_preset(spec)) {
          throw Error("seed: only the stacks:SxN presets take a seed, not '" + spec + "'");
        }
        return tools::preset_scene(spec, *seed);
      },
      py::arg("spec"), py::kw_only(), py::arg("seed") = std::nullopt,
      "A preset ('stacks:4x50': 4 stacks of 50 bunnies on the paper's octree ground) or a scene "
      "file. `seed` draws a preset's yaw angles (default 2008, the committed layout).");
  m.def("presets", &tools::preset_help, "The preset forms, one line each.");

  py::class_<Simulation>(m, "Simulation",
                         "A scene's world, stepped frame by frame with the figures `sphys "
                         "simulate` reports (summary()). Plausibility figures are on.")
      .def(py::init([](const py::object& scene, std::optional<int> depth, std::uint32_t threads,
                       bool cache) {
             auto sim = std::make_unique<Simulation>();
             sim->scene = scene_from(scene);
             if (depth) {
               for (tools::BodySpec& body : sim->scene.bodies) {
                 if (!body.tree.sph_file) body.tree.depth = *depth;
               }
             }
             tools::BuildWorldOptions options;
             options.tree_depth = depth;
             options.threads = threads;
             options.plausibility_figures = true;
             if (cache) options.cache_dir = tools::default_cache_dir();
             py::gil_scoped_release unlocked;
             sim->setup = tools::build_world(sim->scene, options);
             // As `sphys simulate` adds them.
             const tools::SceneRobots robots =
                 tools::add_scene_robots(sim->scene, *sim->setup.world);
             for (std::size_t k = 0; k < robots.robots.size(); ++k) {
               sim->robots->added.emplace_back(robots.robots[k], sim->scene.robots[k]);
             }
             return sim;
           }),
           py::arg("scene"), py::kw_only(), py::arg("depth") = std::nullopt, py::arg("threads") = 1,
           py::arg("cache") = true,
           "Builds the world of a Scene or of a preset or file name: meshes, mass properties and "
           "sphere-trees (built trees cached as the command line caches them unless cache=False). "
           "depth replaces every built tree's depth; threads as the world's setting (0: all).")
      .def_property_readonly(
          "world",
          // A getter made with keep_alive itself: a property's own extras ignore it.
          py::cpp_function([](const Simulation& sim) { return simulation_world(sim); },
                           py::keep_alive<0, 1>()),
          "The simulation's world; its calls take turns with the simulation's.")
      .def_property_readonly(
          "scene", [](const Simulation& sim) { return sim.scene; },
          "A copy of the scene the simulation was built from (changing it changes nothing).")
      .def_property_readonly(
          "body_ids", [](const Simulation& sim) { return sim.setup.bodies; },
          "The scene's bodies' ids, in scene order.")
      .def_property_readonly(
          "frame",
          [](const Simulation& sim) {
            const Turn::Held turn = take_turn(*sim.turn);
            return sim.frame;
          },
          "Frames stepped so far.")
      .def_property_readonly(
          "time",
          [](const Simulation& sim) {
            const Turn::Held turn = take_turn(*sim.turn);
            return sim.frame * sim.scene.time_step;
          },
          "Simulated time so far. unit: s")
      .def("step", &step_simulation, py::arg("frames") = 1,
           "Steps `frames` frames of the scene's time step with the GIL released; returns the last "
           "StepStats. Raises sphys.Error (with the command line's diagnostic) when the state goes "
           "non-finite.")
      .def(
          "run",
          [](Simulation& sim) {
            const Turn::Held turn = take_turn(*sim.turn);
            if (sim.frame < sim.scene.frames) step_frames(sim, sim.scene.frames - sim.frame);
            return from_json_text(tools::run_summary_json(sim.scene, sim.setup, sim.totals));
          },
          "Steps to the scene's last frame and returns summary().")
      .def(
          "poses",
          [](const Simulation& sim) {
            const Turn::Held turn = take_turn(*sim.turn);
            return scene_poses(sim);
          },
          "(B, 7) float32 of the scene's bodies in scene order: position (m), then orientation "
          "(x, y, z, w). The same numbers as a recording's frame.")
      .def(
          "summary",
          [](const Simulation& sim) {
            const Turn::Held turn = take_turn(*sim.turn);
            return from_json_text(tools::run_summary_json(sim.scene, sim.setup, sim.totals));
          },
          "The figures of `sphys simulate --json` over the frames stepped so far, as a dict.");

  py::class_<tools::Recording>(m, "Recording",
                               "A recording's poses: every body at every frame (.sphysrec).")
      .def_readonly("time_step", &tools::Recording::time_step, "between frames. unit: s")
      .def_readonly("metadata", &tools::Recording::metadata, "the scene as JSON text")
      .def_readonly("body_count", &tools::Recording::body_count, "bodies in every frame")
      .def_readonly("frame_count", &tools::Recording::frame_count, "frames recorded")
      .def_property_readonly(
          "joints",
          [](const tools::Recording& r) {
            py::list joints;
            for (const tools::RecordedJoint& joint : r.joints) {
              py::dict entry;
              entry["type"] = joint.type;
              entry["body_a"] = joint.body_a;
              entry["body_b"] = joint.body_b;
              entry["anchor_a"] =
                  py::make_tuple(joint.anchor_a.x(), joint.anchor_a.y(), joint.anchor_a.z());
              entry["anchor_b"] =
                  py::make_tuple(joint.anchor_b.x(), joint.anchor_b.y(), joint.anchor_b.z());
              joints.append(entry);
            }
            return joints;
          },
          "The joints as dicts: type (JointType), body_a and body_b (body indices, None for the "
          "world), anchor_a and anchor_b (in each body's frame, m); none before version 2.")
      .def_property_readonly(
          "positions", [](const py::object& self) { return pose_member_view(self, false, 3); },
          "(F, B, 3) float32 read-only view: each body's centre of mass per frame. unit: m")
      .def_property_readonly(
          "orientations", [](const py::object& self) { return pose_member_view(self, true, 4); },
          "(F, B, 4) float32 read-only view: unit quaternions (x, y, z, w), body to world.")
      .def_property_readonly(
          "poses",
          [](const tools::Recording& r) {
            py::array_t<float> array({static_cast<py::ssize_t>(r.frame_count),
                                      static_cast<py::ssize_t>(r.body_count), py::ssize_t{7}});
            float* out = array.mutable_data();
            for (const tools::BodyPose& pose : r.poses) {
              for (int k = 0; k < 3; ++k) *out++ = pose.position[k];
              for (int k = 0; k < 4; ++k) *out++ = pose.orientation.coeffs()[k];
            }
            return array;
          },
          "(F, B, 7) float32 copy: positions and orientations side by side.")
      .def(
          "scene",
          [](const tools::Recording& r) {
            return tools::parse_recorded_scene(r.metadata, "recording.json");
          },
          "The scene the recording was made from.");
  m.def(
      "read_recording",
      [](const std::filesystem::path& path) { return tools::read_recording(path); },
      py::arg("path"), py::call_guard<py::gil_scoped_release>(),
      "Reads and checks a .sphysrec file.");

  py::class_<PythonRecordingWriter>(
      m, "RecordingWriter",
      "Writes a .sphysrec frame by frame; the file appears only at finish() (use it as a "
      "context manager: an exception leaves no file). Given a Simulation or a World it records "
      "the world's bodies and joints with its robots, as `sphys simulate` does, so that `sphys "
      "view` replays them; given a body count, the poses add_frame is handed.")
      .def(py::init([](const std::filesystem::path& path, std::uint32_t bodies, double time_step,
                       const std::string& metadata) {
             auto writer = std::make_unique<PythonRecordingWriter>();
             writer->file =
                 std::make_unique<tools::RecordingWriter>(path, bodies, time_step, metadata);
             return writer;
           }),
           py::arg("path"), py::arg("bodies"), py::arg("time_step"), py::arg("metadata") = "",
           "`bodies` poses a frame, handed to add_frame; time_step between frames (s); metadata: "
           "the scene as JSON (Scene.to_json()) for the viewer.")
      .def(py::init([](const std::filesystem::path& path, const Simulation& sim,
                       std::optional<double> time_step) {
             return world_writer(path, simulation_world(sim), sim.scene, sim.setup.bodies,
                                 time_step.value_or(sim.scene.time_step));
           }),
           py::arg("path"), py::arg("simulation"), py::arg("time_step") = py::none(),
           py::keep_alive<1, 3>(),
           "Records the simulation as `sphys simulate` does, frame by frame at add_frame(): the "
           "scene's bodies in scene order, then every robot's bodies (the scene's robots, then "
           "those World.add_robot added, each its root link's body first, then the link of each "
           "joint), with the scene's joints, then the robots'; the scene embedded names the "
           "robots, so that `sphys view` draws their links. time_step: between frames (s), the "
           "scene's by default. Bodies added with World.add_body are not recorded.")
      .def(py::init([](const std::filesystem::path& path, const SharedWorld& world,
                       double time_step) {
             return world_writer(path, world, bare_world_scene(world, time_step), {}, time_step);
           }),
           py::arg("path"), py::arg("world"), py::arg("time_step"), py::keep_alive<1, 3>(),
           "Records the world's robots (World.add_robot), as the Simulation form does, in a "
           "scene of no bodies with the world's settings and ground plane: bodies added with "
           "World.add_body are not recorded, as a recording names each body's shape by its "
           "scene. time_step: between frames (s).")
      .def(
          "add_frame",
          [](PythonRecordingWriter& writer, const py::object& poses) {
            if (poses.is_none() && !writer.source) {
              throw Error("add_frame needs the poses of this writer's bodies, (B, 7)");
            }
            if (!poses.is_none() && writer.source) {
              throw Error("this writer records its world's poses: call add_frame() without poses");
            }
            if (writer.source) {
              add_world_frame(writer);
            } else {
              add_given_frame(writer, poses);
            }
          },
          py::arg("poses") = py::none(),
          "One frame: of a writer of a Simulation or a World, the world as it is now (no "
          "poses); else the (B, 7) poses given, as Simulation.poses() gives them. sphys.Error, "
          "writing nothing, for poses of another shape, a value that is not finite, or a world "
          "whose robots changed since the recording began.")
      .def(
          "finish", [](PythonRecordingWriter& writer) { writer.file->finish(); },
          "Moves the file into place. Once only: nothing can follow.")
      .def(
          "__enter__",
          [](PythonRecordingWriter& writer) -> PythonRecordingWriter& { return writer; },
          py::return_value_policy::reference)
      .def("__exit__", [](PythonRecordingWriter& writer, const py::object& type, const py::object&,
                          const py::object&) {
        if (type.is_none() && !writer.file->finished()) writer.file->finish();
        return false;
      });
}

}  // namespace sphys::python
