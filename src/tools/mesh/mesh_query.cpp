// The one translation unit that compiles CGAL (20-30 s and over 1 GB of memory each): everything
// else reaches the AABB tree through MeshQuery's pointer to Impl.
#include "sphys/tools/mesh_query.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include "sphys/error.h"
#include "sphys/tools/check_mesh.h"
#include "sphys/tools/winding_number.h"

namespace sphys::tools {
namespace {

// Inside tests use exact predicates, which make ray parity robust: a ray through an edge or a
// vertex is detected and another ray is cast.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using SideOfMesh = CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel>;
using FaceTree = SideOfMesh::AABB_tree;

// Closest points need no exact predicates (a near tie picks either triangle, at the same
// distance), and plain doubles answer them about 30% faster. CGAL projects onto degenerate
// triangles correctly, so every triangle goes in.
using FastKernel = CGAL::Simple_cartesian<double>;
using FastPoint = FastKernel::Point_3;
using Soup = std::vector<FastKernel::Triangle_3>;
using SoupTree = CGAL::AABB_tree<
    CGAL::AABB_traits<FastKernel, CGAL::AABB_triangle_primitive<FastKernel, Soup::const_iterator>>>;

template <typename P>
P to_point(const Vec3d& p) {
  return {p.x(), p.y(), p.z()};
}

bool repeats_a_vertex(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

// The mesh as a halfedge structure, or nothing when it is not one: Surface_mesh refuses faces
// that would make a vertex non-manifold, which check_mesh (it looks at edges only) lets through.
// A triangle that repeats a vertex is a segment lying on its neighbours; it is left out, as it
// has no halfedge form and adds no crossing to a ray.
std::optional<SurfaceMesh> to_surface_mesh(const TriangleMesh& mesh) {
  SurfaceMesh surface;
  std::vector<SurfaceMesh::Vertex_index> handles;
  handles.reserve(mesh.vertices.size());
  for (const Vec3d& v : mesh.vertices) handles.push_back(surface.add_vertex(to_point<Point>(v)));
  for (const Triangle& t : mesh.triangles) {
    if (repeats_a_vertex(t)) continue;
    const auto face = surface.add_face(handles[t[0]], handles[t[1]], handles[t[2]]);
    if (face == SurfaceMesh::null_face()) return std::nullopt;
  }
  if (surface.number_of_faces() == 0 || !CGAL::is_closed(surface)) return std::nullopt;
  return surface;
}

// The generalized winding number in logarithmic rather than linear time, after Barill, Dickson,
// Schmidt, Levin & Jacobson, "Fast Winding Numbers for Soups and Clouds" (SIGGRAPH 2018): the
// triangles are split into a tree of clusters, and a cluster seen from farther than kFarField
// times its radius counts as a dipole, A·(c - p) / |c - p|³ with A its vector area and c its area
// centroid; nearer clusters are opened, and leaves are summed exactly. At kFarField = 3 the error
// stayed below 0.05 over random points around the bunny (2000 and 70k triangles, with holes), an
// open icosphere and a torus, while answering 10 to 100 times faster than the plain sum.
class WindingTree {
 public:
  explicit WindingTree(const TriangleMesh& mesh) : mesh_(mesh) {
    order_.resize(mesh.triangles.size());
    for (std::uint32_t t = 0; t < order_.size(); ++t) order_[t] = t;
    centroids_.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      centroids_.push_back((mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0);
    }
    build(0, static_cast<std::uint32_t>(order_.size()));
  }

  [[nodiscard]] double approximate(const Vec3d& p) const {
    // Median splits halve the triangles at each level, so 64 entries outlast any 32-bit count.
    std::array<std::uint32_t, 64> stack{};
    std::size_t size = 0;
    stack[size++] = 0;
    double total = 0.0;
    while (size > 0) {
      const Node& node = nodes_[stack[--size]];
      const Vec3d to_center = node.center - p;
      const double d = to_center.norm();
      if (d > kFarField * node.radius) {
        total += node.vector_area.dot(to_center) / (d * d * d);
      } else if (node.leaf) {
        for (std::uint32_t i = node.begin; i < node.end; ++i) {
          const std::size_t t = order_[i];
          total += triangle_solid_angle(mesh_.corner(t, 0) - p, mesh_.corner(t, 1) - p,
                                        mesh_.corner(t, 2) - p);
        }
      } else {
        stack[size++] = node.begin;
        stack[size++] = node.end;
      }
    }
    return total / (4.0 * std::numbers::pi);
  }

 private:
  static constexpr double kFarField = 3.0;
  static constexpr std::uint32_t kLeafSize = 8;

  struct Node {
    Vec3d center = Vec3d::Zero();
    double radius = 0.0;  // of the ball about center that holds the cluster's triangles
    Vec3d vector_area = Vec3d::Zero();
    bool leaf = true;
    std::uint32_t begin = 0;  // a leaf's triangles are order_[begin, end); an inner node's
    std::uint32_t end = 0;    // children are nodes_[begin] and nodes_[end]
  };

  std::uint32_t build(std::uint32_t begin, std::uint32_t end) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Node node;
    Vec3d weighted = Vec3d::Zero();
    double area = 0.0;
    Box3d box;
    for (std::uint32_t i = begin; i < end; ++i) {
      const Vec3d n = 0.5 * mesh_.area_normal(order_[i]);
      node.vector_area += n;
      weighted += n.norm() * centroids_[order_[i]];
      area += n.norm();
      box.extend(centroids_[order_[i]]);
    }
    // A cluster of degenerate triangles has no area to weigh its centre by.
    node.center = area > 0.0 ? Vec3d(weighted / area) : box.center();
    for (std::uint32_t i = begin; i < end; ++i) {
      for (int k = 0; k < 3; ++k) {
        node.radius = std::max(node.radius, (mesh_.corner(order_[i], k) - node.center).norm());
      }
    }
    if (end - begin <= kLeafSize) {
      node.begin = begin;
      node.end = end;
    } else {
      Eigen::Index axis = 0;
      box.sizes().maxCoeff(&axis);
      const std::uint32_t middle = begin + (end - begin) / 2;
      std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                       [&](std::uint32_t a, std::uint32_t b) {
                         return centroids_[a][axis] < centroids_[b][axis];
                       });
      node.leaf = false;
      node.begin = build(begin, middle);
      node.end = build(middle, end);
    }
    nodes_[index] = node;
    return index;
  }

  const TriangleMesh& mesh_;
  std::vector<std::uint32_t> order_;
  std::vector<Vec3d> centroids_;
  std::vector<Node> nodes_;
};

// The tree's answer is trusted when it is this far from 1/2, well beyond its error; closer, the
// exact sum decides, so inside() agrees with is_inside() (only points near holes pay for it).
constexpr double kTrustedMargin = 0.25;

}  // namespace

// Closest points come from a tree over the triangles as a soup, which takes any mesh. Inside tests
// on a watertight mesh cast rays through a second tree, over the mesh as a halfedge structure;
// any other mesh falls back to the winding number, evaluated with a tree of its own. Every tree
// (and the distance accelerator) is built in the constructor: const queries on a built tree only
// read it, so concurrent queries need no locking.
struct MeshQuery::Impl {
  explicit Impl(const TriangleMesh& source) : mesh(source) {
    require_usable(mesh);
    soup.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      soup.emplace_back(to_point<FastPoint>(mesh.corner(t, 0)),
                        to_point<FastPoint>(mesh.corner(t, 1)),
                        to_point<FastPoint>(mesh.corner(t, 2)));
    }
    soup_tree.emplace(soup.cbegin(), soup.cend());
    soup_tree->build();
    soup_tree->accelerate_distance_queries();

    if (check_mesh(mesh).watertight()) surface = to_surface_mesh(mesh);
    if (surface) {
      face_tree.emplace(faces(*surface).first, faces(*surface).second, *surface);
      face_tree->build();
    } else {
      winding_tree.emplace(mesh);
    }
  }

  TriangleMesh mesh;
  Soup soup;  // the soup tree holds iterators into it: never resized after the tree is made
  std::optional<SoupTree> soup_tree;
  std::optional<SurfaceMesh> surface;  // the face tree points into it
  std::optional<FaceTree> face_tree;
  std::optional<WindingTree> winding_tree;  // when there is no face tree; it refers to mesh
};

MeshQuery::MeshQuery(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
MeshQuery::~MeshQuery() = default;
MeshQuery::MeshQuery(MeshQuery&&) noexcept = default;
MeshQuery& MeshQuery::operator=(MeshQuery&&) noexcept = default;

Vec3d MeshQuery::closest_point(const Vec3d& p) const {
  const FastPoint closest = impl_->soup_tree->closest_point(to_point<FastPoint>(p));
  return {closest.x(), closest.y(), closest.z()};
}

double MeshQuery::distance(const Vec3d& p) const { return (closest_point(p) - p).norm(); }

bool MeshQuery::inside(const Vec3d& p) const {
  if (impl_->winding_tree) {
    const double w = impl_->winding_tree->approximate(p);
    if (std::abs(w - 0.5) > kTrustedMargin) return w > 0.5;
    return is_inside(impl_->mesh, p);
  }
  // Side_of_triangle_mesh keeps a lazily built tree behind a mutex; made per call over the
  // shared, already built tree it only reads, so calls from many threads cannot interfere. It
  // costs a bounding-box copy, nothing next to the ray cast.
  const SideOfMesh side(*impl_->face_tree);
  // The solid is closed: a point on the surface is inside, as with the winding number's 1/2.
  return side(to_point<Point>(p)) != CGAL::ON_UNBOUNDED_SIDE;
}

double MeshQuery::signed_distance(const Vec3d& p) const {
  const double d = distance(p);
  return inside(p) ? -d : d;
}

const TriangleMesh& MeshQuery::mesh() const { return impl_->mesh; }

}  // namespace sphys::tools
