"""Bodies spawned on top of each other, as a game might spawn them (docs/performance.md, "Crowds"):
N icospheres of radius 5 cm (a 2-subdivision icosphere's default sphere-tree, 1,000 kg/m³) all
at one point 1 m above the exact ground plane, then stepped at 60 steps per second in the
plausible response with default settings.

Prints, as JSON: the wall time of the first step, of the first three and of the first 60 (the
steps alone, not the measuring between them), the fastest
body speed seen over the run (|v| of the centre plus |w| times the radius), the deepest overlap
of two balls (2r minus the distance of their centres, which bounds the overlap of their meshes)
every `--check-every` steps, the first time it stays under 1 mm, the lowest centre, and the
peak resident set. Works with any build of the module that has World, build_tree and icosphere.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/crowd_spawn.py --bodies 1000 \\
        [--seconds 5] [--steps N]
"""

import argparse
import json
import math
import time

import numpy as np

import sphys

RADIUS = 0.05  # unit: m
DENSITY = 1000.0  # unit: kg/m³
DT = 1.0 / 60.0  # unit: s


def status_mb(field):
    """VmHWM (the peak resident set) or VmRSS of this process, in MB."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024
    return float("nan")


def deepest_overlap(centres):
    """The largest 2r - |c_i - c_j| over all pairs of balls (m), by rows to bound memory."""
    deepest = -math.inf
    for start in range(0, len(centres), 512):
        block = centres[start:start + 512]
        d2 = ((block[:, None, :] - centres[None, :, :]) ** 2).sum(axis=2)
        for k in range(len(block)):
            d2[k, start + k] = math.inf
        deepest = max(deepest, 2 * RADIUS - math.sqrt(d2.min()))
    return deepest


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bodies", type=int, default=1000)
    parser.add_argument("--seconds", type=float, default=5.0, help="simulated time to run (s)")
    parser.add_argument("--steps", type=int, default=0, help="steps to run instead of --seconds")
    parser.add_argument("--check-every", type=int, default=15, help="steps between overlap checks")
    args = parser.parse_args()

    tree = sphys.build_tree(sphys.icosphere(RADIUS, 2))
    mass = DENSITY * 4.0 / 3.0 * math.pi * RADIUS**3
    inertia = np.eye(3) * 0.4 * mass * RADIUS**2
    world = sphys.World(ground_plane=0.0)
    for _ in range(args.bodies):
        world.add_body(tree, position=(0.0, 1.0, 0.0), mass=mass, inertia=inertia)

    steps = args.steps or round(args.seconds / DT)
    result = {"bodies": args.bodies, "steps": steps}
    fastest = 0.0
    separated_at = None
    overlaps = []
    stepping_s = 0.0
    start = time.perf_counter()
    for step in range(1, steps + 1):
        step_start = time.perf_counter()
        stats = world.step(DT)
        stepping_s += time.perf_counter() - step_start
        if step == 1:
            result["first_step_s"] = stepping_s
            result["first_step_stats"] = {k: v for k, v in stats.to_dict().items()
                                          if not k.endswith("_ms") and v is not None}
        if step == 3:
            result["first_3_steps_s"] = stepping_s
        if step == 60:
            result["first_60_steps_s"] = stepping_s
        velocities = world.velocities()
        speeds = (np.linalg.norm(velocities[:, :3], axis=1)
                  + RADIUS * np.linalg.norm(velocities[:, 3:], axis=1))
        fastest = max(fastest, float(speeds.max()))
        if step % args.check_every == 0 or step == steps:
            deepest = deepest_overlap(world.poses()[:, :3].astype(np.float64))
            overlaps.append((round(step * DT, 3), round(deepest * 1000, 2)))
            if deepest < 0.001:
                separated_at = separated_at if separated_at is not None else step * DT
            else:
                separated_at = None
    result["wall_s"] = time.perf_counter() - start
    result["fastest_m_per_s"] = fastest
    result["deepest_overlap_mm_by_time_s"] = overlaps
    result["separated_for_good_at_s"] = separated_at
    result["lowest_centre_m"] = float(world.poses()[:, 1].min())
    result["peak_rss_mb"] = status_mb("VmHWM")
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
