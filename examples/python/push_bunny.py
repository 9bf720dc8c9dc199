"""A robot arm in a world: checked, then played out under position control, pushing a bunny.

    python3 examples/python/push_bunny.py [OUT_FOLDER]

A one-joint arm (a 0.5 m bar turning about the vertical, 6 cm over the ground) stands beside a
pile of small bunnies. sphys's checks from joint values (World.check_motions, the checker
plan_arm plans with) confirm that its approach is free and that its sweep meets the pile; then
the arm is added to the world (World.add_robot) and follows both motions under position control
at 1 kHz, as PyBullet's POSITION_CONTROL would drive it. Prints how far the bunnies moved and the
largest tracking error. The arm's files and a recording of the motions (1 kHz) go to OUT_FOLDER
(push_bunny by default): `sphys view --replay push_bunny/push_bunny.sphysrec` replays the arm with
the bunnies. The C++ example examples/push_bunny plans the test robot with OMPL.
"""

import math
import sys
from pathlib import Path

import numpy as np

import sphys

DT = 1e-3  # 1 kHz control. unit: s
SPEED = 1.0  # the motions' top joint speed. unit: rad/s

ARM_URDF = """<?xml version="1.0"?>
<robot name="sweeper">
  <link name="base">
    <collision><origin xyz="0 0.03 0"/><geometry><box size="0.1 0.06 0.1"/></geometry></collision>
  </link>
  <link name="bar">
    <inertial><origin xyz="0.25 0 0"/><mass value="1"/>
      <inertia ixx="0.0002" iyy="0.021" izz="0.021" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.04 0.04"/></geometry></collision>
  </link>
  <joint name="pan" type="revolute"><parent link="base"/><child link="bar"/>
    <origin xyz="0 0.06 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="50" velocity="2"/></joint>
</robot>
"""

# One sphere on the base, eleven along the bar: ((x, y, z), radius) in each link's frame. unit: m
ARM_SPHERES = {"base": [((0.0, 0.03, 0.0), 0.06)],
               "bar": [((round(x, 2), 0.0, 0.0), 0.025) for x in np.linspace(0.0, 0.5, 11)]}


def quintic(start, end, duration, t):
    """Position and speed at t (s) of a quintic from start to end over duration (s)."""
    s = min(max(t / duration, 0.0), 1.0)
    return (start + (end - start) * s**3 * (10 - 15 * s + 6 * s * s),
            (end - start) * 30 * s * s * (1 - s) ** 2 / duration)


def play(world, robot, start, end, recording):
    """Follows a quintic from start to end (rad) at SPEED at the top, recording every step; the
    largest error (rad)."""
    duration = max(0.2, 1.875 * abs(end - start) / SPEED)
    worst = 0.0
    for step in range(1, int(duration / DT) + 1):
        target, speed = quintic(start, end, duration, step * DT)
        robot.set_joint_targets([target], velocities=[speed])
        world.step(DT)
        recording.add_frame()
        worst = max(worst, abs(robot.joint_positions()[0] - target))
    return worst


def main(out):
    pile = sphys.Scene.from_dict({
        "format": "sphys-scene", "version": 1, "ground": {"type": "plane"},
        "bodies": [{"mesh": "bunny", "size": 0.1, "position": [0.3, 0.06 + 0.1 * i, 0.0],
                    "orientation": {"yaw_degrees": 40 * i}} for i in range(3)]})
    sim = sphys.Simulation(pile)
    sim.step(300)  # five seconds at 60 Hz: the bunnies come to rest
    world = sim.world
    rested = sim.poses()[:, :3].copy()  # the pile's bunnies alone

    model = sphys.robot_model_from_text(ARM_URDF, ARM_SPHERES, out, "sweeper")
    start, approach, through = -2.0, -1.0, 1.0  # pan angles. unit: rad
    motions = world.check_motions(model, [[start], [approach]], [[approach], [through]], 0.01)
    if not motions["free"][0] or motions["free"][1]:
        print("the approach must be free and the sweep must meet the pile", file=sys.stderr)
        return 1

    robot = world.add_robot(model)
    robot.set_configuration([start])
    # The bunnies, then the arm's two bodies, as `sphys simulate` records a scene with a robot.
    with sphys.RecordingWriter(out / "push_bunny.sphysrec", sim, time_step=DT) as recording:
        recording.add_frame()
        worst = max(play(world, robot, start, approach, recording),
                    play(world, robot, approach, through, recording))
    moved = np.linalg.norm(sim.poses()[:, :3] - rested, axis=1)
    print(f"bunnies moved {np.array2string(moved, precision=3)} m; "
          f"largest tracking error {math.degrees(worst):.3f} deg; "
          f"replay: sphys view --replay {out / 'push_bunny.sphysrec'}")
    return 0 if moved.max() > 0.01 else 1


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1] if len(sys.argv) > 1 else "push_bunny")))
