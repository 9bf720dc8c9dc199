// The soft step's passes give the same bits whichever lanes run them: AVX2 (where the processor
// has it), SSE2, plain floats of the same width, and one manifold at a time. Blocks of random
// manifolds (penetrating and apart, inside and outside their friction discs, bouncing and not)
// between bodies that no two lanes of a block share, as the constraint graph's colours guarantee.

#include "dynamics/contact_lanes.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/simd.h"
#include "dynamics/contact_lane_kernels.h"
#include "sphys/error.h"
#include "sphys/solver_settings.h"
#include "sphys/world.h"

namespace sphys {
namespace {

constexpr int kW = kLaneWidth;
constexpr int kBlocks = 64;
// Two bodies per lane, each in one lane only, and one more slot for an immovable body.
constexpr std::size_t kLaneBodies = 2 * kW * kBlocks + 1;

// The solver's body rows: velocities (linear, angular) and motion (translation, rotation matrix),
// kBodyRow floats a slot each.
struct BodyArrays {
  std::vector<float> velocity = std::vector<float>(kBodyRow * kLaneBodies);
  std::vector<float> motion = std::vector<float>(kBodyRow * kLaneBodies);
  LaneBodies view() { return {velocity.data(), motion.data()}; }
};

struct Scenario {
  std::vector<ManifoldBlock<kW>> blocks = std::vector<ManifoldBlock<kW>>(kBlocks);
  BodyArrays bodies;
};

Scenario random_scenario(std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> positive(0.1f, 2.0f);
  Scenario s;
  const auto immovable = static_cast<std::uint32_t>(kLaneBodies - 1);
  for (std::size_t i = 0; i + 1 < kLaneBodies; ++i) {
    float* velocity = &s.bodies.velocity[kBodyRow * i];
    float* motion = &s.bodies.motion[kBodyRow * i];
    for (int k = 0; k < 6; ++k) velocity[k] = unit(random);
    // The row's floats past the velocities must come back as they were.
    for (std::size_t k = 6; k < kBodyRow; ++k) velocity[k] = unit(random);
    for (int k = 0; k < 3; ++k) motion[k] = 0.01f * unit(random);
    // A small rotation: the identity plus a little.
    for (int k = 0; k < 9; ++k) motion[3 + k] = (k % 4 == 0 ? 1.0f : 0.0f) + 0.01f * unit(random);
  }
  for (int k = 0; k < 9; ++k) {
    s.bodies.motion[kBodyRow * immovable + 3 + k] = k % 4 == 0 ? 1.0f : 0.0f;
  }
  std::uint32_t next_body = 0;
  for (ManifoldBlock<kW>& m : s.blocks) {
    m = {};
    m.point_count = kManifoldPoints;
    for (int lane = 0; lane < kW; ++lane) {
      // Every fourth lane against an immovable body, as the ground.
      const bool a_moves = lane % 4 != 3;
      m.body_a[lane] = a_moves ? next_body : immovable;
      m.body_b[lane] = next_body + 1;
      next_body += 2;
      m.a_moves[lane] = a_moves ? 1u : 0u;
      m.b_moves[lane] = 1u;
      m.inverse_mass_a[lane] = a_moves ? positive(random) : 0.0f;
      m.inverse_mass_b[lane] = positive(random);
      for (int k = 0; k < 9; ++k) {
        const float diagonal = k % 4 == 0 ? 1.0f : 0.0f;
        m.inverse_inertia_a[k][lane] = a_moves ? diagonal * positive(random) : 0.0f;
        m.inverse_inertia_b[k][lane] = diagonal * positive(random);
        m.rolling_mass[k][lane] = diagonal * positive(random);
      }
      for (auto& r : m.rolling_impulse) r[lane] = 0.1f * unit(random);
      m.friction[lane] = 0.5f * positive(random);
      m.restitution[lane] = lane % 2 == 0 ? 0.5f : 0.0f;
      m.bias_rate[lane] = 10.0f * positive(random);
      // Friction at the centre: a frame and kept impulses (of any size: some inside their bounds
      // and some outside).
      for (int k = 0; k < 3; ++k) {
        m.friction_normal[k][lane] = unit(random);
        m.tangent1[k][lane] = unit(random);
        m.centre_a[k][lane] = 0.5f * unit(random);
        m.centre_b[k][lane] = 0.5f * unit(random);
      }
      m.tangent_mass[0][lane] = positive(random);
      m.tangent_mass[1][lane] = 0.1f * unit(random);
      m.tangent_mass[2][lane] = positive(random);
      m.twist_mass[lane] = positive(random);
      m.friction_impulse[0][lane] = 0.2f * unit(random);
      m.friction_impulse[1][lane] = 0.2f * unit(random);
      m.twist_impulse[lane] = 0.05f * unit(random);
      // Lanes with fewer points than the block's most: the rest stay zero.
      const int points = 1 + lane % kManifoldPoints;
      for (int i = 0; i < points; ++i) {
        auto& p = m.points[i];
        for (int k = 0; k < 3; ++k) {
          p.normal[k][lane] = unit(random);
          p.ra[k][lane] = 0.5f * unit(random);
          p.rb[k][lane] = 0.5f * unit(random);
        }
        p.impulse[lane] = 0.2f * positive(random);
        p.mass[lane] = positive(random);
        p.lever[lane] = 0.1f * positive(random);
        p.mass_scale[lane] = 0.5f * positive(random);
        p.impulse_scale[lane] = 0.1f * positive(random);
        // Apart by up to 5 cm or into each other by up to 5 cm.
        p.base_separation[lane] = 0.05f * unit(random);
        p.approach[lane] = 3.0f * unit(random);
      }
    }
  }
  return s;
}

// A substep of 1/240 s, and the default solver's slop, correction speed, rolling arm and
// restitution threshold.
constexpr LaneSettings kSettings{.inverse_substep_dt = 240.0f,
                                 .linear_slop = 0.0004f,
                                 .max_correction_speed = 3.0f,
                                 .rolling_resistance = 0.01f,
                                 .restitution_threshold = 1.0f};

// The passes of one step: warm start, solve, relax, restitution; returns the bounces.
template <class F>
std::uint32_t run_passes(std::span<ManifoldBlock<F::kWidth>> blocks, BodyArrays& bodies) {
  const LaneBodies view = bodies.view();
  lanes::warm_start<F>(blocks, view);
  lanes::solve<F>(blocks, view, kSettings, true);
  lanes::solve<F>(blocks, view, kSettings, false);
  return lanes::restitute<F>(blocks, view, kSettings);
}

// One lane of a block as a block of its own.
ManifoldBlock<1> lane_of(const ManifoldBlock<kW>& m, int lane) {
  ManifoldBlock<1> one{};
  const auto copy = [&](const auto& from, auto& to) {
    using From = std::remove_cvref_t<decltype(from)>;
    constexpr std::size_t kRows = sizeof(From) / sizeof(from[0]);
    for (std::size_t r = 0; r < kRows; ++r) to[r][0] = from[r][lane];
  };
  for (int i = 0; i < kManifoldPoints; ++i) {
    const auto& p = m.points[i];
    auto& q = one.points[i];
    copy(p.normal, q.normal);
    copy(p.ra, q.ra);
    copy(p.rb, q.rb);
    q.mass[0] = p.mass[lane];
    q.impulse[0] = p.impulse[lane];
    q.lever[0] = p.lever[lane];
    q.mass_scale[0] = p.mass_scale[lane];
    q.impulse_scale[0] = p.impulse_scale[lane];
    q.base_separation[0] = p.base_separation[lane];
    q.approach[0] = p.approach[lane];
    q.max_normal_impulse[0] = p.max_normal_impulse[lane];
  }
  copy(m.inverse_inertia_a, one.inverse_inertia_a);
  copy(m.inverse_inertia_b, one.inverse_inertia_b);
  copy(m.rolling_mass, one.rolling_mass);
  copy(m.rolling_impulse, one.rolling_impulse);
  copy(m.friction_normal, one.friction_normal);
  copy(m.tangent1, one.tangent1);
  copy(m.centre_a, one.centre_a);
  copy(m.centre_b, one.centre_b);
  copy(m.tangent_mass, one.tangent_mass);
  copy(m.friction_impulse, one.friction_impulse);
  one.twist_mass[0] = m.twist_mass[lane];
  one.twist_impulse[0] = m.twist_impulse[lane];
  one.inverse_mass_a[0] = m.inverse_mass_a[lane];
  one.inverse_mass_b[0] = m.inverse_mass_b[lane];
  one.friction[0] = m.friction[lane];
  one.restitution[0] = m.restitution[lane];
  one.bias_rate[0] = m.bias_rate[lane];
  one.body_a[0] = m.body_a[lane];
  one.body_b[0] = m.body_b[lane];
  one.a_moves[0] = m.a_moves[lane];
  one.b_moves[0] = m.b_moves[lane];
  one.point_count = m.point_count;
  return one;
}

std::vector<std::uint32_t> bits(std::span<const float> values) {
  std::vector<std::uint32_t> out;
  out.reserve(values.size());
  for (const float v : values) out.push_back(std::bit_cast<std::uint32_t>(v));
  return out;
}

void expect_same_bodies(const BodyArrays& x, const BodyArrays& y) {
  EXPECT_EQ(bits(x.velocity), bits(y.velocity));
}

TEST(ContactLanes, SimdLanesPlainFloatsAndSingleLanesGiveTheSameBits) {
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    const Scenario start = random_scenario(seed);

    Scenario portable = start;
    const std::uint32_t portable_bounces =
        run_passes<PortableLanes<kW>>(portable.blocks, portable.bodies);

    // Each set of lanes this processor has, through the table the solver uses.
    std::vector<Scenario> by_table;
    for (const SolverLanes lanes :
         {SolverLanes::kPortable, SolverLanes::kSse2, SolverLanes::kAvx2}) {
      SCOPED_TRACE(solver_lanes_name(lanes));
      try {
        EXPECT_EQ(resolve_solver_lanes(lanes), lanes);
      } catch (const Error& error) {
        // Only AVX2 may be missing, and then the message says so.
        EXPECT_EQ(lanes, SolverLanes::kAvx2) << error.what();
        EXPECT_NE(std::string(error.what()).find("avx2"), std::string::npos) << error.what();
        continue;
      }
      Scenario run = start;
      const LaneKernels<kW>& kernels = lane_kernels(lanes);
      const LaneBodies view = run.bodies.view();
      kernels.warm_start(run.blocks, view);
      kernels.solve(run.blocks, view, kSettings, true);
      kernels.solve(run.blocks, view, kSettings, false);
      const std::uint32_t bounces = kernels.restitute(run.blocks, view, kSettings);
      expect_same_bodies(run.bodies, portable.bodies);
      EXPECT_EQ(bounces, portable_bounces);
      by_table.push_back(run);
    }
    ASSERT_GE(by_table.size(), 2u);  // portable and SSE2 at least, on x86-64

    // Each pass over every lane one at a time, block by block in the same order.
    Scenario single = start;
    std::vector<ManifoldBlock<1>> lanes;
    for (const ManifoldBlock<kW>& m : single.blocks) {
      for (int lane = 0; lane < kW; ++lane) lanes.push_back(lane_of(m, lane));
    }
    const std::uint32_t single_bounces = run_passes<PortableLanes<1>>(lanes, single.bodies);
    expect_same_bodies(single.bodies, portable.bodies);
    EXPECT_EQ(single_bounces, portable_bounces);

    // Impulses too, lane for lane: the points' normal ones, and each manifold's friction and
    // twist.
    const auto same_bits = [&](float x, float expected) {
      EXPECT_EQ(std::bit_cast<std::uint32_t>(x), std::bit_cast<std::uint32_t>(expected));
    };
    for (std::size_t b = 0; b < portable.blocks.size(); ++b) {
      const ManifoldBlock<kW>& expected = portable.blocks[b];
      for (int lane = 0; lane < kW; ++lane) {
        const ManifoldBlock<1>& one = lanes[b * kW + lane];
        const auto each_impulse = [&](const auto& block, int l) {
          for (int i = 0; i < kManifoldPoints; ++i) {
            same_bits(block.points[i].impulse[l], expected.points[i].impulse[lane]);
          }
          for (int r = 0; r < 2; ++r) {
            same_bits(block.friction_impulse[r][l], expected.friction_impulse[r][lane]);
          }
          same_bits(block.twist_impulse[l], expected.twist_impulse[lane]);
        };
        for (const Scenario& run : by_table) each_impulse(run.blocks[b], lane);
        each_impulse(one, 0);
      }
    }
    // The scenario did exercise what it should: some points bounced, and the passes moved the
    // bodies.
    EXPECT_GT(portable_bounces, 0u);
    EXPECT_NE(bits(portable.bodies.velocity), bits(start.bodies.velocity));
    // The immovable body's row was never written.
    const std::size_t immovable = kBodyRow * (kLaneBodies - 1);
    for (const Scenario* run : {&portable, &single}) {
      for (std::size_t k = 0; k < kBodyRow; ++k) {
        EXPECT_EQ(run->bodies.velocity[immovable + k], start.bodies.velocity[immovable + k]);
      }
    }
  }
}

// The pieces of arithmetic that could round apart: min and max of equal and signed zeros, the
// select of a comparison with NaN, square roots and quotients.
TEST(ContactLanes, EachLaneOperationRoundsAsThePlainFloat) {
  alignas(32) float a[kW];
  alignas(32) float b[kW];
  const float cases[][2] = {{0.0f, -0.0f},   {-0.0f, 0.0f}, {1.0f, 3.0f}, {2.5f, -7.0f},
                            {1e-30f, 3e-8f}, {7.0f, 7.0f},  {0.1f, 0.3f}, {-1e30f, 1e-30f}};
  for (std::size_t start = 0; start < std::size(cases); start += kW) {
    for (int lane = 0; lane < kW; ++lane) {
      a[lane] = cases[(start + lane) % std::size(cases)][0];
      b[lane] = cases[(start + lane) % std::size(cases)][1];
    }
    const auto same = [&](auto native, auto portable) {
      alignas(32) float x[kW];
      alignas(32) float y[kW];
      native.store(x);
      portable.store(y);
      for (int lane = 0; lane < kW; ++lane) {
        EXPECT_EQ(std::bit_cast<std::uint32_t>(x[lane]), std::bit_cast<std::uint32_t>(y[lane]))
            << "lane " << lane;
      }
    };
#if defined(__SSE2__)
    using Native = Sse2PairLanes;
#else
    using Native = PortableLanes<kW>;
#endif
    using Plain = PortableLanes<kW>;
    const Native na = Native::load(a);
    const Native nb = Native::load(b);
    const Plain pa = Plain::load(a);
    const Plain pb = Plain::load(b);
    same(min(na, nb), min(pa, pb));
    same(max(na, nb), max(pa, pb));
    same(na / nb, pa / pb);
    same(sqrt(max(na, nb)), sqrt(max(pa, pb)));
    same(select(na < nb, na, nb), select(pa < pb, pa, pb));
    same(select((na > nb) & (nb > Native::splat(0.0f)), na - nb, na * nb),
         select((pa > pb) & (pb > Plain::splat(0.0f)), pa - pb, pa * pb));
  }
}

// auto takes SPHYS_SIMD where it is set, and refuses a value it cannot read by naming it; unset, it
// takes the widest lanes there are. A world names the lanes it resolved.
// SPHYS_SIMD as the process had it, put back when the test ends however it ends.
class KeepSphysSimd {
 public:
  KeepSphysSimd() {
    if (const char* text = std::getenv("SPHYS_SIMD")) saved_ = text;
    unsetenv("SPHYS_SIMD");
  }
  KeepSphysSimd(const KeepSphysSimd&) = delete;
  KeepSphysSimd& operator=(const KeepSphysSimd&) = delete;
  ~KeepSphysSimd() {
    if (saved_) {
      setenv("SPHYS_SIMD", saved_->c_str(), 1);
    } else {
      unsetenv("SPHYS_SIMD");
    }
  }

 private:
  std::optional<std::string> saved_;
};

TEST(SolverLanes, AutoReadsSphysSimdAndTheWorldNamesWhatItResolved) {
  const KeepSphysSimd keep;
  const SolverLanes widest = resolve_solver_lanes(SolverLanes::kAuto);
  EXPECT_NE(widest, SolverLanes::kAuto);
  ASSERT_EQ(setenv("SPHYS_SIMD", "portable", 1), 0);
  EXPECT_EQ(resolve_solver_lanes(SolverLanes::kAuto), SolverLanes::kPortable);
  // An explicit setting is not overridden.
  EXPECT_EQ(resolve_solver_lanes(SolverLanes::kSse2), SolverLanes::kSse2);
  ASSERT_EQ(setenv("SPHYS_SIMD", "sse2", 1), 0);
  EXPECT_EQ(resolve_solver_lanes(SolverLanes::kAuto), SolverLanes::kSse2);
  ASSERT_EQ(setenv("SPHYS_SIMD", "avx512", 1), 0);
  try {
    (void)resolve_solver_lanes(SolverLanes::kAuto);
    ADD_FAILURE() << "SPHYS_SIMD=avx512 was accepted";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("SPHYS_SIMD"), std::string::npos) << message;
    EXPECT_NE(message.find("\"avx512\""), std::string::npos) << message;
    EXPECT_NE(message.find("portable, sse2 or avx2"), std::string::npos) << message;
  }
  ASSERT_EQ(unsetenv("SPHYS_SIMD"), 0);
  EXPECT_EQ(resolve_solver_lanes(SolverLanes::kAuto), widest);
  EXPECT_EQ(solver_lanes_name(SolverLanes::kAvx2), "avx2");

  WorldSettings settings;
  EXPECT_EQ(World(settings).solver_lanes(), widest);
  EXPECT_EQ(World(settings).settings().solver.lanes, SolverLanes::kAuto);  // as given
  settings.solver.lanes = SolverLanes::kPortable;
  EXPECT_EQ(World(settings).solver_lanes(), SolverLanes::kPortable);
}

}  // namespace
}  // namespace sphys
