// Queries: ray casts, overlaps, distances and batched configuration checks, numpy in and out
// (the GIL released while many rays or configurations run).

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "sphys/configuration_check.h"
#include "sphys/world.h"
#include "sphys/world_query.h"

namespace sphys::python {
namespace {

using FloatRows = py::array_t<float, py::array::c_style | py::array::forcecast>;

// A ray's reach when none is given, and the distance of a miss. unit: m
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// A float32 C-contiguous copy or view of `value` whose shape is `shape` (-1: any extent);
// sphys::Error naming `what` and the shape expected otherwise.
FloatRows float_array(const py::handle& value, const char* what,
                      const std::vector<py::ssize_t>& shape, const char* expected) {
  FloatRows array = FloatRows::ensure(value);
  bool fits = array && array.ndim() == static_cast<py::ssize_t>(shape.size());
  for (std::size_t k = 0; fits && k < shape.size(); ++k) {
    fits = shape[k] < 0 || array.shape(static_cast<py::ssize_t>(k)) == shape[k];
  }
  if (!fits) {
    std::string got = "a value that is no array of numbers";
    if (array) {
      got = "shape (";
      for (py::ssize_t k = 0; k < array.ndim(); ++k) {
        got += (k > 0 ? ", " : "") + std::to_string(array.shape(k));
      }
      got += ")";
    }
    throw Error(std::string(what) + " must be " + expected + ", got " + got);
  }
  return array;
}

py::dict hit_dict(const RayHit& hit) {
  py::dict d;
  d["body"] = hit.body;
  d["leaf"] = hit.leaf;
  d["point"] = py::make_tuple(hit.point.x(), hit.point.y(), hit.point.z());
  d["normal"] = py::make_tuple(hit.normal.x(), hit.normal.y(), hit.normal.z());
  d["distance"] = hit.distance;
  return d;
}

py::dict distance_dict(const DistanceResult& r) {
  py::dict d;
  d["distance"] = r.distance;
  d["leaf_a"] = r.leaf_a;
  d["leaf_b"] = r.leaf_b;
  d["point_a"] = py::make_tuple(r.point_a.x(), r.point_a.y(), r.point_a.z());
  d["point_b"] = py::make_tuple(r.point_b.x(), r.point_b.y(), r.point_b.z());
  d["exact"] = r.exact;
  d["sphere_tests"] = r.sphere_tests;
  return d;
}

Ray ray_from(const py::object& origin, const py::object& direction, float max_distance) {
  // NaN and zero-length directions are the query's to refuse, naming ray.direction.
  Ray ray;
  const FloatRows o = float_array(origin, "origin", {3}, "3 numbers");
  const FloatRows d = float_array(direction, "direction", {3}, "3 numbers");
  ray.origin = Vec3(o.at(0), o.at(1), o.at(2));
  ray.direction = Vec3(d.at(0), d.at(1), d.at(2));
  ray.max_distance = max_distance;
  return ray;
}

// The batched check: spheres (N, S, 4), links (S,). Returns free, sphere, body, other_sphere.
py::dict check_configurations(const WorldQuery& query, const py::object& spheres,
                              const py::object& links, bool self_collision,
                              const std::vector<std::array<std::int32_t, 2>>& allowed_pairs,
                              const QueryFilter& filter, int tree_depth, std::uint32_t threads) {
  const FloatRows rows =
      float_array(spheres, "spheres", {-1, -1, 4}, "an (N, S, 4) array of x, y, z, radius (m)");
  const auto link_array =
      py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>::ensure(links);
  if (!link_array || link_array.ndim() != 1 || link_array.shape(0) != rows.shape(1)) {
    throw Error("links must be " + std::to_string(rows.shape(1)) +
                " link indices, one per sphere (spheres is (N, S, 4))");
  }
  ConfigurationCheckSettings settings;
  settings.filter = filter;
  settings.self_collision = self_collision;
  settings.allowed_link_pairs = allowed_pairs;
  settings.tree_depth = tree_depth;
  const ConfigurationChecker checker(
      query, std::vector<std::int32_t>(link_array.data(), link_array.data() + link_array.size()),
      settings);
  const auto count = static_cast<std::size_t>(rows.shape(0));
  std::vector<ConfigurationResult> results(count);
  {
    py::gil_scoped_release unlocked;
    const Parallel parallel(threads);
    checker.check(std::span(rows.data(), static_cast<std::size_t>(rows.size())), results,
                  &parallel);
  }
  return configuration_results_dict(results);
}

constexpr const char* kCheckDoc =
    "Checks N configurations of S spheres at once: spheres (N, S, 4) float32 (x, y, z, radius in "
    "m, world frame), links (S,) each sphere's link. With self_collision, spheres of different "
    "links not listed in allowed_pairs ((a, b) link pairs) count too. tree_depth: the levels of "
    "the bodies' trees to answer at, deeper than the world's (0: the world's). Runs on `threads` "
    "threads "
    "with the GIL released. Returns a dict of (N,) arrays: free (bool), sphere (the first "
    "colliding sphere, -1), body (the slot of a body it touches, -1), other_sphere "
    "(self-collision: "
    "the sphere it touches, -1).";

}  // namespace

py::dict configuration_results_dict(std::span<const ConfigurationResult> results) {
  const auto n = static_cast<py::ssize_t>(results.size());
  py::array_t<bool> free({n});
  py::array_t<std::int32_t> sphere({n});
  py::array_t<std::int32_t> body({n});
  py::array_t<std::int32_t> other({n});
  for (std::size_t i = 0; i < results.size(); ++i) {
    free.mutable_data()[i] = results[i].free;
    sphere.mutable_data()[i] = results[i].sphere;
    body.mutable_data()[i] = results[i].body;
    other.mutable_data()[i] = results[i].other_sphere;
  }
  py::dict d;
  d["free"] = free;
  d["sphere"] = sphere;
  d["body"] = body;
  d["other_sphere"] = other;
  return d;
}

SharedQuery::SharedQuery(SharedWorld world) : world_(std::move(world)) { refresh(); }

std::shared_ptr<const WorldQuery> SharedQuery::current() const {
  const std::lock_guard lock(swap_);
  return query_;
}

void SharedQuery::refresh() {
  std::shared_ptr<const WorldQuery> fresh;
  {
    const Turn::Held turn = take_turn(*world_.turn);
    fresh = std::make_shared<const WorldQuery>(*world_.world);
  }
  const std::lock_guard lock(swap_);
  query_.swap(fresh);  // the old snapshot goes with `fresh` once its last query is done
}

void bind_query(py::module_& m) {
  py::class_<QueryFilter>(m, "QueryFilter",
                          "Which bodies a query sees: not those in skip, only those whose category "
                          "bits (categories[slot], 1 past its end) share a bit with mask, and no "
                          "sleeping one with skip_sleeping.")
      .def(py::init([](std::vector<BodyId> skip, std::uint32_t mask,
                       std::vector<std::uint32_t> categories, bool skip_sleeping) {
             return QueryFilter{std::move(skip), mask, std::move(categories), skip_sleeping};
           }),
           py::kw_only(), py::arg("skip") = std::vector<BodyId>{}, py::arg("mask") = ~0u,
           py::arg("categories") = std::vector<std::uint32_t>{}, py::arg("skip_sleeping") = false,
           "A filter; every argument as the attribute of its name.")
      .def_readwrite("skip", &QueryFilter::skip,
                     "BodyIds left out; each must be in the world (else sphys.Error).")
      .def_readwrite("mask", &QueryFilter::mask,
                     "A body is seen when its category bits share a bit with this.")
      .def_readwrite("categories", &QueryFilter::categories,
                     "Category bits per body slot; a body whose slot is past its end is in "
                     "category 1.")
      .def_readwrite("skip_sleeping", &QueryFilter::skip_sleeping,
                     "True leaves sleeping bodies out.");

  py::class_<SharedQuery>(m, "WorldQuery",
                          "Questions asked of a world's leaf spheres without stepping it, as the "
                          "world was when made or last refreshed (refresh() after stepping). "
                          "Once made, any number of threads may query it at once, while the "
                          "world steps; refresh() takes the world's turn.")
      .def(py::init([](const SharedWorld& world) { return std::make_unique<SharedQuery>(world); }),
           py::arg("world"), py::keep_alive<1, 2>(), "A query of `world` as it is now.")
      .def("refresh", &SharedQuery::refresh,
           "Reads the world again (in its turn): later queries see it as it is now; one "
           "running meanwhile finishes on what it started with.")
      .def(
          "cast_ray",
          [](const SharedQuery& shared, const py::object& origin, const py::object& direction,
             float max_distance, const QueryFilter& filter) -> py::object {
            const std::shared_ptr<const WorldQuery> q = shared.current();
            const std::optional<RayHit> hit =
                q->cast_ray(ray_from(origin, direction, max_distance), filter);
            return hit ? py::object(hit_dict(*hit)) : py::object(py::none());
          },
          py::arg("origin"), py::arg("direction"), py::arg("max_distance") = kInfinity,
          py::arg("filter") = QueryFilter{},
          "The nearest hit as a dict (body, leaf, point, normal, distance in m) or None.")
      .def(
          "cast_ray_all",
          [](const SharedQuery& shared, const py::object& origin, const py::object& direction,
             float max_distance, const QueryFilter& filter) {
            const std::shared_ptr<const WorldQuery> q = shared.current();
            py::list hits;
            for (const RayHit& hit :
                 q->cast_ray_all(ray_from(origin, direction, max_distance), filter)) {
              hits.append(hit_dict(hit));
            }
            return hits;
          },
          py::arg("origin"), py::arg("direction"), py::arg("max_distance") = kInfinity,
          py::arg("filter") = QueryFilter{}, "Every body hit, once at its nearest, nearest first.")
      .def(
          "cast_rays",
          [](const SharedQuery& shared, const py::object& origins, const py::object& directions,
             float max_distance, const QueryFilter& filter, std::uint32_t threads) {
            const std::shared_ptr<const WorldQuery> q = shared.current();
            const FloatRows o = float_array(origins, "origins", {-1, 3}, "an (N, 3) array (m)");
            const FloatRows d =
                float_array(directions, "directions", {o.shape(0), 3}, "an (N, 3) array");
            const auto n = static_cast<std::size_t>(o.shape(0));
            std::vector<Ray> rays(n);
            for (std::size_t i = 0; i < n; ++i) {
              rays[i].origin = Vec3(o.data()[3 * i], o.data()[3 * i + 1], o.data()[3 * i + 2]);
              rays[i].direction = Vec3(d.data()[3 * i], d.data()[3 * i + 1], d.data()[3 * i + 2]);
              rays[i].max_distance = max_distance;
            }
            std::vector<std::optional<RayHit>> hits(n);
            {
              py::gil_scoped_release unlocked;
              const Parallel parallel(threads);
              q->cast_rays(rays, filter, hits, &parallel);
            }
            const auto rows = static_cast<py::ssize_t>(n);
            py::array_t<std::int32_t> body({rows});
            py::array_t<float> distance({rows});
            py::array_t<float> point({rows, py::ssize_t{3}});
            py::array_t<float> normal({rows, py::ssize_t{3}});
            for (std::size_t i = 0; i < n; ++i) {
              const RayHit hit = hits[i].value_or(RayHit{});
              body.mutable_data()[i] = hits[i] ? static_cast<std::int32_t>(hit.body.index) : -1;
              distance.mutable_data()[i] = hits[i] ? hit.distance : kInfinity;
              for (int k = 0; k < 3; ++k) {
                point.mutable_data()[3 * i + k] = hit.point[k];
                normal.mutable_data()[3 * i + k] = hit.normal[k];
              }
            }
            py::dict out;
            out["body"] = body;
            out["distance"] = distance;
            out["point"] = point;
            out["normal"] = normal;
            return out;
          },
          py::arg("origins"), py::arg("directions"), py::arg("max_distance") = kInfinity,
          py::arg("filter") = QueryFilter{}, py::arg("threads") = 1,
          "Nearest hits of N rays ((N, 3) origins and directions) on `threads` threads with the "
          "GIL released: a dict of body (slot, -1 for a miss), distance (m, inf), point and "
          "normal (N, 3).")
      .def(
          "overlap_sphere",
          [](const SharedQuery& shared, const py::object& center, float radius,
             const QueryFilter& filter) {
            const std::shared_ptr<const WorldQuery> q = shared.current();
            return q->overlap_sphere(vec3_from(center, "center"), radius, filter);
          },
          py::arg("center"), py::arg("radius"), py::arg("filter") = QueryFilter{},
          "The bodies with a leaf sphere touching the sphere (m), by slot.")
      .def(
          "overlap_aabb",
          [](const SharedQuery& shared, const py::object& low, const py::object& high,
             const QueryFilter& filter) {
            const std::shared_ptr<const WorldQuery> q = shared.current();
            return q->overlap_aabb({vec3_from(low, "low"), vec3_from(high, "high")}, filter);
          },
          py::arg("low"), py::arg("high"), py::arg("filter") = QueryFilter{},
          "The bodies with a leaf sphere touching the axis-aligned box [low, high] (m).")
      .def(
          "overlap_box",
          [](const SharedQuery& shared, const py::object& center, const py::object& half_extents,
             const py::object& orientation, const QueryFilter& filter) {
            const std::shared_ptr<const WorldQuery> q = shared.current();
            OrientedBox box;
            box.pose.translation = vec3_from(center, "center");
            box.pose.rotation = quat_from(orientation, "orientation");
            box.half_extents = vec3_from(half_extents, "half_extents");
            return q->overlap_box(box, filter);
          },
          py::arg("center"), py::arg("half_extents"),
          py::arg("orientation") = py::make_tuple(0, 0, 0, 1), py::arg("filter") = QueryFilter{},
          "The bodies with a leaf sphere touching the box (m; orientation (x, y, z, w)).")
      .def(
          "overlap_body",
          [](const SharedQuery& shared, BodyId body, const py::object& position,
             const py::object& orientation, const QueryFilter& filter) {
            const std::shared_ptr<const WorldQuery> q = shared.current();
            Transform pose;
            pose.translation = vec3_from(position, "position");
            pose.rotation = quat_from(orientation, "orientation");
            return q->overlap_body(body, pose, filter);
          },
          py::arg("body"), py::arg("position"), py::arg("orientation") = py::make_tuple(0, 0, 0, 1),
          py::arg("filter") = QueryFilter{},
          "The bodies a body's tree would touch at another pose (the body itself left out).")
      .def(
          "distance",
          [](const SharedQuery& shared, BodyId a, const py::object& b,
             std::uint64_t max_sphere_tests, double max_microseconds) {
            const std::shared_ptr<const WorldQuery> q = shared.current();
            const DistanceBudget budget{max_sphere_tests, max_microseconds};
            if (py::isinstance<BodyId>(b))
              return distance_dict(q->distance(a, b.cast<BodyId>(), budget));
            return distance_dict(q->distance(a, vec3_from(b, "b"), budget));
          },
          py::arg("a"), py::arg("b"), py::kw_only(), py::arg("max_sphere_tests") = 0,
          py::arg("max_microseconds") = 0.0,
          "The smallest gap (m) between the leaf spheres of body a and body b (a BodyId) or a "
          "point (3 numbers), with the closest pair; a budget may stop early, then exact is "
          "False and distance a lower bound.")
      .def(
          "check_configurations",
          [](const SharedQuery& shared, const py::object& spheres, const py::object& links,
             bool self_collision, const std::vector<std::array<std::int32_t, 2>>& allowed_pairs,
             const QueryFilter& filter, int tree_depth, std::uint32_t threads) {
            return check_configurations(*shared.current(), spheres, links, self_collision,
                                        allowed_pairs, filter, tree_depth, threads);
          },
          py::arg("spheres"), py::arg("links"), py::kw_only(), py::arg("self_collision") = false,
          py::arg("allowed_pairs") = std::vector<std::array<std::int32_t, 2>>{},
          py::arg("filter") = QueryFilter{}, py::arg("tree_depth") = 0, py::arg("threads") = 1,
          kCheckDoc);

  // The same from a world directly, through a query made for the call in the world's turn; the
  // check itself reads the query's snapshot alone, so other calls on the world go on meanwhile.
  auto world = py::reinterpret_borrow<py::class_<SharedWorld>>(m.attr("World"));
  world.def(
      "query", [](const SharedWorld& w) { return std::make_unique<SharedQuery>(w); },
      py::keep_alive<0, 1>(), "A WorldQuery of the world as it is now.");
  world.def(
      "check_configurations",
      [](const SharedWorld& w, const py::object& spheres, const py::object& links,
         bool self_collision, const std::vector<std::array<std::int32_t, 2>>& allowed_pairs,
         const QueryFilter& filter, int tree_depth, std::uint32_t threads) {
        return check_configurations(*SharedQuery(w).current(), spheres, links, self_collision,
                                    allowed_pairs, filter, tree_depth, threads);
      },
      py::arg("spheres"), py::arg("links"), py::kw_only(), py::arg("self_collision") = false,
      py::arg("allowed_pairs") = std::vector<std::array<std::int32_t, 2>>{},
      py::arg("filter") = QueryFilter{}, py::arg("tree_depth") = 0, py::arg("threads") = 1,
      kCheckDoc);
}

}  // namespace sphys::python
