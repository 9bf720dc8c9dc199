#include "sphys/settings_table.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "core/simd_lanes.h"
#include "sphys/world.h"

namespace sphys {
namespace {

// Where a field lives: WorldSettings::*Member, or (WorldSettings::*Group).*Member.
template <auto Member>
struct Top {
  static auto& in(WorldSettings& settings) { return settings.*Member; }
  static const auto& in(const WorldSettings& settings) { return settings.*Member; }
};

template <auto Group, auto Member>
struct Nested {
  static auto& in(WorldSettings& settings) { return (settings.*Group).*Member; }
  static const auto& in(const WorldSettings& settings) { return (settings.*Group).*Member; }
};

template <typename Path>
double get_scalar(const WorldSettings& settings) {
  const auto value = Path::in(settings);
  using T = std::remove_cv_t<decltype(value)>;
  if constexpr (std::is_enum_v<T>) {
    return static_cast<double>(static_cast<std::underlying_type_t<T>>(value));
  } else if constexpr (std::is_same_v<T, bool>) {
    return value ? 1.0 : 0.0;
  } else if constexpr (std::is_same_v<T, float>) {
    return shortest_double(value);
  } else {
    return static_cast<double>(value);
  }
}

// `value` must be representable in the field's type (a count must not be negative).
template <typename Path>
void set_scalar(WorldSettings& settings, double value) {
  auto& field = Path::in(settings);
  using T = std::remove_cvref_t<decltype(field)>;
  if constexpr (std::is_enum_v<T>) {
    field = static_cast<T>(static_cast<std::underlying_type_t<T>>(value));
  } else if constexpr (std::is_same_v<T, bool>) {
    field = value != 0.0;
  } else {
    field = static_cast<T>(value);
  }
}

template <typename Path>
Setting scalar(Setting setting) {
  setting.get = &get_scalar<Path>;
  setting.set = &set_scalar<Path>;
  return setting;
}

template <typename Path>
Setting vector(Setting setting) {
  setting.get_vector = [](const WorldSettings& settings) -> Vec3 { return Path::in(settings); };
  setting.set_vector = [](WorldSettings& settings, const Vec3& value) {
    Path::in(settings) = value;
  };
  return setting;
}

constexpr SettingRange between(double low, double high) { return {low, high, true, true}; }
constexpr SettingRange at_least(double low) { return {.min = low}; }
constexpr SettingRange above(double low) { return {.min = low, .min_inclusive = false}; }

constexpr std::array<std::string_view, 2> kResponseChoices = {"paper", "plausible"};
constexpr std::array<std::string_view, 2> kContactChoices = {"all", "reduced"};

using W = WorldSettings;
using S = SolverSettings;
using Z = SleepSettings;
using C = CollisionSettings;

// A crowd limit past any pile's: 2^20 overlapping bodies per body is a limit no world reaches, so
// larger values are mistakes. unit: bodies
constexpr std::uint32_t kMaxCrowdPairsPerBody = 1u << 20;

// Kept in the order of docs/scenes.md; the command line finds an entry by its field.
const auto kTable = std::to_array<Setting>({
    vector<Top<&W::gravity>>({
        .key = "gravity",
        .field = "gravity",
        .kind = SettingKind::kVector3,
        .unit = "m/s²",
        .range = between(-kMaxGravity, kMaxGravity),
        .doc = "Acceleration of gravity, y up.",
    }),
    scalar<Top<&W::response>>({
        .key = "response",
        .field = "response",
        .kind = SettingKind::kEnum,
        .choices = kResponseChoices,
        .doc = "How contacts change velocities. paper: the impulse of the paper's eq. 4 per "
               "contact, no friction (docs/experiment.md). plausible: the soft step with warm "
               "starting, Coulomb friction, rolling resistance, restitution above a threshold, "
               "speculative contacts and sleeping (docs/dynamics.md).",
    }),
    scalar<Top<&W::paper_passes>>({
        .key = "paper_passes",
        .field = "paper_passes",
        .kind = SettingKind::kInteger,
        .unit = "passes",
        .range = between(1, kMaxPaperPasses),
        .doc =
            "Paper mode: passes over the contacts per collision pass at most; the response stops "
            "after a pass that finds no approaching contact. 1 gives every contact at most one "
            "impulse, as published.",
    }),
    scalar<Nested<&W::solver, &S::contacts>>({
        .key = "contacts",
        .field = "solver.contacts",
        .kind = SettingKind::kEnum,
        .choices = kContactChoices,
        .doc = "Plausible mode: the contacts the response sees. all: one per overlapping leaf "
               "pair, as the paper makes them. reduced: at most solver.manifold_points per body "
               "pair.",
    }),
    scalar<Top<&W::collision_passes>>({
        .key = "collision_passes",
        .field = "collision_passes",
        .kind = SettingKind::kInteger,
        .unit = "collision passes",
        .range = between(1, kMaxCollisionPasses),
        .doc = "Collision passes per frame (at least): detection and response run again, each "
               "pass over an equal share of the time step.",
    }),
    scalar<Top<&W::max_collision_passes>>({
        .key = "max_collision_passes",
        .field = "max_collision_passes",
        .kind = SettingKind::kInteger,
        .unit = "collision passes",
        .range = between(1, kMaxCollisionPasses),
        .doc = "Plausible mode: more collision passes in a frame where bodies move fast, up to "
               "this many; at most collision_passes turns it off.",
    }),
    scalar<Top<&W::collision_pass_travel>>({
        .key = "collision_pass_travel",
        .field = "collision_pass_travel",
        .kind = SettingKind::kNumber,
        .unit = "bounding radii",
        .range = above(0),
        .doc = "Plausible mode: a body's fastest point (|v| + |ω| · its bounding radius) travels "
               "at most this much of its bounding radius per collision pass, within "
               "max_collision_passes.",
    }),
    scalar<Nested<&W::solver, &S::soft_substeps>>({
        .object = "solver",
        .key = "soft_substeps",
        .field = "solver.soft_substeps",
        .kind = SettingKind::kInteger,
        .unit = "substeps",
        .range = between(1, kMaxSoftSubsteps),
        .doc = "Solver substeps per collision pass, each one solve and one relax pass.",
    }),
    scalar<Nested<&W::solver, &S::contact_hertz>>({
        .object = "solver",
        .key = "contact_hertz",
        .field = "solver.contact_hertz",
        .unit = "Hz",
        .range = above(0),
        .doc = "The contacts' spring frequency, capped at an eighth of the substep "
               "rate; contacts with an immovable body are twice as stiff.",
    }),
    scalar<Nested<&W::solver, &S::contact_damping_ratio>>({
        .object = "solver",
        .key = "contact_damping_ratio",
        .field = "solver.contact_damping_ratio",
        .unit = "dimensionless",
        .range = at_least(0),
        .doc = "The contacts' damping ratio (1 is critical damping).",
    }),
    scalar<Nested<&W::solver, &S::warm_starting>>({
        .object = "solver",
        .key = "warm_starting",
        .field = "solver.warm_starting",
        .kind = SettingKind::kBool,
        .doc = "Start from the previous collision pass's impulses.",
    }),
    scalar<Nested<&W::solver, &S::restitution_threshold>>({
        .object = "solver",
        .key = "restitution_threshold",
        .field = "solver.restitution_threshold",
        .unit = "m/s",
        .range = at_least(0),
        .doc = "Approach speeds below this get no restitution, so resting contacts do not bounce.",
    }),
    scalar<Nested<&W::solver, &S::linear_slop>>({
        .object = "solver",
        .key = "linear_slop",
        .field = "solver.linear_slop",
        .unit = "m",
        .range = at_least(0),
        .doc = "Penetration left alone, so that resting contacts keep touching.",
    }),
    scalar<Nested<&W::solver, &S::max_correction_speed>>({
        .object = "solver",
        .key = "max_correction_speed",
        .field = "solver.max_correction_speed",
        .unit = "m/s",
        .range = at_least(0),
        .doc = "Largest speed at which the contact springs push bodies apart.",
    }),
    scalar<Nested<&W::solver, &S::rolling_resistance>>({
        .object = "solver",
        .key = "rolling_resistance",
        .field = "solver.rolling_resistance",
        .unit = "m",
        .range = at_least(0),
        .doc = "Each contact resists the relative turning of its bodies (rolling and spinning) "
               "with a torque up to this arm times its normal force, as a soft tyre or a dent in "
               "the ground does.",
    }),
    scalar<Nested<&W::solver, &S::manifold_points>>({
        .object = "solver",
        .key = "manifold_points",
        .field = "solver.manifold_points",
        .kind = SettingKind::kInteger,
        .unit = "contacts",
        .range = between(1, kMaxManifoldPoints),
        .doc = "Contacts kept per body pair when contacts are reduced.",
    }),
    scalar<Nested<&W::solver, &S::contact_margin>>({
        .object = "solver",
        .key = "contact_margin",
        .field = "solver.contact_margin",
        .unit = "m",
        .range = at_least(0),
        .doc = "Contacts are made this far before spheres touch.",
    }),
    scalar<Nested<&W::solver, &S::speculative_contacts>>({
        .object = "solver",
        .key = "speculative_contacts",
        .field = "solver.speculative_contacts",
        .kind = SettingKind::kBool,
        .doc = "Widen the margin by how far each pair can close in a collision pass, so that fast "
               "bodies neither tunnel nor sink in.",
    }),
    scalar<Nested<&W::solver, &S::fast_pair_reach>>({
        .object = "solver",
        .key = "fast_pair_reach",
        .field = "solver.fast_pair_reach",
        .unit = "m",
        .range = at_least(0),
        .doc = "Reduced contacts: two bodies that can close by more than this in a collision "
               "pass (and by no more than the smaller one's bounding radius) keep two contacts per "
               "pair of parts that meet (the trees' first-level spheres) instead of one manifold.",
    }),
    scalar<Nested<&W::solver, &S::reuse_distance>>({
        .object = "solver",
        .key = "reuse_distance",
        .field = "solver.reuse_distance",
        .unit = "m",
        .range = at_least(0),
        .doc = "A body pair that moved relative to itself by at most this since its trees last "
               "descended keeps its manifold, recomputed at the new poses, instead of descending "
               "again; 0 descends every pair every collision pass.",
    }),
    scalar<Nested<&W::sleep, &Z::enabled>>({
        .object = "sleep",
        .key = "enabled",
        .field = "sleep.enabled",
        .kind = SettingKind::kBool,
        .doc = "Put bodies at rest to sleep; false simulates every body in every step.",
    }),
    scalar<Nested<&W::sleep, &Z::speed>>({
        .object = "sleep",
        .key = "speed",
        .field = "sleep.speed",
        .unit = "m/s",
        .range = at_least(0),
        .doc = "A body is still while its fastest point (|v| + |ω| · its bounding radius) is "
               "slower than this.",
    }),
    scalar<Nested<&W::sleep, &Z::time>>({
        .object = "sleep",
        .key = "time",
        .field = "sleep.time",
        .unit = "s",
        .range = at_least(0),
        .doc = "A body sleeps once it and every moving body it touches have been still this "
               "long (twice this long while a body of its island is not).",
    }),
    scalar<Top<&W::ground_restitution>>({
        .object = "ground",
        .key = "restitution",
        .field = "ground_restitution",
        .unit = "dimensionless",
        .range = between(0, 1),
        .doc = "The ground's restitution; a contact takes the larger of the ground's and the "
               "body's.",
    }),
    scalar<Top<&W::ground_friction>>({
        .object = "ground",
        .key = "friction",
        .field = "ground_friction",
        .unit = "dimensionless",
        .range = at_least(0),
        .doc = "The ground's friction coefficient; a contact takes the geometric mean of the "
               "ground's and the body's.",
    }),
    scalar<Top<&W::threads>>({
        .key = "threads",
        .in_scene = false,
        .field = "threads",
        .kind = SettingKind::kInteger,
        .unit = "threads",
        .range = between(0, kMaxWorldThreads),
        .doc = "Threads a step runs on (oneTBB); 0 takes every hardware thread. The results are "
               "the same bit for bit whatever the count.",
    }),
    scalar<Top<&W::plausibility_figures>>({
        .key = "plausibility_figures",
        .in_scene = false,
        .field = "plausibility_figures",
        .kind = SettingKind::kBool,
        .doc = "Compute StepStats' plausibility figures (penetration, kinetic energy, rest, "
               "jitter) every step: each a pass over every leaf pair or body.",
    }),
    scalar<Nested<&W::collision, &C::tree_depth>>({
        .key = "tree_depth",
        .in_scene = false,
        .field = "collision.tree_depth",
        .kind = SettingKind::kInteger,
        .unit = "levels",
        .range = between(0, kMostTreeDepth),
        .doc = "Levels of every sphere-tree the narrow phase and the queries use, the root "
               "included; 0 uses them all. A check may still ask for deeper ones "
               "(check_configurations' tree_depth).",
    }),
    scalar<Nested<&W::collision, &C::crowd_pairs_per_body>>({
        .key = "crowd_pairs_per_body",
        .in_scene = false,
        .field = "collision.crowd_pairs_per_body",
        .kind = SettingKind::kInteger,
        .unit = "bodies",
        .range = between(0, kMaxCrowdPairsPerBody),
        .doc =
            "Crowds: where bodies piled on each other overlap more than this many others each "
            "on average, a body that overlaps more than this many is paired only with its "
            "nearest half as many (StepStats.pairs_deferred counts the pairs left out), with one "
            "contact of the trees' roots, so that a step's work stays bounded while they part; "
            "0 turns it off.",
    }),
    scalar<Nested<&W::solver, &S::lanes>>({
        .key = "lanes",
        .in_scene = false,
        .field = "solver.lanes",
        .kind = SettingKind::kEnum,
        .choices = kLaneSetNames,
        .doc = "The SIMD instructions of the soft step's contact passes, 8 manifolds at a time: "
               "auto takes SPHYS_SIMD from the environment where it is set, else AVX2 where the "
               "processor has it, else SSE2. Every choice gives the same bits.",
    }),
    scalar<Nested<&W::collision, &C::max_microseconds>>({
        .key = "max_microseconds",
        .in_scene = false,
        .field = "collision.max_microseconds",
        .unit = "µs",
        .range = at_least(0),
        .doc = "Time-critical narrow phase (paper §3.2): time the sphere-tree descents of a "
               "detection may take, shared by the pairs in order; 0 turns the budget off.",
    }),
});

}  // namespace

std::span<const Setting> settings_table() { return kTable; }

const Setting& setting_of(std::string_view field) {
  const auto found = std::find_if(kTable.begin(), kTable.end(),
                                  [&](const Setting& setting) { return setting.field == field; });
  if (found == kTable.end()) {
    throw std::out_of_range("no setting " + std::string(field) + " in the settings table");
  }
  return *found;
}

}  // namespace sphys
