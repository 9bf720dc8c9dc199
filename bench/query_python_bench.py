"""Python's batched checks against the C++ loops on the same world and configurations.

sphys-query-bench --python-reference DIR writes the batched checks' world (100 bunnies at rest,
the test robot's 60 spheres beside them, 100,000 random configurations) and times the C++ loop
over them; this script then builds the same world in Python from those files and times the same
call, one thread, 21 runs each (as many as the C++ loops), medians; then the same from joint values
(world.check_joint_values against RobotChecker::check, the robot's model loaded from its URDF and
spheres). Run from the repository root:

    PYTHONPATH=build/release/python /usr/bin/python3 bench/query_python_bench.py
"""

import argparse
import pathlib
import subprocess
import tempfile
import time

import numpy as np

import sphys


def median_ms(call, runs=21):
    """The median of `runs` timings of call() in ms, and its last result."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        result = call()
        times.append(1e3 * (time.perf_counter() - start))
    return float(np.median(times)), result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", default="build/release/bin/sphys-query-bench")
    parser.add_argument("--configurations", type=int, default=100000)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        out = subprocess.run([args.bench, "--configurations", str(args.configurations),
                              "--python-reference", folder],
                             check=True, capture_output=True, text=True).stdout.split()
        reference = dict(zip(out[0::2], out[1::2]))
        cpp_ms = float(reference["cpp_loop_ms"])
        path = pathlib.Path(folder)
        tree = sphys.read_sph(path / "bunny.sph")
        poses = np.fromfile(path / "poses.f32", dtype=np.float32).reshape(-1, 7)
        links = np.fromfile(path / "links.i32", dtype=np.int32)
        spheres = np.fromfile(path / "spheres.f32", dtype=np.float32).reshape(-1, len(links), 4)
        package_name, package_dir = reference["package"].split("=", 1)
        model = sphys.load_robot_model(reference["urdf"], path / "arm.yml",
                                       packages={package_name: package_dir})
        values = np.fromfile(path / "values.f64", dtype=np.float64).reshape(-1, len(model.joints))
        base = np.fromfile(path / "base.f32", dtype=np.float32)
        model.set_base(base[:3], base[3:])
    world = sphys.World(gravity=(0, 0, 0))
    for pose in poses:
        world.add_body(tree, position=pose[:3], orientation=pose[3:], static=True)
    python_ms, result = median_ms(lambda: world.check_configurations(spheres, links))
    colliding = int((~result["free"]).sum())
    print(f"| configurations | C++ loop ms | Python ms | Python / C++ | colliding (C++, Python) |")
    print(f"| --- | --- | --- | --- | --- |")
    print(f"| {len(spheres)} | {cpp_ms:.1f} | {python_ms:.1f} | {python_ms / cpp_ms:.3f} | "
          f"{reference['colliding']}, {colliding} |")
    values_ms, result = median_ms(lambda: world.check_joint_values(model, values))
    cpp_values_ms = float(reference["cpp_values_ms"])
    colliding = int((~result["free"]).sum())
    print(f"| from joint values, {len(values)} | {cpp_values_ms:.1f} | {values_ms:.1f} | "
          f"{values_ms / cpp_values_ms:.3f} | {reference['values_colliding']}, {colliding} |")


if __name__ == "__main__":
    main()
