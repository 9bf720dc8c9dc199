"""Joints from Python: a pendulum's period against 2π√(L/g), a motor's speed, the read-back,
bad input named by field, and a removed body's joints going with it."""

import json
import math

import numpy as np
import pytest

import sphys

DT = 1.0 / 60.0
G = 9.81


def ball(world, sphere_tree, radius, position, mass=1.0):
    """A solid ball of `radius` (m) and `mass` (kg) at `position` (m): inertia 2/5 m r²."""
    inertia = 0.4 * mass * radius * radius * np.eye(3)
    return world.add_body(sphere_tree(radius), position=position, mass=mass, inertia=inertia)


def pendulum(world, sphere_tree, length, angle):
    """A 2 cm bob hinged to the world at the origin about z, `length` (m) below it, turned
    `angle` (rad) towards +x. Returns (bob, hinge)."""
    position = (length * math.sin(angle), -length * math.cos(angle), 0.0)
    bob = ball(world, sphere_tree, 0.02, position)
    hinge = world.add_joint(sphys.JointDesc(
        type=sphys.JointType.HINGE, body_a=sphys.BodyId(), body_b=bob,
        anchor_a=(0, 0, 0), anchor_b=[-c for c in position],
        axis_a=(0, 0, 1), axis_b=np.array([0.0, 0.0, 1.0])))
    return bob, hinge


def test_a_pendulum_swings_with_the_period_of_the_small_angle_formula(sphere_tree):
    world = sphys.World(gravity=(0, -G, 0), sleep={"enabled": False})
    length = 1.0
    bob, _ = pendulum(world, sphere_tree, length, 0.05)
    crossings = []  # times the bob crosses the vertical towards -x, interpolated in the step
    x = world.poses([bob])[0, 0]
    for step in range(1, 12 * 60 + 1):
        world.step(DT)
        after = world.poses([bob])[0, 0]
        if x > 0 >= after:
            crossings.append(DT * (step - 1 + x / (x - after)))
        x = after
    assert len(crossings) >= 5
    period = (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    expected = 2 * math.pi * math.sqrt(length / G)
    assert period == pytest.approx(expected, rel=0.01)


def test_the_hinge_reads_back_its_angle_speed_and_the_weight_it_holds(sphere_tree):
    world = sphys.World(gravity=(0, -G, 0), sleep={"enabled": False})
    bob, hinge = pendulum(world, sphere_tree, 1.0, 0.0)
    world.step(DT, steps=30)
    state = world.joint_state(hinge)
    assert isinstance(state, sphys.JointState)
    assert abs(state.position) < 1e-4 and abs(state.speed) < 1e-3
    assert state.gap < 1e-3
    # The hinge holds the bob up: +1 kg × g on body b, nothing sideways.
    assert isinstance(state.force, np.ndarray) and state.force.shape == (3,)
    np.testing.assert_allclose(state.force, (0.0, G, 0.0), atol=0.05)
    assert state.torque.shape == (3,)
    desc = world.joint(hinge)
    assert desc.type == sphys.JointType.HINGE
    assert desc.body_b == bob and desc.body_a.is_null
    np.testing.assert_array_equal(desc.axis_a, (0, 0, 1))


def test_a_motor_reaches_its_speed(sphere_tree):
    world = sphys.World(gravity=(0, 0, 0), sleep={"enabled": False})
    wheel = ball(world, sphere_tree, 0.5, (0, 0, 0), mass=2.0)
    hinge = world.add_joint(sphys.JointDesc(
        type=sphys.JointType.HINGE, body_a=wheel, axis_a=(0, 0, 1), axis_b=(0, 0, 1),
        motor=sphys.JointMotor(enabled=True, speed=3.0, max_effort=5.0)))
    world.step(DT, steps=60)
    # Body b is the world here: the wheel turns at -3 rad/s so that b turns +3 against it.
    assert world.joint_state(hinge).speed == pytest.approx(3.0, rel=1e-3)
    np.testing.assert_allclose(world.velocities([wheel])[0, 3:], (0, 0, -3.0), atol=3e-3)
    # A new speed from the next step on.
    world.set_joint_motor(hinge, sphys.JointMotor(enabled=True, speed=-1.0, max_effort=5.0))
    world.step(DT, steps=60)
    assert world.joint_state(hinge).speed == pytest.approx(-1.0, rel=1e-3)
    assert world.joint(hinge).motor.speed == -1.0


def test_limits_and_springs_set_from_python_are_read_back(sphere_tree):
    world = sphys.World(sleep={"enabled": False})
    _, hinge = pendulum(world, sphere_tree, 1.0, 0.5)
    world.set_joint_limit(hinge, sphys.JointLimit(enabled=True, lower=-0.1, upper=0.2))
    world.set_joint_spring(hinge, sphys.JointSpring(enabled=True, hertz=2, damping_ratio=0.5))
    desc = world.joint(hinge)
    assert desc.limit.enabled and desc.limit.lower == pytest.approx(-0.1)
    assert desc.spring.hertz == 2 and desc.spring.damping_ratio == 0.5
    # The C++ defaults: a ball joint with every part off and a 1 m length.
    blank = sphys.JointDesc()
    assert blank.type == sphys.JointType.BALL and not blank.limit.enabled
    assert not blank.motor.enabled and not blank.spring.enabled and not blank.cone.enabled
    assert blank.length == 1.0 and not blank.collide_connected
    np.testing.assert_array_equal(blank.axis_b, (1, 0, 0))


@pytest.mark.parametrize("make, field", [
    (lambda w, b: sphys.JointDesc(body_a=b, anchor_a=(0, 0)), "anchor_a"),
    (lambda w, b: sphys.JointDesc(body_a=b, axis_b=(0, float("nan"), 0)), "axis_b"),
    (lambda w, b: w.add_joint(sphys.JointDesc(type=sphys.JointType.HINGE, body_a=b,
                                              axis_a=(0, 0, 0))), "axis_a"),
    (lambda w, b: w.add_joint(sphys.JointDesc(
        type=sphys.JointType.HINGE, body_a=b,
        limit=sphys.JointLimit(enabled=True, lower=1, upper=0))), "limit.lower"),
    (lambda w, b: w.add_joint(sphys.JointDesc(
        body_a=b, motor=sphys.JointMotor(max_effort=-1))), "motor.max_effort"),
    (lambda w, b: w.add_joint(sphys.JointDesc(
        body_a=b, spring=sphys.JointSpring(hertz=-2))), "spring.hertz"),
    (lambda w, b: w.add_joint(sphys.JointDesc(
        body_a=b, cone=sphys.JointCone(enabled=True, angle=4))), "cone.angle"),
    (lambda w, b: w.add_joint(sphys.JointDesc(body_a=b, friction=-1)), "friction"),
    (lambda w, b: w.add_joint(sphys.JointDesc(body_a=b, friction=float("nan"))), "friction"),
    (lambda w, b: w.add_joint(sphys.JointDesc(type=sphys.JointType.DISTANCE, body_a=b,
                                              length=0)), "length"),
    (lambda w, b: w.add_joint(sphys.JointDesc(body_a=b, body_b=b)), "body_b"),
    (lambda w, b: w.set_joint_motor(w.add_joint(sphys.JointDesc(body_a=b)),
                                    sphys.JointMotor(speed=float("inf"))), "motor.speed"),
    (lambda w, b: w.remove_joint(sphys.JointId()), "null joint id"),
])
def test_bad_input_raises_sphys_error_naming_the_field(sphere_tree, make, field):
    world = sphys.World()
    body = world.add_body(sphere_tree(0.5))
    with pytest.raises(sphys.Error, match=field.replace(".", r"\.")):
        make(world, body)


def test_a_removed_bodys_joints_go_with_it(sphere_tree):
    world = sphys.World(sleep={"enabled": False})
    a = world.add_body(sphere_tree(0.5), position=(0, 0, 0))
    b = world.add_body(sphere_tree(0.5), position=(2, 0, 0))
    c = world.add_body(sphere_tree(0.5), position=(4, 0, 0))
    ab = world.add_joint(sphys.JointDesc(type=sphys.JointType.WELD, body_a=a, body_b=b,
                                         anchor_a=(1, 0, 0), anchor_b=(-1, 0, 0)))
    bc = world.add_joint(sphys.JointDesc(type=sphys.JointType.DISTANCE, body_a=b, body_b=c,
                                         length=2.0))
    ca = world.add_joint(sphys.JointDesc(body_a=c, body_b=a, anchor_a=(-2, 0, 0),
                                         anchor_b=(2, 0, 0)))
    world.remove_body(b)
    assert set(world.joints_removed()) == {ab, bc}
    assert not world.joint_alive(ab) and not world.joint_alive(bc)
    assert world.joint_alive(ca)
    with pytest.raises(sphys.Error, match="no joint"):
        world.joint_state(ab)
    world.remove_joint(ca)
    assert not world.joint_alive(ca)
    with pytest.raises(sphys.Error):
        world.remove_joint(ca)


def test_joints_are_refused_in_paper_mode(sphere_tree):
    world = sphys.World(response="paper")
    body = world.add_body(sphere_tree(0.5))
    with pytest.raises(sphys.Error, match="plausible mode only"):
        world.add_joint(sphys.JointDesc(body_a=body))


def test_a_scene_dicts_joints_reach_its_simulation_and_come_back_in_to_dict():
    # A 10 cm bunny hinged 1 m below a pivot, let go 30° from the vertical: within the first
    # second (half a period, π√(1/9.81) = 1.003 s) it swings through to the other side.
    scene = sphys.Scene.from_dict({
        "format": "sphys-scene", "version": 1, "frames": 60, "ground": {"type": "none"},
        "sleep": {"enabled": False},
        "bodies": [{"size": 0.1, "position": [0.5, 1.1339746, 0],
                    "sphere_tree": {"method": "octree", "depth": 1}}],
        "joints": [{"type": "hinge", "body_a": None, "body_b": 0, "anchor_a": [0, 2, 0],
                    "anchor_b": [-0.5, 0.8660254, 0], "axis_a": [0, 0, 1],
                    "axis_b": [0, 0, 1], "limit": {"lower": -1, "upper": 1}}],
    })
    written = scene.to_dict()["joints"]
    assert len(written) == 1 and written[0]["type"] == "hinge" and written[0]["body_a"] is None
    assert written[0]["limit"] == {"enabled": True, "lower": -1, "upper": 1}
    simulation = sphys.Simulation(scene)
    lowest = 1.0
    for _ in range(60):
        simulation.step()
        bob = simulation.poses()[0, :3]
        lowest = min(lowest, bob[0])
        assert abs(np.linalg.norm(bob - (0, 2, 0)) - 1.0) < 0.01
    assert lowest < -0.4
    with pytest.raises(sphys.Error, match="/joints/0/body_b: no body 3"):
        sphys.Scene.from_dict({"format": "sphys-scene", "version": 1, "bodies": [{}],
                               "joints": [{"type": "ball", "body_a": 0, "body_b": 3}]})


def test_a_recording_keeps_the_scenes_joints(tmp_path, simulate_cli):
    scene = {
        "format": "sphys-scene", "version": 1, "ground": {"type": "none"},
        "bodies": [{"size": 0.1, "position": [0.5, 1.1339746, 0],
                    "sphere_tree": {"method": "octree", "depth": 1}}],
        "joints": [{"type": "hinge", "body_a": None, "body_b": 0, "anchor_a": [0, 2, 0],
                    "anchor_b": [-0.5, 0.875, 0], "axis_a": [0, 0, 1], "axis_b": [0, 0, 1]}],
    }
    path = tmp_path / "pendulum.json"
    path.write_text(json.dumps(scene))
    _, recording_path = simulate_cli(str(path), "3")
    recording = sphys.read_recording(str(recording_path))
    assert recording.joints == [{"type": sphys.JointType.HINGE, "body_a": None, "body_b": 0,
                                 "anchor_a": (0.0, 2.0, 0.0), "anchor_b": (-0.5, 0.875, 0.0)}]
