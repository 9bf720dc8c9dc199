"""A robot arm in a world: checked, then played out under position control, pushing a bunny.

    python3 examples/python/push_bunny.py

A one-joint arm (a 0.5 m bar turning about the vertical, 6 cm over the ground) stands beside a
pile of small bunnies. sphys's checks from joint values (World.check_motions, the checker
plan_arm plans with) confirm that its approach is free and that its sweep meets the pile; then
the arm is added to the world (World.add_robot) and follows both motions under position control
at 1 kHz, as PyBullet's POSITION_CONTROL would drive it. Prints how far the bunnies moved and the
largest tracking error. The C++ example examples/push_bunny plans the test robot with OMPL.
"""

import math
import sys
import tempfile
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

# cuRobo's YAML: one sphere on the base, eleven along the bar.
ARM_SPHERES = "collision_spheres:\n  base:\n    - center: [0.0, 0.03, 0.0]\n      radius: 0.06\n" \
    "  bar:\n" + "".join(f"    - center: [{x:.2f}, 0.0, 0.0]\n      radius: 0.025\n"
                         for x in np.linspace(0.0, 0.5, 11))


def quintic(start, end, duration, t):
    """Position and speed at t (s) of a quintic from start to end over duration (s)."""
    s = min(max(t / duration, 0.0), 1.0)
    return (start + (end - start) * s**3 * (10 - 15 * s + 6 * s * s),
            (end - start) * 30 * s * s * (1 - s) ** 2 / duration)


def play(world, robot, start, end):
    """Follows a quintic from start to end (rad) at SPEED at the top; the largest error (rad)."""
    duration = max(0.2, 1.875 * abs(end - start) / SPEED)
    worst = 0.0
    for step in range(1, int(duration / DT) + 1):
        target, speed = quintic(start, end, duration, step * DT)
        robot.set_joint_targets([target], velocities=[speed])
        world.step(DT)
        worst = max(worst, abs(robot.joint_positions()[0] - target))
    return worst


def main():
    pile = sphys.Scene.from_dict({
        "format": "sphys-scene", "version": 1, "ground": {"type": "plane"},
        "bodies": [{"mesh": "bunny", "size": 0.1, "position": [0.3, 0.06 + 0.1 * i, 0.0],
                    "orientation": {"yaw_degrees": 40 * i}} for i in range(3)]})
    sim = sphys.Simulation(pile)
    sim.step(300)  # five seconds at 60 Hz: the bunnies come to rest
    world = sim.world
    rested = sim.poses()[:, :3].copy()  # the pile's bunnies alone

    with tempfile.TemporaryDirectory() as folder:
        (Path(folder) / "sweeper.urdf").write_text(ARM_URDF)
        (Path(folder) / "sweeper.yml").write_text(ARM_SPHERES)
        model = sphys.load_robot_model(Path(folder) / "sweeper.urdf", Path(folder) / "sweeper.yml")
    start, approach, through = -2.0, -1.0, 1.0  # pan angles. unit: rad
    motions = world.check_motions(model, [[start], [approach]], [[approach], [through]], 0.01)
    if not motions["free"][0] or motions["free"][1]:
        print("the approach must be free and the sweep must meet the pile", file=sys.stderr)
        return 1

    robot = world.add_robot(model)
    robot.set_configuration([start])
    worst = max(play(world, robot, start, approach), play(world, robot, approach, through))
    moved = np.linalg.norm(sim.poses()[:, :3] - rested, axis=1)
    print(f"bunnies moved {np.array2string(moved, precision=3)} m; "
          f"largest tracking error {math.degrees(worst):.3f} deg")
    return 0 if moved.max() > 0.01 else 1


if __name__ == "__main__":
    sys.exit(main())
