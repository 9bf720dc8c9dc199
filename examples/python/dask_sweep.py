"""A sweep on Dask: two response modes times three seeds of a bunny stack, run side by side.

    python3 examples/python/dask_sweep.py [OUT_FOLDER]

Each run is an independent simulation on a local cluster of two single-threaded worker
processes (Debian: python3-distributed, python3-pandas); runs.csv and runs.json go into
OUT_FOLDER (default sweep-out).
"""

import sys

import sphys.sweep


def main(out="sweep-out"):
    result = sphys.sweep.sweep(
        ["stacks:1x6"],
        settings=[{"response": "paper"}, {"response": "plausible"}],
        seeds=[1, 2, 3],  # the stack's yaw angles
        frames=300,  # 5 s at 60 frames per second
        n_workers=2,
        out=out,
        progress=False,
    )
    for row in result.rows():
        print(f"{row['settings']:26} seed {row['seed']}: {row['status']}, deepest penetration "
              f"{row['deepest_penetration_m']:.4f} m, {row['bodies_asleep']} of {row['bodies']} "
              f"asleep, final kinetic energy {row['final_kinetic_energy_J']:.3g} J")
    return 1 if result.failed else 0


# Dask's worker processes start by importing this file: the sweep must run only in the main one.
if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
