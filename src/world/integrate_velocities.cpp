// Paper mode's first stage: the velocities under gravity and the forces applied for the step (the
// first half of semi-implicit Euler).

#include "core/stopwatch.h"
#include "world/applied_forces.h"
#include "world/awake_runs.h"
#include "world/stages.h"

namespace sphys {

void integrate_velocities(PassContext& pass) {
  const PhaseClock clock(&pass.world.parallel);
  WorldState& world = pass.world;
  BodyStore& store = world.store;
  const std::span<Vec3> linear = store.linear_velocities();
  const std::span<Vec3> angular = store.angular_velocities();
  // Velocities stay finite here whatever they were: integrate_positions finds a body that is not.
  world.parallel.for_each_run(
      store.awake().size(), kAwakeBodiesPerRun, [&](std::size_t begin, std::size_t end) {
        for (const std::uint32_t body : store.awake().subspan(begin, end - begin)) {
          const AppliedForces applied = applied_forces(world, body, pass.pass_dt);
          linear[body] += applied.acceleration * pass.pass_dt;
          angular[body] += applied.spin_gained;
        }
      });
  clock.add_to(pass.stats.integration_ms, pass.stats.integration_serial_ms);
}

}  // namespace sphys
