"""A pile of bunnies dropped on the ground plane, each bunny's height plotted over time to a PNG.

    python3 examples/python/drop_pile.py [OUT.png]

after `pip install .` (README.md), or with PYTHONPATH=build/release/python and Debian's
/usr/bin/python3. Needs matplotlib (Debian: python3-matplotlib).
"""

import sys

import matplotlib

matplotlib.use("Agg")  # draws to a file: no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import sphys  # noqa: E402

FRAMES = 240  # 4 s at the scene's 60 frames per second


def main(out="drop_pile.png"):
    # Two stacks of ten bunnies over the exact plane y = 0, in sphys's plausible mode.
    simulation = sphys.Simulation("stacks:2x10", depth=2)
    heights = np.empty((FRAMES + 1, len(simulation.body_ids)))  # unit: m
    heights[0] = simulation.poses()[:, 1]
    for frame in range(1, FRAMES + 1):
        simulation.step()
        heights[frame] = simulation.poses()[:, 1]
    times = np.arange(FRAMES + 1) * simulation.scene.time_step  # unit: s

    figure, axes = plt.subplots(figsize=(7, 4))
    axes.plot(times, heights, linewidth=0.8)
    axes.set_xlabel("time (s)")
    axes.set_ylabel("height of each bunny's centre of mass (m)")
    axes.set_title(f"{heights.shape[1]} bunnies dropped on the plane")
    figure.tight_layout()
    figure.savefig(out, dpi=100)

    summary = simulation.summary()
    print(f"{out}: lowest {heights[-1].min():.3f} m, highest {heights[-1].max():.3f} m at "
          f"{times[-1]:.1f} s; {summary['bodies_asleep']} of {heights.shape[1]} asleep")
    # A pile at rest on the plane: every centre of mass above it.
    return 0 if heights[-1].min() > 0.0 else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
