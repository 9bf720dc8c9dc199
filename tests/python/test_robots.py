"""Robots simulated in a world from Python: a one-joint arm from its URDF held under gravity by
position control, driven by velocity and torque control, reset, read back as numpy arrays,
recorded for `sphys view`, and bad input named."""

import json
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

# One sphere on the base, five along the arm: ((x, y, z), radius) in each link's frame. unit: m
ARM_SPHERES = {"base": [((0.0, 0.0, 0.0), 0.07)],
               "arm": [((x, 0.0, 0.0), 0.08) for x in (0.1, 0.3, 0.5, 0.7, 0.9)]}


@pytest.fixture
def arm_model(tmp_path):
    return sphys.robot_model_from_text(ARM_URDF, ARM_SPHERES, tmp_path, "arm")


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


# ---------------------------------------------------------------------------------------------
# Recordings of worlds holding robots

# Each link's centre of mass in its frame (the URDF's inertial origins): a robot's body stands
# there, its axes the link's. unit: m
ARM_CENTRES = np.array([[0.0, 0.0, 0.0], [0.5, 0.0, 0.0]])


def rotation_matrices(quaternions):
    """The rotation matrices of (..., 4) unit quaternions (x, y, z, w), in float64."""
    x, y, z, w = np.moveaxis(np.asarray(quaternions, dtype=np.float64), -1, 0)
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], axis=-1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], axis=-1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], axis=-1),
    ], axis=-2)


def assert_links_recorded(recording, first_body, link_poses):
    """The arm's links placed from its two bodies' recorded poses (bodies first_body and the next)
    are the world's link poses of every frame, (F, 2, 4, 4), within 1e-6 m and 1e-6."""
    bodies = slice(first_body, first_body + 2)
    axes = rotation_matrices(recording.orientations[:, bodies])
    origins = (recording.positions[:, bodies].astype(np.float64)
               - np.einsum("flij,lj->fli", axes, ARM_CENTRES))
    np.testing.assert_allclose(origins, link_poses[..., :3, 3], rtol=0, atol=1e-6)
    np.testing.assert_allclose(axes, link_poses[..., :3, :3], rtol=0, atol=1e-6)


def assert_arm_joint(joint, root_body):
    """The arm's hinge as a recording keeps it: from its root's body to the arm's, at the joint's
    origin 0.1 m out from the root, 0.5 m behind the arm's centre of mass."""
    assert joint["type"] == sphys.JointType.HINGE
    assert (joint["body_a"], joint["body_b"]) == (root_body, root_body + 1)
    np.testing.assert_allclose(joint["anchor_a"], (0.1, 0.0, 0.0), atol=1e-7)
    np.testing.assert_allclose(joint["anchor_b"], (-0.5, 0.0, 0.0), atol=1e-7)


def test_a_recording_of_a_world_keeps_its_robot_where_the_world_has_it(arm_model, tmp_path, cli):
    world = sphys.World(ground_plane=0.0, sleep={"enabled": False})
    robot = world.add_robot(arm_model, base=((0, 1, 0), (0, 0, 0, 1)))
    robot.set_joint_targets([1.2])  # from 0: the arm swings up, at most 2 rad/s
    path = tmp_path / "arm.sphysrec"
    link_poses = [robot.link_poses()]
    with sphys.RecordingWriter(path, world, DT) as recording:
        recording.add_frame()
        for _ in range(300):
            world.step(DT)
            recording.add_frame()
            link_poses.append(robot.link_poses())
    assert robot.joint_positions()[0] > 0.4  # it moved: the frames differ

    recording = sphys.read_recording(path)
    assert recording.body_count == 2 and recording.frame_count == 301
    assert recording.time_step == DT
    assert_links_recorded(recording, 0, np.stack(link_poses))
    assert len(recording.joints) == 1
    assert_arm_joint(recording.joints[0], 0)
    # The scene names the robot, for the viewer: no bodies of its own, the world's ground plane.
    scene = recording.scene().to_dict()
    assert scene["bodies"] == [] and scene["ground"]["type"] == "plane"
    [named] = scene["robots"]
    assert named["urdf"] == str(tmp_path / "arm.urdf") and named["fixed_base"]
    assert named["spheres"] == str(tmp_path / "arm.yml") and named["position"] == [0, 1, 0]
    # The replaying tools load the robot's links for its two bodies.
    done = cli("export", path, "--gltf", tmp_path / "arm.glb")
    assert done.returncode == 0, done.stderr
    assert "2 bodies (2 distinct meshes), 301 frames" in done.stdout


def test_a_recording_of_a_simulation_with_robots_is_the_command_lines(arm_model, tmp_path,
                                                                       simulate_cli, cli):
    # A bunny beside the arm, which the scene drives to 1.2 rad by position control.
    frames = 60
    (tmp_path / "scene.json").write_text(json.dumps({
        "format": "sphys-scene", "version": 1, "frames": frames, "ground": {"type": "plane"},
        "bodies": [{"mesh": "bunny", "size": 0.2, "position": [-1.0, 0.3, 0.0]}],
        "robots": [{"urdf": "arm.urdf", "spheres": "arm.yml", "position": [0, 1, 0],
                    "targets": [1.2]}]}))
    _, cli_path = simulate_cli(tmp_path / "scene.json", frames)

    def record(path, sim, robot=None):
        """Records the simulation's start and `frames` frames; the robot's link poses."""
        link_poses = []
        with sphys.RecordingWriter(path, sim) as recording:
            for frame in range(frames + 1):
                if frame > 0:
                    sim.step()
                recording.add_frame()
                if robot is not None:
                    link_poses.append(robot.link_poses())
        return np.stack(link_poses) if link_poses else None

    # The scene's bunny, then the scene's robot: the command line's recording, byte for byte.
    mine = tmp_path / "mine.sphysrec"
    record(mine, sphys.Simulation(tmp_path / "scene.json"))
    assert mine.read_bytes() == cli_path.read_bytes()
    recording = sphys.read_recording(mine)
    assert recording.body_count == 3 and [j["body_a"] for j in recording.joints] == [1]

    # A robot World.add_robot adds comes after the scene's, its joint after theirs.
    sim = sphys.Simulation(tmp_path / "scene.json")
    robot = sim.world.add_robot(arm_model, base=((2, 1, 0), (0, 0, 0, 1)))
    robot.set_joint_targets([-0.5])
    both = tmp_path / "both.sphysrec"
    link_poses = record(both, sim, robot)
    recording = sphys.read_recording(both)
    assert recording.body_count == 5 and len(recording.joints) == 2
    assert_arm_joint(recording.joints[1], 3)
    assert_links_recorded(recording, 3, link_poses)
    assert abs(robot.joint_positions()[0] + 0.5) < 0.05  # it moved to its target
    robots = recording.scene().to_dict()["robots"]
    assert [r["position"] for r in robots] == [[0, 1, 0], [2, 1, 0]]
    assert robots[1]["urdf"] == str(tmp_path / "arm.urdf") and robots[1]["targets"] == []
    done = cli("export", both, "--gltf", tmp_path / "both.glb")
    assert done.returncode == 0, done.stderr
    assert f"5 bodies (5 distinct meshes), {frames + 1} frames" in done.stdout


def test_a_recording_names_bad_input(arm_model, tmp_path):
    world = sphys.World()
    robot = world.add_robot(arm_model)
    path = tmp_path / "bad.sphysrec"
    with pytest.raises(sphys.Error, match="time step must be positive and finite, got nan"):
        sphys.RecordingWriter(path, world, float("nan"))
    with pytest.raises(TypeError):
        sphys.RecordingWriter(path, world)  # a World has no time step of its own
    writer = sphys.RecordingWriter(path, world, DT)
    with pytest.raises(sphys.Error, match="records its world's poses: call add_frame"):
        writer.add_frame(np.zeros((2, 7)))
    writer.add_frame()
    other = world.add_robot(arm_model, base=((1, 0, 0), (0, 0, 0, 1)))
    with pytest.raises(sphys.Error, match=r"robots changed since the recording began \(1 then, "
                                          r"2 now\)"):
        writer.add_frame()
    other.remove()
    robot.remove()
    with pytest.raises(sphys.Error, match=r"\(1 then, 0 now\)"):
        writer.add_frame()
    del writer
    assert not path.exists()  # never finished: no file

    # A writer of poses takes (B, 7) finite poses.
    writer = sphys.RecordingWriter(path, 2, DT)
    with pytest.raises(sphys.Error, match="needs the poses of this writer's bodies"):
        writer.add_frame()
    with pytest.raises(sphys.Error, match=r"poses must be an array of shape \(B, 7\)"):
        writer.add_frame(np.zeros((2, 6)))
    with pytest.raises(sphys.Error, match=r"poses must be an array of shape \(B, 7\)"):
        writer.add_frame("poses")
    with pytest.raises(sphys.Error, match="frame 0 has 3 poses, the recording has 2 bodies"):
        writer.add_frame(np.tile([0, 0, 0, 0, 0, 0, 1.0], (3, 1)))
    poses = np.tile([0, 0, 0, 0, 0, 0, 1.0], (2, 1))
    poses[1, 0] = np.nan
    with pytest.raises(sphys.Error, match="not finite"):
        writer.add_frame(poses)
