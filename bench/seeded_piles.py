"""The paper's layouts and 1,000 bunnies over several seeds of their bunnies' yaw angles.

A pile is chaotic: one run of a scene says little of a solver change, as another seed of the same
layout comes to rest a hundred frames earlier or later. For each scene and seed this runs the
preset on the exact plane and prints the deepest penetration, the overlap at the end and the frame
from which every bunny is at rest, then per scene the mean of those frames and how many runs fall
outside the plausibility bounds (deepest under 5% of a bunny, every bunny asleep by the end,
overlap at the end under 1 mm per metre of bunny).

    PYTHONPATH=build/release/python /usr/bin/python3 bench/seeded_piles.py [--seeds 2008 1 2 ...]
"""

import argparse
import statistics
import sys

import sphys

# The layouts and tree depths of the paper's experiment, and the 1,000-bunny heap.
SCENES = ["4x25:2", "4x25:3", "4x50:2", "4x50:3", "8x10:2", "8x10:3", "8x20:2", "8x20:3",
          "100x10:2"]
# The preset's own seed first, then six more.
SEEDS = [2008, 1, 2, 3, 4, 5, 6]
MOST_DEEPEST = 0.05  # of the bunny's size
MOST_OVERLAP = 0.001  # of the bunny's size


def run(layout, depth, seed, threads):
    """One run's summary (what `sphys simulate --json` prints)."""
    scene = sphys.load_scene(f"stacks:{layout}", seed=seed)
    return sphys.Simulation(scene, depth=depth, threads=threads).run()


def inside_bounds(summary):
    size = summary["largest_body_size_m"]
    return (summary["deepest_penetration_m"] < MOST_DEEPEST * size
            and summary["bodies_asleep"] == summary["movable_bodies"]
            and summary["end_overlap_m"] < MOST_OVERLAP * size)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", nargs="+", default=SCENES, help="LAYOUT:DEPTH, e.g. 8x20:2")
    parser.add_argument("--seeds", nargs="+", type=int, default=SEEDS)
    parser.add_argument("--threads", type=int, default=1)
    args = parser.parse_args(argv)

    print("| scene | per seed: deepest %, overlap mm, all at rest from frame | mean frame "
          "| outside |")
    print("| --- | --- | --- | --- |")
    outside_total = 0
    for name in args.scenes:
        layout, depth = name.split(":")
        runs = [run(layout, int(depth), seed, args.threads) for seed in args.seeds]
        cells = []
        for summary in runs:
            mark = "" if inside_bounds(summary) else "**out** "
            cells.append(f"{mark}{summary['deepest_penetration_percent_of_size']:.1f}, "
                         f"{1000 * summary['end_overlap_m']:.2f}, "
                         f"{summary['all_at_rest_from_frame']}")
        frames = [r["all_at_rest_from_frame"] for r in runs if r["all_at_rest_from_frame"] >= 0]
        mean = f"{statistics.mean(frames):.0f}" if frames else "—"
        outside = sum(not inside_bounds(r) for r in runs)
        outside_total += outside
        print(f"| {layout} d{depth} | {'; '.join(cells)} | {mean} | {outside} of {len(runs)} |")
    print(f"\n{outside_total} runs outside the bounds, seeds {' '.join(map(str, args.seeds))}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
