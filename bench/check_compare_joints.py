"""sphys-compare --jointed builds the same jointed scene in every engine: the same bodies and
joints, each holding its anchors together (a joint left out or built at the wrong anchor would
open by decimetres while a chain swings down for half a second: 0.5 g t² is 1.2 m).

Usage: check_compare_joints.py PATH_TO_SPHYS_COMPARE
"""
import csv
import pathlib
import subprocess
import sys
import tempfile

ENGINES = ["sphys", "bullet-spheres", "ode", "mujoco"]
# Per scene: bodies and joints. 2 ragdolls of 11 limbs and 10 joints; 2 chains of 3 links, each
# hinged to the world and to its neighbour, over 3 rows of 1 bunny, two high.
EXPECTED = {"ragdolls:2": (22, 20), "chains:2x3": (6 + 6, 6)}
LARGEST_GAP = 0.05  # a held joint's anchors apart at most over the run. unit: m


def main(compare):
    with tempfile.TemporaryDirectory() as folder:
        out = pathlib.Path(folder) / "results.md"
        subprocess.run([compare, "--layouts", "none", "--jointed", ",".join(EXPECTED),
                        "--engines", ",".join(ENGINES), "--frames", "30", "--out", str(out)],
                       check=True, capture_output=True)
        with open(out.with_suffix(".csv"), newline="") as f:
            rows = list(csv.DictReader(f))
    assert [(r["layout"], r["engine"]) for r in rows] == [
        (scene, engine) for scene in EXPECTED for engine in ENGINES], rows
    for row in rows:
        bodies, joints = EXPECTED[row["layout"]]
        assert row["warnings"] == "", row
        assert int(row["bodies"]) == bodies and int(row["joints"]) == joints, row
        assert float(row["largest_joint_gap_m"]) < LARGEST_GAP, row
        assert int(row["below_plane"]) == 0, row
    print("ok:", len(rows), "rows")


if __name__ == "__main__":
    main(sys.argv[1])
