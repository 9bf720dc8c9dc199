#pragma once

// Batched checks for motion planners: a robot's spheres, each on a link, posed at many
// configurations and checked against a world's leaf spheres (and, if asked, against each other).
// What a planner's state-validity checker and motion validator call.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "sphys/parallel.h"
#include "sphys/sphere_tree.h"
#include "sphys/world_query.h"

namespace sphys {

// What a ConfigurationChecker checks against, and how deep.
struct ConfigurationCheckSettings {
  // Which of the world's bodies count (e.g. the robot's own base, if it is a body, left out).
  QueryFilter filter;
  // Spheres of different links are checked against each other too, but for the pairs of links
  // listed in `allowed_link_pairs` (what SRDF's disabled collisions list: neighbours, links that
  // can never meet). Spheres of one link never are.
  bool self_collision = false;
  // Pairs of links (either order) whose spheres may touch: not checked against each other.
  std::vector<std::array<std::int32_t, 2>> allowed_link_pairs;
  // Levels of the world's sphere-trees the check answers at, the root included; 0: the levels the
  // world uses (CollisionSettings::tree_depth). Deeper than the world's, a sphere is tested below
  // the world's leaves it touches only, down to this level (or a tree's last), so that it costs
  // more only near bodies: fewer configurations collide by the trees' conservatism, and never one
  // more. unit: levels
  int tree_depth = 0;
  // A ball every sphere of every configuration lies in, if known (a robot's reach about its base:
  // RobotChecker gives its own). The groups reaching into its box are listed once and scanned in
  // order instead of walking the hierarchy from its root, for each configuration whose links
  // all lie inside that box; a configuration outside it is walked as without. unit: m
  std::optional<Sphere> reach;
};

// One configuration's answer.
struct ConfigurationResult {
  bool free = true;  // no sphere touches a body or (self-collision) another link's sphere
  // The first colliding sphere: the lowest-numbered sphere that touches a body of the world,
  // else (self-collision) the first sphere of the first pair of spheres that touch, pairs in
  // order of their first sphere then their second. -1 when free.
  std::int32_t sphere = -1;
  std::int32_t body = -1;          // the slot of a body it touches (World::id_of), else -1
  std::int32_t other_sphere = -1;  // self-collision: the sphere of another link it touches
};

// Checks configurations of a set of spheres against the bodies a WorldQuery read. Spheres touch
// when |c_a - c_b| <= r_a + r_b (touching counts as a collision, so "free" is strict).
class ConfigurationChecker {
 public:
  // `sphere_links`: each sphere's link, 0 .. links - 1. Throws sphys::Error naming
  // `sphere_links` for a negative link or `settings.allowed_link_pairs` for a pair naming a link
  // no sphere has, and the filter's unknown bodies.
  ConfigurationChecker(const WorldQuery& query, std::vector<std::int32_t> sphere_links,
                       ConfigurationCheckSettings settings = {});

  // How many spheres a configuration has (the size of sphere_links).
  [[nodiscard]] std::size_t spheres() const { return links_.size(); }
  // Links: one more than the largest in sphere_links.
  [[nodiscard]] std::size_t links() const { return link_count_; }
  // Whether a check reads every sphere whatever is near (Run::check_bounded): self-collision.
  [[nodiscard]] bool reads_every_sphere() const { return !self_pairs_.empty(); }

  // `spheres`: N configurations of spheres() spheres, each (x, y, z, radius) in the world frame
  // (N × S × 4 floats, unit: m); `results`: N entries. Configurations run on `parallel`'s
  // threads when given. Throws sphys::Error naming `spheres` or `results` for sizes that do not
  // match; non-finite spheres count as colliding (never "free" by accident).
  void check(std::span<const float> spheres, std::span<ConfigurationResult> results,
             const Parallel* parallel = nullptr) const;

  // The same with the spheres given in their links' frames (`link_spheres`, one per sphere, in
  // sphere order: what `sphys spherize` writes) and N × links() link poses in the world frame.
  void check_link_poses(std::span<const Transform> link_poses, std::span<const Sphere> link_spheres,
                        std::span<ConfigurationResult> results,
                        const Parallel* parallel = nullptr) const;

 private:
  // What check_one works in, one per run of configurations (src/robot/configuration_scratch.h).
  struct Scratch;

 public:
  // Checks configurations one at a time on one thread, keeping its working memory from one to the
  // next: for callers that make the spheres themselves, a few at a time (RobotChecker).
  class Run {
   public:
    // A run of `checker`'s checks, which must outlive it.
    explicit Run(const ConfigurationChecker& checker);
    ~Run();
    Run(const Run&) = delete;
    Run& operator=(const Run&) = delete;
    // One configuration's spheres() spheres, (x, y, z, radius) each, as check() reads them.
    [[nodiscard]] ConfigurationResult check(const float* spheres);
    // Several configurations checked together, as a motion's states are: `configurations` of them
    // at `spheres` (which must stay as they are until the next gather or check), each link
    // bounded once over all of them and the groups near that bound collected once, so that a link
    // far from everything costs nothing more per configuration. check_gathered(c) then gives what
    // check() would for configuration c; a configuration out of range throws sphys::Error.
    void gather(const float* spheres, std::size_t configurations);
    // What check() would give for the gathered configuration `configuration`.
    [[nodiscard]] ConfigurationResult check_gathered(std::size_t configuration);
    // For a caller that bounds each link itself, as RobotChecker does from its links' poses:
    // `boxes` holds, per link (links() of them), six rows `stride` floats apart, low x, y, z then
    // high x, y, z (m, world frame): boxes[(6 link + row) stride]. Each box must hold every sphere
    // of its link (it is not widened here: the caller's margin covers its roundings). The groups
    // near each box are collected; near(link) says whether there are any. check_bounded(spheres)
    // then gives what check() would for spheres inside those boxes, reading only the spheres of
    // links near a group, or every sphere when reads_every_sphere() (self-collision).
    void bound(const float* boxes, std::size_t stride);
    // After bound(): whether any group lies near the link's box.
    [[nodiscard]] bool near(std::size_t link) const;
    // After bound(): what check() would give for `spheres`, which lie inside the links' boxes.
    [[nodiscard]] ConfigurationResult check_bounded(const float* spheres);
    // After bound() with boxes that hold their links' spheres in every one of `configurations`
    // states at `spheres`: those states gathered as gather() gathers them, reading only the
    // spheres of links near a group; check_gathered then answers for each. Throws sphys::Error
    // when reads_every_sphere().
    void gather_bounded(const float* spheres, std::size_t configurations);

   private:
    const ConfigurationChecker* checker_;
    std::unique_ptr<Scratch> scratch_;
    const float* gathered_ = nullptr;
    std::size_t gathered_count_ = 0;
    bool gathered_finite_ = true;
    bool gathered_bounded_ = false;  // by gather_bounded: only near links' spheres were given
  };

 private:
  // One configuration's S spheres, x y z r each.
  [[nodiscard]] ConfigurationResult check_one(const float* spheres, Scratch& scratch) const;
  // The answer for spheres whose links' groups `scratch` holds: with `every_sphere_given`, each
  // sphere is checked to be finite first, else only those of links near a group are read.
  [[nodiscard]] ConfigurationResult answer(const float* spheres, const Scratch& scratch,
                                           bool every_sphere_given) const;
  // The groups near each link's bound in `scratch`, into its candidates (up to kMostCandidates),
  // kLinksPerWalk links a walk of the hierarchy, their bounds in lanes.
  static constexpr std::size_t kLinksPerWalk = 32;
  void collect_candidates(Scratch& scratch) const;
  void collect_candidates(std::size_t first, std::size_t end, Scratch& scratch) const;
  // The slot of a body the sphere (x y z r) of `link` touches, from the link's candidates, else -1.
  [[nodiscard]] std::int32_t sphere_touches(const float* sphere, std::size_t link,
                                            const Scratch& scratch) const;
  // The first sphere of the first pair of spheres of different links (not allowed) that touch,
  // and its partner in `other`; -1 when none do.
  [[nodiscard]] std::int32_t self_collision(const float* spheres, std::int32_t& other) const;
  // The slot of a body whose leaf spheres the sphere touches, else -1: over every group the
  // hierarchy leads to, or over `candidates` only (groups known to hold every group near it).
  [[nodiscard]] std::int32_t touched_body(float x, float y, float z, float radius) const;
  [[nodiscard]] std::int32_t touched_body(float x, float y, float z, float radius,
                                          std::span<const std::uint32_t> candidates) const;
  // Whether the sphere touches the group's leaf spheres at the check's level: those the world
  // uses, or, with a deeper tree_depth, the spheres at that level below the group's leaves.
  [[nodiscard]] bool group_touches(std::uint32_t group, const Vec3& centre, float radius) const;
  // Below the group's leaves, whether the sphere touches a sphere at the level asked: a subtree is
  // entered where the sphere reaches its bound (SphereTree::subtree_radius), since builders do
  // not nest children inside their parents.
  [[nodiscard]] bool touches_below(std::uint32_t group, const Vec3& centre, float radius) const;
  // Runs of configurations, each with its scratch, on the threads.
  template <class Check>
  void run_configurations(std::size_t count, const Parallel* parallel, const Check& check) const;

  const WorldQuery* query_;
  std::vector<std::int32_t> links_;
  std::size_t link_count_ = 0;
  // The spheres in runs of one link each, in order: a link far from everything skips its run.
  struct SphereRun {
    std::size_t first;
    std::size_t end;
    std::size_t link;
  };
  std::vector<SphereRun> runs_;
  std::vector<std::uint8_t> group_seen_;  // per group of the snapshot: the filter sees its body
  // The level asked (ConfigurationCheckSettings::tree_depth) when deeper than the world's, else 0;
  // then each body slot's rotation, as the snapshot placed its leaves.
  int deeper_depth_ = 0;
  std::vector<Mat3> rotations_;
  // With ConfigurationCheckSettings::reach: its box, and the seen groups whose boxes meet it,
  // in order (the hierarchy's leaf order, which a walk visits them in).
  std::optional<Aabb> reach_box_;
  std::vector<std::uint32_t> reachable_groups_;
  std::vector<std::array<std::int32_t, 2>> self_pairs_;  // sphere pairs checked for self-collision
};

}  // namespace sphys
