"""What a body and a pair of bodies cost in memory (docs/performance.md, "Memory").

The heap in use (glibc's mallinfo2: every allocation sphys makes goes through malloc) is read
before a world is built and after it has stepped, in two kinds of scene of the same bunnies:

  spread  bunnies on a grid 3 m apart on the plane: every body, no pair of bodies
  piled   the stacks:SxN preset: the same count of bunnies in stacks of 10 that fall into heaps

Sleeping is off in both, so that every body keeps its ground contact and its place in the solver.

From the spread scenes at two sizes, the bytes per body (the slope, so what every world has once
drops out); from the piled scene at the larger size, the bytes per pair of overlapping bounds: its
heap beyond the spread scene's, over the broad phase's pairs at the end. Vectors keep their
capacity, so both are what a world holds at its largest, not at its tightest.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/memory_bench.py [--sizes 1000 4000]
"""

import argparse
import ctypes
import gc
import platform

import sphys


class MallInfo2(ctypes.Structure):
    _fields_ = [(name, ctypes.c_size_t) for name in (
        "arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks",
        "fordblks", "keepcost")]


_libc = ctypes.CDLL(None)
_libc.mallinfo2.restype = MallInfo2


def heap_in_use():
    """Bytes allocated and not freed: small blocks plus memory-mapped large ones."""
    gc.collect()
    info = _libc.mallinfo2()
    return info.uordblks + info.hblkhd


def spread_scene(count, depth):
    """`count` bunnies on a square grid 3 m apart, resting just above the plane."""
    scene = sphys.load_scene("stacks:1x1").to_dict()
    template = scene["bodies"][0]
    side = int(count ** 0.5 + 0.999)
    bodies = []
    for k in range(count):
        body = dict(template)
        body["position"] = [3.0 * (k % side), template["position"][1], 3.0 * (k // side)]
        bodies.append(body)
    scene["bodies"] = bodies
    return sphys.Scene.from_dict(scene)


def awake(scene):
    """The scene with sleeping off, so that every body keeps its contacts and solver rows."""
    d = scene.to_dict()
    d["sleep"]["enabled"] = False
    return sphys.Scene.from_dict(d)


def measure(scene, depth, frames):
    """Heap the world adds (bytes), the broad phase's pairs and the contacts at the end."""
    scene = awake(scene)
    before = heap_in_use()
    sim = sphys.Simulation(scene, depth=depth, threads=1)
    sim.step(frames)
    stats = sim.world.stats
    grown = heap_in_use() - before
    del sim
    return grown, stats.candidate_pairs, stats.contacts


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs=2, default=[1000, 4000],
                        help="bunnies in the smaller and the larger scenes (multiples of 10)")
    parser.add_argument("--depth", type=int, default=2, help="sphere-tree depth")
    parser.add_argument("--frames", type=int, default=300, help="steps before measuring")
    args = parser.parse_args()
    small, large = args.sizes

    print(f"machine: {platform.processor() or platform.machine()}, "
          f"Python {platform.python_version()}; depth {args.depth}, {args.frames} frames")
    spread = {}
    for count in (small, large):
        spread[count] = measure(spread_scene(count, args.depth), args.depth, args.frames)
        grown, pairs, contacts = spread[count]
        print(f"spread {count:6d}: heap +{grown / 2**20:8.2f} MiB, {pairs} pairs, "
              f"{contacts} contacts")
    piled = measure(sphys.load_scene(f"stacks:{large // 10}x10"), args.depth, args.frames)
    grown, pairs, contacts = piled
    print(f"piled  {large:6d}: heap +{grown / 2**20:8.2f} MiB, {pairs} pairs, "
          f"{contacts} contacts")

    per_body = (spread[large][0] - spread[small][0]) / (large - small)
    per_pair = (piled[0] - spread[large][0]) / max(pairs, 1)
    print(f"per body: {per_body / 1024:.2f} KiB; per pair of overlapping bounds: "
          f"{per_pair / 1024:.2f} KiB ({contacts / max(pairs, 1):.2f} contacts per pair)")


if __name__ == "__main__":
    main()
