"""A soak of the plausible world (docs/reliability.md, "Soak"): a heap that is never left alone.

Runs `stacks:100x10` (1,000 bunnies, depth 2) on the exact ground plane in the plausible response
for MINUTES of simulated time at 60 steps per second. (The preset's 16 m octree ground is
narrower than its 100 stacks: half the heap would slide off it and fall for ever.) Every simulated second one bunny, chosen by a fixed-seed generator, is
removed and a fresh one is dropped from 6 m above a random point over the pile, so the body
count stays 1,000 and the world keeps adding, removing, waking and putting bodies to sleep.

Checked, and the run fails (exit 1) when one does not hold:
  * no step goes non-finite;
  * memory is flat after the first simulated minute: the resident set at each later minute
    stays within --rss-slack MB of the first minute's (printed per minute with the peak);
  * the recording (one frame per simulated second, the 1,000 slots' poses) reads back whole
    with a frame for every second;
  * at the end no bunny's centre is below the ground.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/soak.py [--minutes 30] [--out DIR]
"""

import argparse
import os
import platform
import random
import sys
import time

import numpy as np

import sphys

STEPS_PER_S = 60


def status_mb(field):
    """A memory figure of this process from /proc/self/status (Linux), in MB: VmRSS, the resident
    set now; VmHWM, its peak."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024
    raise RuntimeError(f"no {field} in /proc/self/status")


def rss_mb():
    return status_mb("VmRSS")


def peak_rss_mb():
    return status_mb("VmHWM")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--minutes", type=float, default=30.0, help="simulated minutes (default 30)")
    parser.add_argument("--scene", default="stacks:100x10", help="the heap (default stacks:100x10)")
    parser.add_argument("--depth", type=int, default=2, help="sphere-tree depth (default 2)")
    parser.add_argument("--seed", type=int, default=2008, help="which bunnies go, where new ones fall")
    parser.add_argument("--rss-slack", type=float, default=32.0,
                        help="MB the resident set may grow after the first minute (default 32)")
    parser.add_argument("--out", default="out/soak", help="folder for soak.sphysrec")
    args = parser.parse_args(argv)
    if not args.minutes > 0:
        parser.error("--minutes must be positive")

    layout = sphys.load_scene(args.scene).to_dict()
    layout["ground"] = {"type": "plane", "height": 0.0}
    scene = sphys.Scene.from_dict(layout, args.scene)
    sim = sphys.Simulation(scene, depth=args.depth)
    world = sim.world
    first = scene.to_dict()["bodies"][0]
    density = first["density"]
    tree_spec = first["sphere_tree"]
    depth = args.depth
    # The dropped bunnies: the preset's own shape (1 m bunny, its density and tree method).
    bunny = sphys.normalize(sphys.load_model("bunny"), first["size"], density=density).mesh
    mass = sphys.mass_properties(bunny, density=density)
    tree = sphys.build_tree(bunny, method=tree_spec["method"], branching=tree_spec["branching"],
                            depth=depth)
    slots = list(sim.body_ids)
    start_poses = sim.poses()
    lo, hi = start_poses[:, [0, 2]].min(axis=0), start_poses[:, [0, 2]].max(axis=0)
    rng = random.Random(args.seed)

    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "soak.sphysrec")
    seconds = int(round(args.minutes * 60))
    dt = scene.time_step
    print(f"soak      {args.scene} on the plane: {len(slots)} bodies, depth {depth}, plausible, "
          f"{seconds} s simulated at {STEPS_PER_S} steps/s; {platform.machine()}, "
          f"Python {platform.python_version()}", flush=True)
    print(f"{'minute':>6} {'rss MB':>8} {'peak MB':>8} {'asleep':>7} {'contacts':>9} "
          f"{'ms/step':>8} {'wall s':>7}", flush=True)
    failures = []
    minute_rss = []
    wall_start = time.perf_counter()
    with sphys.RecordingWriter(path, len(slots), 1.0, scene.to_json()) as recording:
        recording.add_frame(world.poses(slots))
        minute_wall = time.perf_counter()
        for second in range(1, seconds + 1):
            for _ in range(STEPS_PER_S):
                stats = world.step(dt)
                if stats.non_finite_body is not None or world.stopped:
                    failures.append(f"second {second}: body {stats.non_finite_body} went non-finite")
                    break
            if failures:
                break
            # One bunny goes, a fresh one falls into its slot.
            slot = rng.randrange(len(slots))
            world.remove_body(slots[slot])
            x, z = rng.uniform(lo[0], hi[0]), rng.uniform(lo[1], hi[1])
            height = float(world.poses(slots[:slot] + slots[slot + 1:])[:, 1].max()) + 6.0
            slots[slot] = world.add_body(tree, position=(x, height, z), mass=mass.mass,
                                         inertia=mass.inertia, orientation=(0, 0, 0, 1))
            recording.add_frame(world.poses(slots))
            if second % 60 == 0:
                now = time.perf_counter()
                minute_rss.append(rss_mb())
                print(f"{second // 60:>6} {minute_rss[-1]:>8.1f} {peak_rss_mb():>8.1f} "
                      f"{stats.bodies_asleep:>7} {stats.contacts:>9} "
                      f"{(now - minute_wall) / (60 * STEPS_PER_S) * 1e3:>8.3f} "
                      f"{now - wall_start:>7.0f}", flush=True)
                minute_wall = now
    if len(minute_rss) >= 2:
        growth = max(minute_rss[1:]) - minute_rss[0]
        print(f"memory    first minute {minute_rss[0]:.1f} MB, largest later {max(minute_rss[1:]):.1f} "
              f"MB (+{growth:.1f} MB), peak {peak_rss_mb():.1f} MB")
        if growth > args.rss_slack:
            failures.append(f"the resident set grew by {growth:.1f} MB after the first minute")
    read = sphys.read_recording(path)
    expected_frames = (second if not failures else 0) + 1
    print(f"recording {path}: {read.frame_count} frames of {read.body_count} bodies, "
          f"{os.path.getsize(path) / 1e6:.1f} MB")
    if not failures and read.frame_count != expected_frames:
        failures.append(f"the recording has {read.frame_count} frames, not {expected_frames}")
    lowest = float(world.poses(slots)[:, 1].min())
    below = int((world.poses(slots)[:, 1] < 0.0).sum())
    print(f"end       lowest centre y {lowest:.3f} m, {below} below the ground, "
          f"{world.stats.bodies_asleep} of {len(slots)} asleep, {time.perf_counter() - wall_start:.0f} s wall")
    if below:
        failures.append(f"{below} bodies ended below the ground")
    for failure in failures:
        print(f"FAILED    {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
