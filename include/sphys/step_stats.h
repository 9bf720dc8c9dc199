#pragma once

// Figures of one World::step: every figure the experiment reports, each measured once. With
// several collision passes, times and counts are summed over them and the deepest penetration is
// their largest.
// Times and counts are always measured; the plausibility figures (marked below) only with
// WorldSettings::plausibility_figures, as each costs a pass over every leaf pair or body.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace sphys {

// What detection counts, kept once: by each narrow-phase chunk, summed into a detection's figures
// (the detector's CollisionStats) and those into a step's (StepStats).
struct DetectionCounters {
  std::uint32_t candidate_pairs = 0;  // overlapping bounds from the broad phase
  std::uint64_t sphere_tests = 0;     // in the narrow phase, ground plane included
  // Overlapping leaf pairs (ground plane: leaves under it).
  std::uint32_t leaf_pairs = 0;
  std::uint32_t pairs_cut_short = 0;     // node pairs left when a time-critical budget ran out
  std::uint32_t coincident_centres = 0;  // contacts whose normal came from the fallback
  // Pairs (a body and the ground plane included) whose trees descended, and pairs that kept their
  // contacts from the last descent as they barely moved (SolverSettings::reuse_distance).
  std::uint32_t descended_pairs = 0;
  std::uint32_t reused_pairs = 0;  // kept their contacts (reuse_distance), no descent
  // Crowds (CollisionSettings::crowd_pairs_per_body): overlapping body pairs the broad phase left
  // out to keep the step's work bounded.
  std::uint64_t pairs_deferred = 0;

  // Adds every counter of `other` to this one's.
  DetectionCounters& operator+=(const DetectionCounters& other) {
    candidate_pairs += other.candidate_pairs;
    sphere_tests += other.sphere_tests;
    leaf_pairs += other.leaf_pairs;
    pairs_cut_short += other.pairs_cut_short;
    coincident_centres += other.coincident_centres;
    descended_pairs += other.descended_pairs;
    reused_pairs += other.reused_pairs;
    pairs_deferred += other.pairs_deferred;
    return *this;
  }
};

// The figures of one World::step (the top of this file says which are measured when).
struct StepStats : DetectionCounters {
  // Wall-clock time of each phase of the step and of the whole step. unit: ms
  double broad_phase_ms = 0.0;   // bounds and Sweep & Prune
  double narrow_phase_ms = 0.0;  // sphere-tree descents (leaf pairs)
  double contacts_ms = 0.0;      // contact point, normal and depth per leaf pair (eq. 1-3)
  double response_ms = 0.0;      // impulses
  double integration_ms = 0.0;   // velocities and positions
  // Plausible mode: waking what moving bodies touch (their pairs' narrow phase is counted in
  // the phases above), islands and sleep.
  double sleep_ms = 0.0;
  double step_ms = 0.0;  // the whole step
  // Each phase's serial time, and the whole step's: its time on one thread outside the loops that
  // threads share (Parallel::loop_ms), which more threads do not shorten. Over step_ms, the serial
  // share that bounds what threads can gain (Amdahl's law). unit: ms
  double broad_phase_serial_ms = 0.0;   // of broad_phase_ms
  double narrow_phase_serial_ms = 0.0;  // of narrow_phase_ms
  double contacts_serial_ms = 0.0;      // of contacts_ms
  double response_serial_ms = 0.0;      // of response_ms
  double integration_serial_ms = 0.0;   // of integration_ms
  double sleep_serial_ms = 0.0;         // of sleep_ms
  double serial_ms = 0.0;               // the whole step's, the phases' and what lies between them
  // Detection as the paper counts it: broad phase, narrow phase and contacts. unit: ms
  [[nodiscard]] double detection_ms() const {
    return broad_phase_ms + narrow_phase_ms + contacts_ms;
  }

  // Bodies in the broad phase at the step's last detection, static ones included. (The detection
  // counters, DetectionCounters, are summed over the step's detections.)
  std::uint32_t bodies = 0;
  std::uint32_t contacts = 0;         // the response's contacts (after reduction, when reduced)
  std::uint32_t impulses = 0;         // paper mode: eq. 4's impulses applied, over all passes
  std::uint32_t contacts_solved = 0;  // plausible mode: contacts with a moving body solved
  // Paper mode: passes over the contacts. Plausible mode: the soft step's solve and relax passes.
  std::uint32_t response_passes = 0;
  // Collision passes in this step (WorldSettings::collision_passes, max_collision_passes).
  std::uint32_t collision_passes = 1;
  std::uint32_t warm_started = 0;  // contacts whose impulses came from the previous collision pass
  std::uint32_t bounces = 0;       // contacts given restitution (plausible mode)
  // Groups of touching dynamic bodies (plausible mode), persistent: a group whose bodies parted
  // counts as one until the next step splits it.
  std::uint32_t islands = 0;
  // Crowds (CollisionSettings::crowd_pairs_per_body): the moving bodies in a crowd (their largest
  // count over the collision passes).
  std::uint32_t crowded_bodies = 0;
  std::uint32_t movable_bodies = 0;  // bodies that are not static
  std::uint32_t bodies_asleep = 0;   // movable bodies asleep at the end of the step

  // Plausibility figures, measured on the leaf-pair contacts before any reduction and on the
  // bodies at the end of the step (WorldSettings::plausibility_figures).
  float deepest_penetration = 0.0f;        // largest overlap of two leaf spheres (0: none). unit: m
  double mean_penetration = 0.0;           // mean overlap of the overlapping leaf pairs. unit: m
  std::uint32_t penetrating_contacts = 0;  // leaf pairs that overlap (not touching or apart)
  double kinetic_energy = 0.0;             // all moving bodies. unit: J
  // Asleep, or with every point slower than SleepSettings::speed.
  std::uint32_t bodies_at_rest = 0;
  // Mean speed of the fastest point of the bodies that should be resting: asleep (speed 0), or
  // touching something and slower than ten times SleepSettings::speed. unit: m/s
  double jitter = 0.0;

  // The first body (by index) whose state stopped being finite (or whose orientation stopped
  // being a rotation) in this step; the world stops stepping from then on. Unset while all is well.
  std::optional<std::uint32_t> non_finite_body;
};

// One figure of StepStats, for whatever lists them all (the frames CSV of `sphys simulate`, the
// run summary's time shares, Python's StepStats): adding a figure to StepStats means adding it to
// step_figures() alone.
struct StepFigure {
  std::string_view name;  // the member's name, and Python's
  std::string_view unit;  // "ms", "m", "m/s", "J"; empty for counts
  bool count = false;     // a whole number (Python gives an int)
  // Every frame's value is a column of frames.csv (its name: frames_csv_column()).
  bool in_frames_csv = false;
  double (*read)(const StepStats&) = nullptr;  // the figure's value in a step's stats
};

// Every figure of StepStats, the frames CSV's in its column order first; a non-finite body
// (StepStats::non_finite_body) is not a figure.
[[nodiscard]] std::span<const StepFigure> step_figures();
// The figure's frames.csv column: its name, with its unit appended where the name does not end in
// it ("kinetic_energy_J", "jitter_m_per_s", "step_ms", "contacts").
[[nodiscard]] std::string frames_csv_column(const StepFigure& figure);

}  // namespace sphys
