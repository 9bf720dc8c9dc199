// Worlds: settings, bodies, stepping (the GIL released), poses, velocities and contacts as arrays.

#include <Python.h>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "sphys/settings_table.h"
#include "sphys/tools/setting_text.h"
#include "sphys/world.h"

namespace sphys::python {
namespace {

// Settings nested in sub-mappings flattened to dotted fields.
void flatten(const py::handle& mapping, const std::string& prefix,
             std::vector<std::pair<std::string, py::object>>& out) {
  if (!py::isinstance<py::dict>(mapping)) throw Error("settings must be a dict");
  for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(mapping)) {
    const std::string name = prefix + py::str(key).cast<std::string>();
    if (py::isinstance<py::dict>(value)) {
      flatten(value, name + ".", out);
    } else {
      out.emplace_back(name, py::reinterpret_borrow<py::object>(value));
    }
  }
}

const Setting* find_setting(std::string_view field) {
  for (const Setting& setting : settings_table()) {
    if (setting.field == field) return &setting;
  }
  return nullptr;
}

// A Python value as the command line's text for set_setting_from_text: repr() of a float is the
// shortest text that reads back to the same double.
std::string setting_text(const py::object& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) {
    return py::repr(value).cast<std::string>();
  }
  // numpy scalars and the like: their float, else their text, which the table then refuses.
  try {
    return py::repr(py::float_(value)).cast<std::string>();
  } catch (const py::error_already_set&) {
    return py::str(value).cast<std::string>();
  }
}

py::array_t<float> rows_of(const World& world, const std::vector<std::uint32_t>& slots, int columns,
                           bool poses) {
  py::array_t<float> array(
      {static_cast<py::ssize_t>(slots.size()), static_cast<py::ssize_t>(columns)});
  auto out = array.mutable_unchecked<2>();
  const BodyStore& store = world.bodies();
  for (std::size_t row = 0; row < slots.size(); ++row) {
    const auto i = static_cast<py::ssize_t>(row);
    const std::uint32_t slot = slots[row];
    if (poses) {
      const Transform& pose = store.poses()[slot];
      for (int k = 0; k < 3; ++k) out(i, k) = pose.translation[k];
      // (x, y, z, w): scalar last.
      for (int k = 0; k < 4; ++k) out(i, 3 + k) = pose.rotation.coeffs()[k];
    } else {
      for (int k = 0; k < 3; ++k) {
        out(i, k) = store.linear_velocities()[slot][k];
        out(i, 3 + k) = store.angular_velocities()[slot][k];
      }
    }
  }
  return array;
}

// The slots of the given bodies, or of every body in the world in slot order.
std::vector<std::uint32_t> slots_of(const World& world,
                                    const std::optional<std::vector<BodyId>>& ids) {
  std::vector<std::uint32_t> slots;
  if (ids) {
    for (const BodyId id : *ids) slots.push_back(world.slot_of(id));
    return slots;
  }
  for (std::uint32_t slot = 0; slot < world.body_slots(); ++slot) {
    if (world.alive(world.id_of(slot))) slots.push_back(slot);
  }
  return slots;
}

// Steps `steps` times without the GIL, in one turn; between steps, takes the GIL back to let
// Ctrl-C through.
StepStats step_world(SharedWorld& shared, float dt, int steps) {
  if (steps < 1) throw Error("steps must be at least 1, got " + std::to_string(steps));
  const Turn::Held turn = take_turn(*shared.turn);
  World& world = *shared.world;
  StepStats stats;
  for (int i = 0; i < steps; ++i) {
    {
      py::gil_scoped_release unlocked;
      stats = world.step(dt);
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (world.stopped()) break;
  }
  return stats;
}

// A figure of StepStats as Python has it: an int for a count, else a float.
py::object figure_value(const StepFigure& figure, const StepStats& stats) {
  const double value = figure.read(stats);
  if (figure.count) return py::int_(static_cast<std::uint64_t>(value));
  return py::float_(value);
}

// A world call that applies a vector (`what`: "impulse", "force") at a world point to a body, as
// Python calls it: the vectors read and checked, then the call on its turn.
template <void (World::*Apply)(BodyId, const Vec3&, const Vec3&)>
auto applied_at_point(const char* what) {
  return [what](SharedWorld& w, BodyId body, const py::object& vector, const py::object& point) {
    const Vec3 applied = vec3_from(vector, what);
    const Vec3 at = vec3_from(point, "point");
    const Turn::Held turn = take_turn(*w.turn);
    (w.world.get()->*Apply)(body, applied, at);
  };
}

py::dict stats_dict(const StepStats& s) {
  py::dict d;
  for (const StepFigure& figure : step_figures()) d[py::str(figure.name)] = figure_value(figure, s);
  d["non_finite_body"] =
      s.non_finite_body ? py::object(py::int_(*s.non_finite_body)) : py::object(py::none());
  return d;
}

}  // namespace

bool Turn::try_take() {
  const std::lock_guard lock(mutex_);
  if (taken_) return false;
  taken_ = true;
  return true;
}

bool Turn::take_within(std::chrono::milliseconds wait) {
  std::unique_lock lock(mutex_);
  if (!freed_.wait_for(lock, wait, [&] { return !taken_; })) return false;
  taken_ = true;
  return true;
}

void Turn::give_back() {
  {
    const std::lock_guard lock(mutex_);
    taken_ = false;
  }
  freed_.notify_one();
}

Turn::Held take_turn(Turn& turn) {
  // How long a wait lasts before Ctrl-C is looked at. unit: ms
  constexpr std::chrono::milliseconds kSignalCheck(50);
  bool taken = turn.try_take();
  while (!taken) {
    {
      const py::gil_scoped_release unlocked;
      taken = turn.take_within(kSignalCheck);
    }
    if (!taken && PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  return Turn::Held(turn);
}

WorldSettings settings_from(const py::handle& mapping, WorldSettings base) {
  std::vector<std::pair<std::string, py::object>> fields;
  flatten(mapping, "", fields);
  for (const auto& [field, value] : fields) {
    const Setting* setting = find_setting(field);
    if (setting != nullptr && setting->kind == SettingKind::kVector3) {
      setting->set_vector(base, vec3_from(value, setting->field.data()));
    } else {
      set_setting_from_text(base, field, setting_text(value), "settings");
    }
  }
  check_world_settings(base);
  return base;
}

py::dict settings_dict(const WorldSettings& settings) {
  py::dict d;
  for (const Setting& setting : settings_table()) {
    const std::string field(setting.field);
    switch (setting.kind) {
      case SettingKind::kVector3: {
        const Vec3 v = setting.get_vector(settings);
        d[field.c_str()] =
            py::make_tuple(shortest_double(v.x()), shortest_double(v.y()), shortest_double(v.z()));
        break;
      }
      case SettingKind::kBool:
        d[field.c_str()] = setting.get(settings) != 0.0;
        break;
      case SettingKind::kEnum:
        d[field.c_str()] =
            std::string(setting.choices[static_cast<std::size_t>(setting.get(settings))]);
        break;
      case SettingKind::kInteger:
        d[field.c_str()] = static_cast<std::uint64_t>(setting.get(settings));
        break;
      case SettingKind::kNumber:
        d[field.c_str()] = setting.get(settings);
        break;
    }
  }
  return d;
}

void bind_world(py::module_& m) {
  m.attr("GROUND_PLANE_BODY") = kGroundPlaneBody;
  bind_slot_id<BodyTag>(m, "BodyId",
                        "A body of a world: its slot and the slot's generation (from 1). "
                        "BodyId() is the null id, which names no body: a world refuses it.",
                        "The body's slot in its world's body store.",
                        "The slot's generation, from 1 (0: the null id); a removed body's slot "
                        "takes the next one.",
                        "True for BodyId(), which names no body.");

  py::class_<StepStats> step_stats(
      m, "StepStats",
      "Figures of one step; times in ms, penetrations in m, energy in J. The plausibility figures "
      "need the world's plausibility_figures setting.");
  for (const StepFigure& figure : step_figures()) {
    const std::string doc = figure.unit.empty() ? "a count" : "unit: " + std::string(figure.unit);
    step_stats.def_property_readonly(
        std::string(figure.name).c_str(),
        [figure](const StepStats& s) { return figure_value(figure, s); }, doc.c_str());
  }
  step_stats
      .def_readonly("non_finite_body", &StepStats::non_finite_body,
                    "The slot of the first body whose state stopped being finite in this step "
                    "(the world steps no more), or None.")
      .def("to_dict", &stats_dict, "Every figure by name (the names of sphys/step_stats.h).")
      .def("__repr__", [](const StepStats& s) {
        return "<sphys.StepStats " + std::to_string(s.step_ms) + " ms, " +
               std::to_string(s.contacts) + " contacts>";
      });

  m.def(
      "settings_table",
      [] {
        py::list rows;
        const py::dict defaults = settings_dict(WorldSettings{});
        for (const Setting& setting : settings_table()) {
          py::dict row;
          row["field"] = std::string(setting.field);
          row["unit"] = std::string(setting.unit);
          row["valid"] = range_text(setting);
          row["default"] = defaults[std::string(setting.field).c_str()];
          row["doc"] = std::string(setting.doc);
          rows.append(row);
        }
        return rows;
      },
      "Every world setting: its field, unit, valid values, default and what it does.");

  // Every method takes the world's turn first (take_turn); step holds it for all its steps.
  py::class_<SharedWorld>(m, "World",
                          "A world of rigid bodies with sphere-trees. Settings are keyword "
                          "arguments named as in scene files, nested for the solver and sleep "
                          "(World(gravity=(0, -9.81, 0), solver={'soft_substeps': 8})); see "
                          "settings_table(). ground_plane: height (m) of an exact ground plane, or "
                          "None. Any thread may call it: calls take turns (docs/python.md).")
      .def(py::init([](const py::object& ground_plane, const py::kwargs& settings) {
             WorldSettings world_settings = settings_from(settings, WorldSettings{});
             if (!ground_plane.is_none()) {
               // Any real number (numpy's included), not a bool or a str.
               const py::object real = py::module_::import("numbers").attr("Real");
               if (py::isinstance<py::bool_>(ground_plane) || !py::isinstance(ground_plane, real)) {
                 throw Error("ground_plane must be a height (m) or None, got " +
                             py::repr(ground_plane).cast<std::string>());
               }
               const auto height = py::float_(ground_plane).cast<double>();
               if (!std::isfinite(height)) throw Error("ground_plane must be finite or None");
               world_settings.collision.ground_plane_height = static_cast<float>(height);
             }
             return SharedWorld{std::make_shared<World>(world_settings)};
           }),
           py::kw_only(), py::arg("ground_plane") = py::none(),
           "A world of the given settings (see the class) and ground plane height (m) or None.")
      .def_property_readonly(
          "settings",
          [](const SharedWorld& w) {
            const Turn::Held turn = take_turn(*w.turn);
            return settings_dict(w.world->settings());
          },
          "Every setting by its dotted field.")
      .def_property_readonly(
          "solver_lanes",
          [](const SharedWorld& w) {
            return std::string(solver_lanes_name(w.world->solver_lanes()));
          },
          "The SIMD instructions solver.lanes resolved to on this processor: 'avx2', 'sse2' or "
          "'portable' (fixed when the world is made).")
      .def_property_readonly(
          "ground_plane",
          [](const SharedWorld& w) {
            const Turn::Held turn = take_turn(*w.turn);
            return w.world->settings().collision.ground_plane_height;
          },
          "Height of the exact ground plane (m), or None.")
      .def(
          "add_body",
          [](SharedWorld& w, const std::shared_ptr<SphereTree>& tree, const py::object& position,
             const py::object& orientation, const py::object& linear_velocity,
             const py::object& angular_velocity, float mass, const py::object& inertia,
             float restitution, float friction, bool is_static) {
            BodyDesc desc;
            desc.tree = tree;
            desc.pose.translation = vec3_from(position, "position");
            desc.pose.rotation = quat_from(orientation, "orientation");
            desc.linear_velocity = vec3_from(linear_velocity, "linear_velocity");
            desc.angular_velocity = vec3_from(angular_velocity, "angular_velocity");
            desc.mass = mass;
            if (!inertia.is_none()) {
              const auto rows =
                  py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(inertia);
              if (!rows || rows.ndim() != 2 || rows.shape(0) != 3 || rows.shape(1) != 3) {
                throw Error("inertia must be a 3x3 matrix (kg·m²)");
              }
              for (int r = 0; r < 3; ++r) {
                for (int c = 0; c < 3; ++c) desc.inertia(r, c) = static_cast<float>(rows.at(r, c));
              }
            }
            desc.restitution = restitution;
            desc.friction = friction;
            desc.is_static = is_static;
            const Turn::Held turn = take_turn(*w.turn);
            return w.world->add_body(desc);
          },
          py::arg("tree"), py::kw_only(), py::arg("position") = py::make_tuple(0, 0, 0),
          py::arg("orientation") = py::make_tuple(0, 0, 0, 1),
          py::arg("linear_velocity") = py::make_tuple(0, 0, 0),
          py::arg("angular_velocity") = py::make_tuple(0, 0, 0), py::arg("mass") = 1.0f,
          py::arg("inertia") = py::none(), py::arg("restitution") = BodyDesc{}.restitution,
          py::arg("friction") = BodyDesc{}.friction, py::arg("static") = false,
          "Adds a body whose sphere-tree is in its body frame (origin at the centre of mass). "
          "position (m); orientation a unit quaternion (x, y, z, w); velocities in m/s and rad/s "
          "(world frame); mass (kg); inertia 3x3 about the centre of mass in body axes (kg·m², "
          "identity if None); restitution 0..1; friction >= 0. Returns its BodyId.")
      .def(
          "remove_body",
          [](SharedWorld& w, BodyId body) {
            const Turn::Held turn = take_turn(*w.turn);
            w.world->remove_body(body);
          },
          py::arg("body"),
          "Removes a body; its id names no body from then on (sphys.Error for a stale id).")
      .def(
          "alive",
          [](const SharedWorld& w, BodyId body) {
            const Turn::Held turn = take_turn(*w.turn);
            return w.world->alive(body);
          },
          py::arg("body"), "Whether the id names a body of the world now.")
      .def(
          "asleep",
          [](const SharedWorld& w, BodyId body) {
            const Turn::Held turn = take_turn(*w.turn);
            return w.world->asleep(body);
          },
          py::arg("body"),
          "Whether the body sleeps: at rest, not simulated until something touches it.")
      .def(
          "body_ids",
          [](const SharedWorld& w) {
            const Turn::Held turn = take_turn(*w.turn);
            std::vector<BodyId> ids;
            for (const std::uint32_t slot : slots_of(*w.world, std::nullopt))
              ids.push_back(w.world->id_of(slot));
            return ids;
          },
          "The bodies in the world, in the order of poses() and velocities().")
      .def("__len__",
           [](const SharedWorld& w) {
             const Turn::Held turn = take_turn(*w.turn);
             return slots_of(*w.world, std::nullopt).size();
           })
      .def(
          "set_velocity",
          [](SharedWorld& w, BodyId body, const py::object& linear, const py::object& angular) {
            const Vec3 v = vec3_from(linear, "linear");
            const Vec3 omega = vec3_from(angular, "angular");
            const Turn::Held turn = take_turn(*w.turn);
            w.world->set_velocity(body, v, omega);
          },
          py::arg("body"), py::arg("linear"), py::arg("angular") = py::make_tuple(0, 0, 0),
          "Sets a body's velocities (m/s, rad/s, world frame) and wakes it.")
      .def("apply_impulse", applied_at_point<&World::apply_impulse>("impulse"), py::arg("body"),
           py::arg("impulse"), py::arg("point"),
           "An impulse (N·s, world frame) at a world point (m); wakes the body.")
      .def("apply_force", applied_at_point<&World::apply_force>("force"), py::arg("body"),
           py::arg("force"), py::arg("point"),
           "A force (N, world frame) at a world point (m) through the next step, as gravity acts; "
           "forces add up until the step, which ends them. Wakes the body.")
      .def(
          "apply_torque",
          [](SharedWorld& w, BodyId body, const py::object& torque) {
            const Vec3 t = vec3_from(torque, "torque");
            const Turn::Held turn = take_turn(*w.turn);
            w.world->apply_torque(body, t);
          },
          py::arg("body"), py::arg("torque"),
          "A torque (N·m, world frame) through the next step, as apply_force.")
      .def(
          "set_pair_material",
          [](SharedWorld& w, BodyId a, BodyId b, float friction, float restitution) {
            if (a == b) throw Error("set_pair_material: a and b are the same body");
            const Turn::Held turn = take_turn(*w.turn);
            w.world->set_pair_material(a, b, PairMaterial{friction, restitution});
          },
          py::arg("a"), py::arg("b"), py::kw_only(), py::arg("friction"), py::arg("restitution"),
          "The friction (>= 0) and restitution (0..1) of contacts between two bodies.")
      .def("step", &step_world, py::arg("dt") = 1.0 / 60.0, py::arg("steps") = 1,
           "Advances the world `steps` times by dt (s) with the GIL released, in one turn: other "
           "threads' calls wait for all the steps; returns the last step's StepStats. Ctrl-C stops "
           "between steps. A world whose state went non-finite stops (StepStats.non_finite_body "
           "says which body).")
      .def_property_readonly(
          "stats",
          [](const SharedWorld& w) {
            const Turn::Held turn = take_turn(*w.turn);
            return w.world->stats();
          },
          "The last step's StepStats.")
      .def_property_readonly(
          "stopped",
          [](const SharedWorld& w) {
            const Turn::Held turn = take_turn(*w.turn);
            return w.world->stopped();
          },
          "True once the state went non-finite.")
      .def(
          "poses",
          [](const SharedWorld& w, const std::optional<std::vector<BodyId>>& ids) {
            const Turn::Held turn = take_turn(*w.turn);
            return rows_of(*w.world, slots_of(*w.world, ids), 7, true);
          },
          py::arg("ids") = std::nullopt,
          "(N, 7) float32: position (m) then orientation (x, y, z, w) of the given bodies, or of "
          "every body in body_ids() order. A copy: it does not change as the world steps.")
      .def(
          "velocities",
          [](const SharedWorld& w, const std::optional<std::vector<BodyId>>& ids) {
            const Turn::Held turn = take_turn(*w.turn);
            return rows_of(*w.world, slots_of(*w.world, ids), 6, false);
          },
          py::arg("ids") = std::nullopt,
          "(N, 6) float32: linear (m/s) then angular (rad/s) velocity, world frame.")
      .def(
          "contacts",
          [](const SharedWorld& w) {
            const Turn::Held turn = take_turn(*w.turn);
            const auto contacts = w.world->contacts();
            const auto n = static_cast<py::ssize_t>(contacts.size());
            py::array_t<std::uint32_t> bodies({n, py::ssize_t{2}});
            py::array_t<float> points({n, py::ssize_t{3}});
            py::array_t<float> normals({n, py::ssize_t{3}});
            py::array_t<float> depths({n});
            auto b = bodies.mutable_unchecked<2>();
            auto p = points.mutable_unchecked<2>();
            auto nn = normals.mutable_unchecked<2>();
            auto d = depths.mutable_unchecked<1>();
            for (py::ssize_t i = 0; i < n; ++i) {
              const Contact& c = contacts[static_cast<std::size_t>(i)];
              b(i, 0) = c.body_a;
              b(i, 1) = c.body_b;
              for (int k = 0; k < 3; ++k) {
                p(i, k) = c.point[k];
                nn(i, k) = c.normal[k];
              }
              d(i) = c.depth;
            }
            py::dict out;
            out["bodies"] = bodies;
            out["points"] = points;
            out["normals"] = normals;
            out["depths"] = depths;
            return out;
          },
          "The last step's contacts as arrays: bodies (K, 2) uint32 body indices (BodyId.index; "
          "GROUND_PLANE_BODY for the ground plane), points (K, 3) m, normals (K, 3) unit vectors "
          "from the first body to the second, "
          "depths (K,) m.")
      .def(
          "set_detection_budget",
          [](SharedWorld& w, std::uint64_t max_sphere_tests, double max_microseconds) {
            const Turn::Held turn = take_turn(*w.turn);
            w.world->set_detection_budget(max_sphere_tests, max_microseconds);
          },
          py::arg("max_sphere_tests"), py::arg("max_microseconds"),
          "The narrow phase's budgets from the next step on; 0 turns one off.");
}

}  // namespace sphys::python
