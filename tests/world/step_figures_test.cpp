// The table of StepStats' figures that the frames CSV and Python list: names, units, columns and
// the members they read.

#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/step_stats.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"
#include "sphys/world.h"

namespace sphys {
namespace {

const StepFigure& figure_named(std::string_view name) {
  for (const StepFigure& figure : step_figures()) {
    if (figure.name == name) return figure;
  }
  throw std::out_of_range(std::string(name));
}

TEST(StepFigures, EachNameOnce) {
  std::set<std::string_view> names;
  for (const StepFigure& figure : step_figures()) {
    EXPECT_TRUE(names.insert(figure.name).second) << figure.name;
    EXPECT_NE(figure.read, nullptr) << figure.name;
  }
}

TEST(StepFigures, TheFramesCsvColumnsAreTheDocumentedOnes) {
  // docs/file-formats.md, "Per-frame statistics: frames.csv", after frame and time_s.
  const std::vector<std::string> documented = {"step_ms",
                                               "broad_phase_ms",
                                               "narrow_phase_ms",
                                               "contacts_ms",
                                               "response_ms",
                                               "integration_ms",
                                               "sleep_ms",
                                               "candidate_pairs",
                                               "sphere_tests",
                                               "leaf_pairs",
                                               "contacts",
                                               "impulses",
                                               "contacts_solved",
                                               "kinetic_energy_J",
                                               "deepest_penetration_m",
                                               "mean_penetration_m",
                                               "bodies_at_rest",
                                               "bodies_asleep",
                                               "jitter_m_per_s",
                                               "warm_started",
                                               "islands",
                                               "collision_passes",
                                               "serial_ms",
                                               "broad_phase_serial_ms",
                                               "narrow_phase_serial_ms",
                                               "contacts_serial_ms",
                                               "response_serial_ms",
                                               "integration_serial_ms",
                                               "sleep_serial_ms"};
  std::vector<std::string> columns;
  for (const StepFigure& figure : step_figures()) {
    if (figure.in_frames_csv) columns.push_back(frames_csv_column(figure));
  }
  EXPECT_EQ(columns, documented);
}

TEST(StepFigures, EachReadsItsOwnMember) {
  StepStats stats;
  stats.broad_phase_ms = 1.5;
  stats.narrow_phase_ms = 2.0;
  stats.contacts_ms = 0.25;
  stats.sphere_tests = (std::uint64_t{1} << 40) + 3;  // a DetectionCounters member
  stats.pairs_deferred = 11;
  stats.deepest_penetration = 0.125f;
  stats.jitter = 0.5;
  stats.islands = 7;
  EXPECT_EQ(figure_named("broad_phase_ms").read(stats), 1.5);
  EXPECT_EQ(figure_named("sphere_tests").read(stats), static_cast<double>(stats.sphere_tests));
  EXPECT_EQ(figure_named("pairs_deferred").read(stats), 11.0);
  EXPECT_EQ(figure_named("deepest_penetration").read(stats), 0.125);
  EXPECT_EQ(figure_named("jitter").read(stats), 0.5);
  EXPECT_EQ(figure_named("islands").read(stats), 7.0);
  EXPECT_EQ(figure_named("detection_ms").read(stats), 3.75);
  EXPECT_TRUE(figure_named("islands").count);
  EXPECT_FALSE(figure_named("jitter").count);
  EXPECT_EQ(figure_named("jitter").unit, "m/s");
}

TEST(StepFigures, DetectionCountersAddUp) {
  DetectionCounters a;
  a.candidate_pairs = 1;
  a.sphere_tests = 2;
  a.leaf_pairs = 3;
  a.pairs_cut_short = 4;
  a.coincident_centres = 5;
  a.descended_pairs = 6;
  a.reused_pairs = 7;
  a.pairs_deferred = 8;
  DetectionCounters sum = a;
  sum += a;
  EXPECT_EQ(sum.candidate_pairs, 2u);
  EXPECT_EQ(sum.sphere_tests, 4u);
  EXPECT_EQ(sum.leaf_pairs, 6u);
  EXPECT_EQ(sum.pairs_cut_short, 8u);
  EXPECT_EQ(sum.coincident_centres, 10u);
  EXPECT_EQ(sum.descended_pairs, 12u);
  EXPECT_EQ(sum.reused_pairs, 14u);
  EXPECT_EQ(sum.pairs_deferred, 16u);
}

// The serial times of a falling bunny pile, one and two threads: each phase's is part of its
// time, they add up to no more than the step's, and on one thread the loops that threads would
// share (the narrow phase's chunks, the soft step's passes) are a good part of the step, not
// serial (about half of it while the pile of 100 falls: its solver's colours hold too few blocks
// to share; 95% of the step of 1,000 bunnies over a run).
TEST(StepFigures, SerialTimesArePartsOfThePhasesAndTheStep) {
  constexpr double kClockSlack = 1e-3;  // clocks read a little apart. unit: ms
  for (const std::uint32_t threads : {1u, 2u}) {
    SCOPED_TRACE(threads);
    tools::Scene scene = tools::bunny_stacks_scene(4, 25, 2);
    scene.ground.kind = tools::GroundSpec::Kind::kPlane;
    tools::BuildWorldOptions options;
    options.threads = threads;
    const tools::SimulationSetup setup = tools::build_world(scene, options);
    double step_ms = 0.0;
    double serial_ms = 0.0;
    for (int frame = 0; frame < 60; ++frame) {
      const StepStats stats = setup.world->step(static_cast<float>(scene.time_step));
      const std::pair<double, double> phases[] = {
          {stats.broad_phase_ms, stats.broad_phase_serial_ms},
          {stats.narrow_phase_ms, stats.narrow_phase_serial_ms},
          {stats.contacts_ms, stats.contacts_serial_ms},
          {stats.response_ms, stats.response_serial_ms},
          {stats.integration_ms, stats.integration_serial_ms},
          {stats.sleep_ms, stats.sleep_serial_ms}};
      double phases_serial_ms = 0.0;
      for (const auto& [ms, serial] : phases) {
        EXPECT_GE(serial, 0.0);
        EXPECT_LE(serial, ms + kClockSlack);
        phases_serial_ms += serial;
      }
      EXPECT_LE(phases_serial_ms, stats.serial_ms + kClockSlack);
      EXPECT_LE(stats.serial_ms, stats.step_ms);
      step_ms += stats.step_ms;
      serial_ms += stats.serial_ms;
    }
    // On one thread the shares are the work's; on two they also hold the waits of a machine whose
    // cores other processes share, which a test cannot bound.
    if (threads == 1) {
      EXPECT_LT(serial_ms, 0.8 * step_ms);
    }
  }
}

}  // namespace
}  // namespace sphys
