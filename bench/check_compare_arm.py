"""sphys-compare's arm scene builds the same robot in sphys and MuJoCo: the same links and joints,
each engine's position control following the motion (a robot built at the wrong joint axes,
with the wrong parent, colliding with its own base or not driven would leave its targets by
tens of degrees: the motion turns the pan joint by 1.3 rad), its joints held together, and an
engine with no robot says so instead of running without it.

Usage: check_compare_arm.py PATH_TO_SPHYS_COMPARE
"""
import csv
import math
import pathlib
import subprocess
import sys
import tempfile

ENGINES = ["sphys", "mujoco", "ode"]
BUNNIES = 2
ROBOT_BODIES = 6  # the test robot's root and the links its 5 joints move
ROBOT_JOINTS = 5
LARGEST_TRACKING_ERROR = math.radians(1.0)  # unit: rad
LARGEST_FINGER_ERROR = 0.005  # unit: m
LARGEST_GAP = 0.01  # unit: m


def main(compare):
    with tempfile.TemporaryDirectory() as folder:
        out = pathlib.Path(folder) / "results.md"
        subprocess.run([compare, "--layouts", "none", "--jointed", f"arm:{BUNNIES}",
                        "--engines", ",".join(ENGINES), "--out", str(out)],
                       check=True, capture_output=True)
        with open(out.with_suffix(".csv"), newline="") as f:
            rows = {row["engine"]: row for row in csv.DictReader(f)}
    assert list(rows) == ENGINES, rows
    assert "has no robot" in rows["ode"]["warnings"], rows["ode"]
    for engine in ["sphys", "mujoco"]:
        row = rows[engine]
        assert row["warnings"] == "", row
        assert int(row["frames"]) == 10000 and int(row["fewest_frames_run"]) == 10000, row
        assert int(row["bodies"]) == BUNNIES + ROBOT_BODIES, row
        assert int(row["joints"]) == ROBOT_JOINTS, row
        assert float(row["largest_tracking_error_rad"]) < LARGEST_TRACKING_ERROR, row
        assert float(row["largest_finger_error_m"]) < LARGEST_FINGER_ERROR, row
        assert float(row["largest_joint_gap_m"]) < LARGEST_GAP, row
        assert int(row["below_plane"]) == 0, row
    print("ok:", {e: float(rows[e]["largest_tracking_error_rad"]) for e in ["sphys", "mujoco"]})


if __name__ == "__main__":
    main(sys.argv[1])
