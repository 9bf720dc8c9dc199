"""A planner's check: a batch of configurations of a three-sphere probe tested against a pile.

    python3 examples/python/check_configurations.py

A motion planner asks whether each of many configurations of its robot is free; sphys answers a
whole batch from numpy arrays at once, the robot given as spheres in the world frame. Here the
"robot" is a probe of three spheres in a row, placed at random over the pile and turned about
the vertical.
"""

import sys

import numpy as np

import sphys

CONFIGURATIONS = 10_000
PROBE_OFFSETS = np.array([-0.1, 0.0, 0.1])  # the spheres along the probe's axis. unit: m
PROBE_RADIUS = 0.04  # unit: m


def probe_spheres(positions, yaws):
    """(N, 3, 4) float32 spheres, x y z radius in m, of probes centred at `positions` (N, 3, m)
    and turned by `yaws` (N,, rad) about the vertical."""
    axes = np.stack([np.cos(yaws), np.zeros_like(yaws), np.sin(yaws)], axis=1)
    centres = positions[:, None, :] + PROBE_OFFSETS[None, :, None] * axes[:, None, :]
    radii = np.full(centres.shape[:2] + (1,), PROBE_RADIUS)
    return np.concatenate([centres, radii], axis=2).astype(np.float32)


def main():
    # A pile of 20 bunnies, dropped and left to settle for 3 s.
    simulation = sphys.Simulation("stacks:2x10", depth=2)
    simulation.step(180)
    world = simulation.world

    rng = np.random.default_rng(1)
    positions = rng.uniform((-0.6, 0.0, -0.6), (0.6, 1.0, 0.6), size=(CONFIGURATIONS, 3))
    yaws = rng.uniform(0.0, np.pi, size=CONFIGURATIONS)
    links = np.zeros(3, dtype=np.int32)  # one link: the probe is rigid
    result = world.check_configurations(probe_spheres(positions, yaws), links, threads=2)
    free = result["free"]
    print(f"{free.sum()} of {CONFIGURATIONS} configurations free; the first colliding one, "
          f"{np.flatnonzero(~free)[0]}, touches body slot {result['body'][~free][0]}")

    # Ground truth for two cases: far above the pile every probe is free, and a probe at a
    # bunny's centre of mass collides with it.
    above = world.check_configurations(probe_spheres(positions + (0, 5, 0), yaws), links)
    centres = simulation.poses()[:, :3].astype(np.float64)
    inside = world.check_configurations(
        probe_spheres(centres, np.zeros(len(centres))), links)
    ok = above["free"].all() and not inside["free"].any()
    print(f"5 m above the pile: {above['free'].sum()} free; at the bunnies' centres: "
          f"{(~inside['free']).sum()} of {len(centres)} colliding")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
