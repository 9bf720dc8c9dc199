"""What stepping from a Python loop costs over stepping in C++ (docs/python.md, "Benchmark").

Builds identical simulations of a scene (default stacks:4x50 at the preset's depth), steps them
all through an untimed warm-up, then runs rounds of chunks of K frames each:

  A  sim.step(frames=K)                          the loop in C++, one call per chunk
  B  for _ in range(K): sim.step()               the loop in Python, one call per step
  C  for _ in range(K): sim.world.step(dt)       the same on the World, without the Simulation's
                                                 frame count and totals (--no-world leaves it out)

Each chunk is timed with time.perf_counter. Every simulation steps the same frames of the same
pile in every round, so the chunks of a round do the same physics (the poses are compared bit for
bit after every round), and the order of the variants turns round by round so that a slow spell
of the machine falls on all of them. Reported per variant: the mean ms per step (all timed steps)
and the median over chunks of a chunk's ms per step; the ratios of means and of medians over A,
the median of the per-round ratios, and the per-call overhead (B - A) in microseconds. Finally the
bare cost of a call: an empty World and an empty Simulation stepped from a Python loop against
the same steps in one call.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_step_bench.py [--frames N]
"""

import argparse
import platform
import statistics
import sys
import time

import numpy

import sphys


def _chunk_a(sim, k):
    sim.step(frames=k)


def _chunk_b(sim, k):
    for _ in range(k):
        sim.step()


def _make_chunk_c(dt):
    def chunk(sim, k):
        world = sim.world
        for _ in range(k):
            world.step(dt)
    return chunk


def _bare_call_us(calls):
    """Microseconds per call of an empty World's step and an empty Simulation's step from a Python
    loop, beyond the same steps made by one call (best of 5 alternating tries each)."""
    world = sphys.World()
    empty = sphys.Simulation(sphys.Scene.from_dict(
        {"format": "sphys-scene", "version": 1, "frames": 10_000_000, "bodies": []}))
    results = {}
    for name, one_call, python_loop in (
            ("World.step(dt)", lambda: world.step(1 / 60, steps=calls),
             lambda: [world.step(1 / 60) for _ in range(calls)]),
            ("Simulation.step()", lambda: empty.step(frames=calls),
             lambda: [empty.step() for _ in range(calls)])):
        best_one, best_loop = float("inf"), float("inf")
        for _ in range(5):
            start = time.perf_counter()
            one_call()
            best_one = min(best_one, time.perf_counter() - start)
            start = time.perf_counter()
            python_loop()
            best_loop = min(best_loop, time.perf_counter() - start)
        results[name] = (best_one / calls * 1e6, best_loop / calls * 1e6)
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python_step_bench.py",
        description="Stepping a scene from a Python loop against the same steps in C++.")
    parser.add_argument("--scene", default="stacks:4x50", help="preset or scene file (default stacks:4x50)")
    parser.add_argument("--depth", type=int, help="sphere-tree depth (default: the scene's)")
    parser.add_argument("--frames", type=int,
                        help="frames stepped in all, warm-up included (default: the scene's)")
    parser.add_argument("--warmup", type=int, default=40, help="untimed frames first (default 40)")
    parser.add_argument("--chunk", type=int, default=20, help="frames per timed chunk (default 20)")
    parser.add_argument("--threads", type=int, default=1, help="the world's threads (default 1)")
    parser.add_argument("--no-world", action="store_true", help="leave variant C out")
    parser.add_argument("--calls", type=int, default=20000,
                        help="calls of the bare-call measure (default 20000; 0 skips it)")
    args = parser.parse_args(argv)
    if args.chunk < 1 or args.warmup < 0:
        parser.error("--chunk must be at least 1 and --warmup at least 0")

    scene = sphys.load_scene(args.scene)
    built = time.perf_counter()
    variants = [("A", "sim.step(frames=K)", "C++ loop"), ("B", "sim.step() K times", "Python loop")]
    if not args.no_world:
        variants.append(("C", "sim.world.step(dt) K times", "Python loop"))
    sims = {key: sphys.Simulation(scene, depth=args.depth, threads=args.threads) for key, _, _ in variants}
    built = time.perf_counter() - built
    first = sims["A"]
    total = args.frames if args.frames is not None else first.scene.frames
    rounds = (total - args.warmup) // args.chunk
    if rounds < 1:
        parser.error(f"--frames {total} leaves no chunk of {args.chunk} after {args.warmup} warm-up frames")
    dt = first.scene.time_step
    chunks = {"A": _chunk_a, "B": _chunk_b, "C": _make_chunk_c(dt)}

    print(f"scene     {first.scene.name}: {len(first.body_ids)} bodies, "
          f"{first.scene.settings['response']} response, {args.threads} thread(s)")
    print(f"machine   {platform.machine()}, Python {platform.python_version()}, "
          f"numpy {numpy.__version__}; {len(sims)} worlds built in {built:.1f} s")
    print(f"frames    {args.warmup} untimed, then {rounds} rounds of {len(sims)} chunks of "
          f"{args.chunk} (frames {args.warmup + 1} to {args.warmup + rounds * args.chunk})")

    if args.warmup:
        for sim in sims.values():
            sim.step(frames=args.warmup)

    per_step = {key: [] for key in sims}   # s per step, one entry per chunk
    mismatched_rounds = 0
    keys = list(sims)
    for r in range(rounds):
        order = keys[r % len(keys):] + keys[:r % len(keys)]
        for key in order:
            sim = sims[key]
            start = time.perf_counter()
            chunks[key](sim, args.chunk)
            per_step[key].append((time.perf_counter() - start) / args.chunk)
        poses = first.poses()
        if any(not numpy.array_equal(poses, sims[key].poses()) for key in keys[1:]):
            mismatched_rounds += 1

    mean = {key: statistics.fmean(values) for key, values in per_step.items()}
    median = {key: statistics.median(values) for key, values in per_step.items()}
    print()
    print(f"{'variant':<46}{'mean ms/step':>13}{'median ms/step':>16}{'mean / A':>10}"
          f"{'median / A':>12}{'rounds / A':>12}")
    for key, call, loop in variants:
        paired = statistics.median(b / a for a, b in zip(per_step["A"], per_step[key]))
        print(f"{key}  {call + ' (' + loop + ')':<44}{mean[key] * 1e3:>13.4f}{median[key] * 1e3:>16.4f}"
              f"{mean[key] / mean['A']:>10.4f}{median[key] / median['A']:>12.4f}{paired:>12.4f}")
    print("(rounds / A: the median over rounds of the variant's chunk time over A's in the same round)")
    print()
    for key, call, _ in variants[1:]:
        differences = [b - a for a, b in zip(per_step["A"], per_step[key])]
        print(f"per call  {key} - A: {(mean[key] - mean['A']) * 1e6:+.1f} us per step (means), "
              f"{statistics.median(differences) * 1e6:+.1f} us (median of the rounds' differences)")
    print(f"physics   poses identical bit for bit after "
          f"{rounds - mismatched_rounds} of {rounds} rounds" + ("" if not mismatched_rounds else "  <- NOT LOCKSTEP"))
    s = sims["A"].summary()
    print(f"inside    A's steps by the C++ clock: mean {s['step_ms']['mean']:.4f} ms, median "
          f"{s['step_ms']['median']:.4f} ms over its {s['frames']} frames (warm-up included); "
          f"{s['contacts_per_frame']['mean']:.0f} contacts per frame; sphere-trees {s['sphere_trees']}")

    if args.calls > 0:
        print()
        print(f"bare call, empty world, best of 5 x {args.calls} steps: one call for all | one call each")
        for name, (one, each) in _bare_call_us(args.calls).items():
            print(f"  {name:<20}{one:8.2f} us/step | {each:8.2f} us/step  -> {each - one:.2f} us per call")
    return 1 if mismatched_rounds else 0


if __name__ == "__main__":
    sys.exit(main())
