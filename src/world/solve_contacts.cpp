// Plausible mode's response: each contact's material, then the soft step, which integrates and
// moves the bodies in its own substeps.

#include "core/stopwatch.h"
#include "dynamics/soft_step_context.h"
#include "world/mix_materials.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {

void solve_contacts(PassContext& pass) {
  const PhaseClock clock(&pass.world.parallel);
  WorldState& world = pass.world;
  const std::span<const Contact> contacts = world.detector.contacts();
  mix_materials(world);
  // Every collision pass gets all the soft step's substeps, even when fast bodies split a frame
  // into several: sharing them out (a quarter each of four) let a blow into a pile sink bodies
  // 10% of a bunny deep, against 4% (stacks:4x50, depth 2).
  const SolverSettings& solver = world.settings.solver;
  const SoftStepContext context(solver, world.settings.gravity, pass.pass_dt, solver.soft_substeps,
                                world.parallel);
  world.joint_solver.set_joints(world.joints.all());
  const SoftStepStats solved = world.solver.solve(world.store, contacts, world.detector.memory(),
                                                  world.materials, context, &world.joint_solver);
  StepStats& stats = pass.stats;
  stats.contacts_solved += solved.contacts_solved;
  stats.warm_started += solved.warm_started;
  stats.bounces += solved.bounces;
  stats.response_passes += 2 * solver.soft_substeps;  // a solve and a relax pass per substep
  stats.contacts += static_cast<std::uint32_t>(contacts.size());
  clock.add_to(stats.response_ms, stats.response_serial_ms);
}

}  // namespace sphys
