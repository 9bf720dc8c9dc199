"""Robots simulated in a world from Python: a one-joint arm from its URDF held under gravity by
position control, driven by velocity and torque control, reset, read back as numpy arrays, and
bad input named."""

import math

import numpy as np
import pytest

import sphys

DT = 1e-3  # 1 kHz control. unit: s

# A 1 m, 1 kg arm on a static base, turning about z: gravity (-y) pulls it down with
# 1 kg · 9.81 m/s² · 0.5 m = 4.9 N·m when it is level.
ARM_URDF = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><origin xyz="0.5 0 0"/><mass value="1"/>
      <inertia ixx="0.001" iyy="0.083" izz="0.083" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0.5 0 0"/><geometry><box size="1 0.1 0.1"/></geometry></collision>
  </link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0.1 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="20" velocity="2"/></joint>
</robot>
"""

# cuRobo's YAML: one sphere on the base, five along the arm.
ARM_SPHERES = """collision_spheres:
  base:
    - center: [0.0, 0.0, 0.0]
      radius: 0.07
  arm:
""" + "".join(f"""    - center: [{x}, 0.0, 0.0]
      radius: 0.08
""" for x in (0.1, 0.3, 0.5, 0.7, 0.9))


@pytest.fixture
def arm_model(tmp_path):
    (tmp_path / "arm.urdf").write_text(ARM_URDF)
    (tmp_path / "arm.yml").write_text(ARM_SPHERES)
    return sphys.load_robot_model(tmp_path / "arm.urdf", tmp_path / "arm.yml")


def test_position_control_holds_the_arm_level_within_the_effort(arm_model):
    world = sphys.World(sleep={"enabled": False})
    robot = world.add_robot(arm_model, base=((0, 1, 0), (0, 0, 0, 1)))
    assert len(robot.bodies) == 2 and len(robot.joints) == 1
    robot.set_configuration([0.3])
    robot.set_joint_targets(np.array([0.3]), kp=0.2, kd=1.0)
    world.step(DT, steps=2000)
    positions = robot.joint_positions()
    assert positions.dtype == np.float64 and positions.shape == (1,)
    assert abs(positions[0] - 0.3) < math.radians(0.5)
    # Holding the arm 0.3 rad above level: the weight's moment about the joint.
    assert robot.joint_efforts()[0] == pytest.approx(9.81 * 0.5 * math.cos(0.3), rel=0.02)
    assert abs(robot.joint_velocities()[0]) < 1e-3


def test_the_links_stand_where_the_joint_values_put_them(arm_model):
    world = sphys.World()
    robot = world.add_robot(arm_model, base=((0, 1, 0), (0, 0, 0, 1)))
    robot.set_configuration([math.pi / 2])
    poses = robot.link_poses()
    assert poses.shape == (2, 4, 4)
    np.testing.assert_allclose(poses[1][:3, 3], [0.1, 1.0, 0.0], atol=1e-5)
    # The arm's x axis turned a quarter about z: pointing up.
    np.testing.assert_allclose(poses[1][:3, 0], [0.0, 1.0, 0.0], atol=1e-5)


def test_velocity_and_torque_control(arm_model):
    world = sphys.World(gravity=(0, 0, 0), sleep={"enabled": False})
    robot = world.add_robot(arm_model)
    robot.set_joint_velocities([0.5])
    world.step(DT, steps=500)
    assert robot.joint_velocities()[0] == pytest.approx(0.5, abs=0.01)
    robot.apply_torques([1000.0])  # bounded by the URDF's 20 N·m
    world.step(DT, steps=10)
    assert robot.joint_efforts()[0] == pytest.approx(20.0, rel=0.01)
    assert robot.joint_velocities()[0] > 0.5


def test_a_free_robot_falls(arm_model):
    world = sphys.World()
    robot = world.add_robot(arm_model, base=((0, 2, 0), (0, 0, 0, 1)), fixed_base=False)
    world.step(DT, steps=100)
    assert robot.link_poses()[0][1, 3] < 2.0 - 0.5 * 9.81 * 0.1**2 * 0.9


def test_bad_input_is_named(arm_model, tmp_path):
    world = sphys.World()
    robot = world.add_robot(arm_model)
    with pytest.raises(sphys.Error, match=r"positions must be a number or a \(1,\) array"):
        robot.set_joint_targets([0.1, 0.2])
    with pytest.raises(sphys.Error, match="joint 'turn'.*outside its limits"):
        robot.set_configuration([3.0])
    robot.remove()
    with pytest.raises(sphys.Error, match="no robot"):
        robot.joint_positions()
    (tmp_path / "float.urdf").write_text(ARM_URDF.replace('type="revolute"', 'type="floating"'))
    with pytest.raises(sphys.Error, match='joint "turn" is floating'):
        sphys.load_robot_model(tmp_path / "float.urdf", tmp_path / "arm.yml")
