"""Worlds: bodies, stepping, poses, velocities and contacts against closed forms (free fall,
Newton's law of restitution, impulses, the contact geometry of eq. 1-3), settings, StepStats,
errors, and stepping with the GIL released."""

import math
import textwrap
import threading
import time

import numpy as np
import pytest

import sphys

DT = 1.0 / 60.0
GROUND = 0xFFFFFFFF  # contacts()["bodies"] index of the exact ground plane (sphys/contact.h)


def quat_about(axis, angle):
    """The unit quaternion (x, y, z, w) of a turn by `angle` (rad) about `axis`."""
    axis = np.asarray(axis, dtype=np.float64)
    axis = axis / np.linalg.norm(axis)
    return (*(math.sin(angle / 2) * axis), math.cos(angle / 2))


def rotation_matrix(q):
    """The rotation matrix of a unit quaternion (x, y, z, w)."""
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


# ---------------------------------------------------------------------------------------------
# Free fall


@pytest.mark.parametrize("gravity", [(0.0, -9.81, 0.0), (0.0, 0.0, -9.81)], ids=["y-up", "z-up"])
def test_free_fall_is_exactly_semi_implicit_euler(sphere_tree, gravity):
    # One collision pass per step (max_collision_passes=1 turns the adaptive passes off), no
    # ground: the soft step's 6 substeps of h = dt / 6 are each v += g h, then x += v h, in float32
    # (src/dynamics/soft_step_solver.cpp, src/bodies/rigid_body.cpp). numpy's float32 does the
    # same operations, each rounded once (the library is not built with fused multiply-adds), so
    # the two agree bit for bit.
    world = sphys.World(gravity=gravity, max_collision_passes=1)
    start = (1.0, 10.0, 2.0)
    body = world.add_body(sphere_tree(0.5), position=start)
    g = np.array(gravity, dtype=np.float32)
    h = np.float32(np.float32(DT) / np.float32(6))
    x = np.array(start, dtype=np.float32)
    v = np.zeros(3, dtype=np.float32)
    steps = 60
    for _ in range(steps):
        stats = world.step(DT)
        assert stats.collision_passes == 1
        for _ in range(6):
            v = (v + g * h).astype(np.float32)
            x = (x + v * h).astype(np.float32)
    np.testing.assert_array_equal(world.poses([body])[0, :3], x)
    np.testing.assert_array_equal(world.velocities([body])[0, :3], v)
    np.testing.assert_array_equal(world.velocities([body])[0, 3:], 0.0)
    np.testing.assert_array_equal(world.poses([body])[0, 3:], [0, 0, 0, 1])  # no turn

    # And against the closed form: semi-implicit Euler with step h falls further than
    # x0 + g t²/2 by exactly |g| h t / 2 (x_n = x0 + g h² n(n+1)/2); the velocity is g t.
    t = steps * DT
    exact = np.array(start) + np.array(gravity) * t * t / 2
    lag = np.array(gravity) * (DT / 6) * t / 2
    np.testing.assert_allclose(world.poses()[0, :3], exact + lag, atol=2e-5)
    np.testing.assert_allclose(world.velocities()[0, :3], np.array(gravity) * t, atol=2e-5)


def test_free_fall_with_adaptive_collision_passes_stays_within_the_euler_bound(sphere_tree):
    # By default a fast body takes more collision passes, each of 6 solver substeps. Each
    # substep of length h falls g h²/2 further than the exact parabola, so after time t the extra fall is between 0 and g dt t / 2 (all
    # h <= dt, summing to t); the velocity is g t exactly whatever the substeps.
    world = sphys.World(plausibility_figures=True)
    mass = 2.0
    body = world.add_body(sphere_tree(0.5), position=(0.0, 10.0, 0.0), mass=mass)
    steps = 90
    passes = []
    for _ in range(steps):
        passes.append(world.step(DT).collision_passes)
    assert max(passes) > 1, "the falling body should have needed more collision passes"
    t = steps * DT
    g = 9.81
    y = float(world.poses([body])[0, 1])
    parabola = 10.0 - g * t * t / 2
    slack = 1e-4  # float32 rounding of a position near 10 m over 90 steps
    assert parabola - g * DT * t / 2 - slack <= y <= parabola + slack
    vy = float(world.velocities([body])[0, 1])
    # g h added in float32 once per solver substep, some thousand times.
    assert vy == pytest.approx(-g * t, abs=5e-4)
    # The kinetic energy the step reports is ½ m v² of the one moving body.
    assert world.stats.kinetic_energy == pytest.approx(0.5 * mass * vy * vy, rel=1e-6)
    assert world.stats.bodies == 1 and world.stats.movable_bodies == 1
    assert world.stats.contacts == 0 and world.stats.candidate_pairs == 0


# ---------------------------------------------------------------------------------------------
# Bodies


def test_add_remove_alive_body_ids_len(sphere_tree):
    world = sphys.World()
    assert len(world) == 0 and world.body_ids() == []
    assert world.poses().shape == (0, 7) and world.velocities().shape == (0, 6)
    a = world.add_body(sphere_tree(), position=(0, 0, 0))
    b = world.add_body(sphere_tree(), position=(3, 0, 0))
    c = world.add_body(sphere_tree(), position=(6, 0, 0))
    assert (a.index, a.generation) == (0, 1) and not a.is_null
    assert (b.index, c.index) == (1, 2)
    assert world.body_ids() == [a, b, c] and len(world) == 3
    assert all(world.alive(x) for x in (a, b, c))

    world.remove_body(b)
    assert not world.alive(b) and world.alive(a) and world.alive(c)
    assert world.body_ids() == [a, c] and len(world) == 2
    # poses() follows body_ids(): the removed body's row is gone.
    np.testing.assert_array_equal(world.poses()[:, 0], [0, 6])

    # The freed slot is reused with a new generation: the old id never names the new body.
    d = world.add_body(sphere_tree(), position=(9, 0, 0))
    assert d.index == b.index and d.generation == b.generation + 1
    assert d != b and not world.alive(b) and world.alive(d)
    assert hash(d) != hash(b) and len({a, b, c, d}) == 4
    assert repr(d) == f"BodyId(index={d.index}, generation={d.generation})"
    assert world.body_ids() == [a, d, c]
    np.testing.assert_array_equal(world.poses()[:, 0], [0, 9, 6])


def test_add_body_state_reads_back(sphere_tree):
    world = sphys.World()
    q = quat_about((1, 2, 3), 0.7)
    body = world.add_body(sphere_tree(), position=(1.5, -2.0, 3.25), orientation=q,
                          linear_velocity=(0.5, 0.25, -1.0), angular_velocity=(0.1, -0.2, 0.3))
    pose = world.poses([body])
    assert pose.dtype == np.float32 and pose.shape == (1, 7)
    np.testing.assert_array_equal(pose[0, :3], np.float32([1.5, -2.0, 3.25]))
    np.testing.assert_allclose(pose[0, 3:], q, atol=1e-7)
    vel = world.velocities([body])
    assert vel.dtype == np.float32 and vel.shape == (1, 6)
    np.testing.assert_array_equal(vel[0], np.float32([0.5, 0.25, -1.0, 0.1, -0.2, 0.3]))
    # A quaternion within 1e-3 of unit length is accepted and normalised.
    other = world.add_body(sphere_tree(), position=(5, 0, 0), orientation=(0, 0, 0, 1.0005))
    np.testing.assert_allclose(world.poses([other])[0, 3:], [0, 0, 0, 1], atol=1e-7)
    # Rows follow the ids asked for, in their order.
    np.testing.assert_array_equal(world.poses([other, body])[:, 0], [5, 1.5])
    np.testing.assert_array_equal(world.velocities([other, body])[:, 0], [0, 0.5])
    assert world.poses([]).shape == (0, 7)


def test_poses_and_velocities_are_copies(sphere_tree):
    world = sphys.World()
    world.add_body(sphere_tree(), position=(0, 5, 0))
    poses, velocities = world.poses(), world.velocities()
    assert poses.flags.writeable and poses.flags.c_contiguous
    world.step(DT, steps=3)
    np.testing.assert_array_equal(poses[0, :3], [0, 5, 0])
    np.testing.assert_array_equal(velocities[0], 0)
    assert world.poses()[0, 1] < 5
    poses[0, 1] = 99.0  # writing to the copy leaves the world alone
    assert world.poses()[0, 1] < 5


def test_set_velocity_and_apply_impulse(sphere_tree):
    world = sphys.World(gravity=(0, 0, 0))
    mass = 2.0
    inertia = np.diag([2.0, 4.0, 8.0])
    q = quat_about((0, 0, 1), math.pi / 2)  # body x along world y
    body = world.add_body(sphere_tree(), position=(1.0, 2.0, 3.0), orientation=q, mass=mass,
                          inertia=inertia)
    world.set_velocity(body, (1.0, -2.0, 0.5), (0.25, 0.0, -0.5))
    np.testing.assert_array_equal(world.velocities([body])[0], [1.0, -2.0, 0.5, 0.25, 0.0, -0.5])
    world.set_velocity(body, (3.0, 0.0, 0.0))  # angular defaults to zero
    np.testing.assert_array_equal(world.velocities([body])[0], [3, 0, 0, 0, 0, 0])

    # Through the centre of mass: Δv = J / m exactly (1/2 is exact in float), no turn.
    impulse = np.array([1.0, 2.0, -3.0])
    world.apply_impulse(body, impulse, (1.0, 2.0, 3.0))
    np.testing.assert_array_equal(world.velocities([body])[0], [3.5, 1.0, -1.5, 0, 0, 0])

    # Off the centre: Δω = I_world⁻¹ (r × J) with I_world = R I_body Rᵀ.
    r = np.array([0.0, 0.5, 0.0])
    world.apply_impulse(body, impulse, np.array([1.0, 2.0, 3.0]) + r)
    R = rotation_matrix(q)
    expected_w = np.linalg.solve(R @ inertia @ R.T, np.cross(r, impulse))
    got = world.velocities([body])[0]
    np.testing.assert_allclose(got[:3], [4.0, 2.0, -3.0], atol=1e-6)
    np.testing.assert_allclose(got[3:], expected_w, atol=1e-6)
    # (The rotation matters: with the body's own axes the answer would differ.)
    assert not np.allclose(expected_w, np.linalg.solve(inertia, np.cross(r, impulse)))


def test_apply_force_and_torque_act_through_the_next_step_only(sphere_tree):
    world = sphys.World(gravity=(0, 0, 0))
    mass = 2.0
    inertia = np.diag([2.0, 4.0, 8.0])
    body = world.add_body(sphere_tree(), position=(0.0, 5.0, 0.0), mass=mass, inertia=inertia)
    force = np.array([4.0, 0.0, -2.0])
    torque = np.array([0.0, 0.0, 1.6])  # about a principal axis: no precession
    for _ in range(60):
        world.apply_force(body, force, world.poses([body])[0][:3])  # through the centre
        world.apply_torque(body, torque)
        world.step(DT)
    # One second of each: Δv = F t / m, Δω = I⁻¹ τ t.
    v = world.velocities([body])[0]
    np.testing.assert_allclose(v[:3], force / mass, rtol=1e-4)
    np.testing.assert_allclose(v[3:], [0.0, 0.0, 1.6 / 8.0], rtol=1e-4, atol=1e-6)
    # Off the centre, a force turns the body too; a step without a new force changes nothing.
    world.apply_force(body, (0.0, 1.0, 0.0), world.poses([body])[0][:3] + np.array([1.0, 0.0, 0.0]))
    world.step(DT)
    after = world.velocities([body])[0]
    assert after[5] > v[5]
    world.step(DT)
    np.testing.assert_allclose(world.velocities([body])[0], after, rtol=1e-6, atol=1e-9)
    with pytest.raises(sphys.Error):
        world.apply_force(body, (float("nan"), 0, 0), (0, 0, 0))


def test_static_body_does_not_move(sphere_tree):
    world = sphys.World()
    wall = world.add_body(sphere_tree(), position=(0, 1, 0), static=True)
    ball = world.add_body(sphere_tree(), position=(5, 1, 0))
    world.set_velocity(wall, (1, 0, 0))  # a static body keeps still
    stats = world.step(DT, steps=10)
    np.testing.assert_array_equal(world.poses([wall])[0], [0, 1, 0, 0, 0, 0, 1])
    np.testing.assert_array_equal(world.velocities([wall])[0], 0)
    assert world.poses([ball])[0, 1] < 1
    assert stats.bodies == 2 and stats.movable_bodies == 1


# ---------------------------------------------------------------------------------------------
# Contacts and collisions


def test_sphere_comes_to_rest_on_the_ground_plane_and_sleeps(sphere_tree):
    height = -2.0
    radius = 0.5
    world = sphys.World(ground_plane=height, plausibility_figures=True)
    assert world.ground_plane == height
    body = world.add_body(sphere_tree(radius), position=(0.25, height + radius + 0.2, -0.5))
    slept_at = None
    for frame in range(240):  # 4 s; the default sleep time is 0.5 s
        stats = world.step(DT)
        if world.asleep(body):
            slept_at = frame
            break
        contacts = world.contacts()
        if len(contacts["depths"]):
            # A sphere over the plane: one contact, the plane first, normal +y.
            np.testing.assert_array_equal(contacts["bodies"], [[GROUND, body.index]])
            np.testing.assert_array_equal(contacts["normals"], [[0, 1, 0]])
    assert slept_at is not None, "the sphere never fell asleep"
    assert stats.bodies_asleep == 1 and stats.bodies_at_rest == 1
    assert stats.kinetic_energy == 0.0
    pose = world.poses([body])[0]
    # At rest on the plane: the centre one radius above it, within the solver's slop (0.4 mm);
    # the plausibility figure agrees.
    assert pose[1] == pytest.approx(height + radius, abs=1e-3)
    assert stats.deepest_penetration <= 1e-3
    np.testing.assert_allclose(pose[[0, 2]], [0.25, -0.5], atol=1e-6)  # fell straight down
    np.testing.assert_array_equal(world.velocities([body]), 0)
    contacts = world.contacts()
    np.testing.assert_array_equal(contacts["bodies"], [[GROUND, body.index]])
    np.testing.assert_allclose(contacts["points"], [[0.25, height, -0.5]], atol=1e-3)
    assert abs(contacts["depths"][0]) <= 1e-3

    # A sleeping body stays put; set_velocity and apply_impulse wake it.
    world.step(DT, steps=5)
    np.testing.assert_array_equal(world.poses([body])[0], pose)
    world.set_velocity(body, (0, 2, 0))
    assert not world.asleep(body)
    world.step(DT, steps=120)
    assert world.asleep(body)
    world.apply_impulse(body, (0, 1, 0), world.poses([body])[0, :3])
    assert not world.asleep(body)
    assert world.velocities([body])[0, 1] == pytest.approx(1.0)  # mass 1


@pytest.mark.parametrize("mode", ["paper", "plausible"])
def test_contacts_match_the_sphere_geometry(sphere_tree, mode):
    # Two single-sphere bodies approach. One collision pass per step, so the contacts of a step are made
    # from the poses it started with: v = C2 - C1, n = v/|v|, P = C1 + r1/(r1+r2) v,
    # depth = r1 + r2 - |v| (eq. 1-3). Paper mode makes contacts from overlaps only (depth >= 0);
    # plausible mode also from gaps up to its margin (negative depth).
    r1, r2 = 0.5, 0.25
    world = sphys.World(gravity=(0, 0, 0), response=mode, max_collision_passes=1)
    a = world.add_body(sphere_tree(r1), position=(-1.0, 0.2, 0.0), linear_velocity=(2, 0, 0))
    b = world.add_body(sphere_tree(r2), position=(1.0, 0.0, 0.1), linear_velocity=(-1, 0, 0),
                       mass=3.0)
    seen = 0
    for _ in range(40):
        before = world.poses().astype(np.float64)
        world.step(DT)
        c = world.contacts()
        k = len(c["depths"])
        assert c["bodies"].shape == (k, 2) and c["bodies"].dtype == np.uint32
        assert c["points"].shape == (k, 3) and c["points"].dtype == np.float32
        assert c["normals"].shape == (k, 3) and c["normals"].dtype == np.float32
        assert c["depths"].shape == (k,) and c["depths"].dtype == np.float32
        if k == 0:
            continue
        seen += 1
        assert k == 1
        np.testing.assert_array_equal(c["bodies"], [[a.index, b.index]])
        np.testing.assert_allclose(np.linalg.norm(c["normals"], axis=1), 1.0, atol=1e-6)
        v = before[1, :3] - before[0, :3]
        distance = np.linalg.norm(v)
        np.testing.assert_allclose(c["normals"][0], v / distance, atol=1e-6)
        np.testing.assert_allclose(c["points"][0], before[0, :3] + r1 / (r1 + r2) * v, atol=1e-6)
        assert c["depths"][0] == pytest.approx(r1 + r2 - distance, abs=1e-6)
        if mode == "paper":
            assert c["depths"][0] >= 0
        else:
            # A gap contact: no further apart than the margin plus how far they close in a step.
            assert c["depths"][0] >= -(0.02 + 3.0 * DT)
    assert seen >= 1


@pytest.mark.parametrize("mode", ["paper", "plausible"])
def test_head_on_collision_obeys_newtons_law_of_restitution(sphere_tree, mode):
    # Equal spheres, centres on the x axis, no gravity, no ground. With restitution e (each body's
    # 0.5, the mix takes the larger):
    #   v1' = (m1 v1 + m2 v2 - m2 e (v1 - v2)) / (m1 + m2),  v2' = (... + m1 e (v1 - v2)) / (...)
    e, m1, m2, v1, v2 = 0.5, 1.0, 3.0, 2.0, -1.0
    world = sphys.World(gravity=(0, 0, 0), response=mode)
    a = world.add_body(sphere_tree(), position=(-1, 0, 0), linear_velocity=(v1, 0, 0), mass=m1,
                       restitution=e)
    b = world.add_body(sphere_tree(), position=(1, 0, 0), linear_velocity=(v2, 0, 0), mass=m2,
                       restitution=e)
    world.step(DT, steps=60)
    p = m1 * v1 + m2 * v2
    expected = [(p - m2 * e * (v1 - v2)) / (m1 + m2), (p + m1 * e * (v1 - v2)) / (m1 + m2)]
    vel = world.velocities([a, b])
    np.testing.assert_allclose(vel[:, 0], expected, atol=1e-5)
    np.testing.assert_allclose(vel[:, 1:], 0, atol=1e-6)


@pytest.mark.parametrize("mode", ["paper", "plausible"])
def test_oblique_collision_conserves_linear_momentum(sphere_tree, mode):
    # Off-centre, in 3D, with friction in plausible mode: every impulse acts on both bodies,
    # equal and opposite, so the total momentum stays (float32 rounding aside).
    world = sphys.World(gravity=(0, 0, 0), response=mode)
    masses = np.array([1.0, 3.0])
    a = world.add_body(sphere_tree(), position=(-1, 0.2, 0), linear_velocity=(2, 0, 0),
                       mass=masses[0], angular_velocity=(0, 0, 5))
    b = world.add_body(sphere_tree(0.4), position=(1, 0, 0.1), linear_velocity=(-1, 0.5, 0),
                       mass=masses[1])
    momentum = lambda: (world.velocities([a, b])[:, :3].astype(np.float64) * masses[:, None]).sum(0)
    before = momentum()
    touched = False
    for _ in range(60):
        world.step(DT)
        touched |= len(world.contacts()["depths"]) > 0
    assert touched
    after = momentum()
    np.testing.assert_allclose(after, before, atol=1e-5)
    # The collision did something: both bodies changed course.
    vel = world.velocities([a, b])
    assert vel[0, 0] < 2 - 0.5 and vel[1, 0] > -1 + 0.1


def test_set_pair_material_overrides_the_mix(sphere_tree):
    # Both bodies have restitution 0: a perfectly inelastic collision, both move on together at
    # p / (m1 + m2). The pair's material (restitution 1, either order of the ids) makes it
    # elastic: v1' = (p - m2 (v1 - v2)) / M, v2' = (p + m1 (v1 - v2)) / M. Pair materials are
    # plausible mode's (docs/scenes.md).
    def collide(pair_material):
        world = sphys.World(gravity=(0, 0, 0))
        a = world.add_body(sphere_tree(), position=(-1, 0, 0), linear_velocity=(2, 0, 0),
                           restitution=0.0)
        b = world.add_body(sphere_tree(), position=(1, 0, 0), linear_velocity=(-1, 0, 0), mass=3,
                           restitution=0.0)
        if pair_material is not None:
            world.set_pair_material(b, a, friction=0.0, restitution=pair_material)
        world.step(DT, steps=60)
        return world.velocities([a, b])[:, 0]

    np.testing.assert_allclose(collide(None), [-0.25, -0.25], atol=1e-5)
    np.testing.assert_allclose(collide(1.0), [-2.5, 0.5], atol=1e-5)
    np.testing.assert_allclose(collide(0.5), [-1.375, 0.125], atol=1e-5)


def test_set_pair_material_errors(sphere_tree):
    world = sphys.World()
    a = world.add_body(sphere_tree())
    b = world.add_body(sphere_tree(), position=(3, 0, 0))
    with pytest.raises(sphys.Error, match="friction"):
        world.set_pair_material(a, b, friction=-1.0, restitution=0.5)
    with pytest.raises(sphys.Error, match="restitution"):
        world.set_pair_material(a, b, friction=0.5, restitution=1.5)
    world.remove_body(b)
    with pytest.raises(sphys.Error, match="no body"):
        world.set_pair_material(a, b, friction=0.5, restitution=0.5)


def test_set_detection_budget():
    # A settling pile of three bunnies: exact detection cuts no pair short; a budget of a few
    # sphere tests cuts pairs short and tests fewer spheres; 0 and 0 turn the budgets off again.
    sim = sphys.Simulation("stacks:1x3")
    world = sim.world
    exact = sim.step(40)
    assert exact.pairs_cut_short == 0 and exact.contacts > 0
    world.set_detection_budget(5, 0)
    cut = sim.step()
    assert cut.pairs_cut_short > 0
    assert cut.sphere_tests < exact.sphere_tests
    world.set_detection_budget(0, 250.5)
    assert world.settings["collision.max_microseconds"] == 250.5
    world.set_detection_budget(0, 0)
    assert world.settings["collision.max_microseconds"] == 0.0
    again = sim.step()
    assert again.pairs_cut_short == 0
    with pytest.raises(sphys.Error, match="max_microseconds"):
        world.set_detection_budget(0, -1.0)
    with pytest.raises(sphys.Error, match="max_microseconds"):
        world.set_detection_budget(0, float("nan"))


# ---------------------------------------------------------------------------------------------
# Stepping, stats, a world that goes non-finite


def test_step_steps_and_stats(sphere_tree):
    one = sphys.World(max_collision_passes=1)
    many = sphys.World(max_collision_passes=1)
    for w in (one, many):
        w.add_body(sphere_tree(), position=(0, 5, 0))
    for _ in range(7):
        last = one.step(DT)
    stats = many.step(DT, steps=7)
    np.testing.assert_array_equal(one.poses(), many.poses())  # steps=7 is 7 steps of dt
    assert isinstance(stats, sphys.StepStats)
    d = stats.to_dict()
    assert many.stats.to_dict() == d  # the world keeps the last step's figures
    # Every figure is a property, and to_dict holds exactly those.
    names = {n for n in dir(stats) if not n.startswith("_") and n != "to_dict"}
    assert set(d) == names
    for name in names:
        assert d[name] == getattr(stats, name), name
    # Counts are ints, measures floats (sphys/step_stats.h's table of figures says which).
    assert isinstance(d["sphere_tests"], int) and isinstance(d["islands"], int)
    assert isinstance(d["step_ms"], float) and isinstance(d["jitter"], float)
    assert d["detection_ms"] == pytest.approx(
        stats.broad_phase_ms + stats.narrow_phase_ms + stats.contacts_ms)
    assert 0 <= stats.integration_ms <= stats.step_ms
    assert 0 <= stats.sleep_ms <= stats.step_ms
    assert sphys.GROUND_PLANE_BODY == GROUND
    assert d["bodies"] == 1 and d["movable_bodies"] == 1 and d["collision_passes"] == 1
    assert d["contacts"] == 0 and d["non_finite_body"] is None
    assert last.bodies == stats.bodies
    assert "contacts" in repr(stats) and repr(stats).startswith("<sphys.StepStats")


def test_step_stats_count_a_two_sphere_collision(sphere_tree):
    # Two single-sphere bodies, head on (as in the restitution test), one collision pass per step: every
    # count is known. Kinetic energy: ½ m v² summed, before (3.5 J) and after the collision.
    world = sphys.World(gravity=(0, 0, 0), max_collision_passes=1, plausibility_figures=True)
    world.add_body(sphere_tree(), position=(-1, 0, 0), linear_velocity=(2, 0, 0), restitution=0.5)
    world.add_body(sphere_tree(), position=(1, 0, 0), linear_velocity=(-1, 0, 0), mass=3,
                   restitution=0.5)
    history = [world.step(DT).to_dict() for _ in range(30)]
    first = history[0]
    assert first["kinetic_energy"] == pytest.approx(0.5 * 1 * 2**2 + 0.5 * 3 * 1**2, rel=1e-6)
    assert (first["candidate_pairs"], first["sphere_tests"], first["contacts"]) == (0, 0, 0)
    assert first["islands"] == 2 and first["bodies"] == 2 and first["movable_bodies"] == 2
    touching = [k for k, s in enumerate(history) if s["contacts"]]
    assert touching, "the spheres never met"
    meet = history[touching[0]]
    # One broad-phase pair, one root-root sphere test, one leaf pair, one contact, one island;
    # nothing warm-started yet; the soft step's solve and relax passes of its 6 substeps.
    assert {k: meet[k] for k in ("candidate_pairs", "sphere_tests", "leaf_pairs", "contacts",
                                 "descended_pairs", "impulses", "contacts_solved", "islands",
                                 "warm_started",
                                 "reused_pairs", "pairs_cut_short", "coincident_centres",
                                 "response_passes", "collision_passes")} == {
        "candidate_pairs": 1, "sphere_tests": 1, "leaf_pairs": 1, "contacts": 1,
        "descended_pairs": 1, "impulses": 0, "contacts_solved": 1, "islands": 1, "warm_started": 0, "reused_pairs": 0,
        "pairs_cut_short": 0, "coincident_centres": 0, "response_passes": 12, "collision_passes": 1}
    assert history[touching[1]]["warm_started"] == 1  # the contact's impulse carried over
    bounced = [k for k, s in enumerate(history) if s["bounces"]]
    assert len(bounced) == 1 and history[bounced[0]]["bounces"] == 1  # restitution applied once
    # After the bounce: v = -1.375 and 0.125 m/s (Newton's law, e = 0.5).
    assert history[-1]["kinetic_energy"] == pytest.approx(
        0.5 * 1 * 1.375**2 + 0.5 * 3 * 0.125**2, rel=1e-6)
    # Jitter right after the bounce: of the touching bodies, only the one slower than 10x the
    # sleep speed (0.5 m/s) should be resting: mean fastest-point speed 0.125 m/s.
    assert history[bounced[0]]["jitter"] == pytest.approx(0.125, rel=1e-5)


def test_coincident_centres_take_the_fallback_normal(sphere_tree):
    # Two spheres with the same centre (and centre of mass): the normal is a unit vector drawn
    # from the pair (the same in every run), the depth r1 + r2, at the common centre; paper mode
    # gives no impulse as nothing approaches.
    normals = []
    for _ in range(2):
        world = sphys.World(gravity=(0, 0, 0), response="paper", plausibility_figures=True)
        world.add_body(sphere_tree(0.5), position=(1, 2, 3))
        world.add_body(sphere_tree(0.25), position=(1, 2, 3))
        stats = world.step(DT)
        c = world.contacts()
        normals.append(c["normals"])
    np.testing.assert_array_equal(normals[0], normals[1])
    assert c["normals"].shape == (1, 3) and abs(np.linalg.norm(c["normals"][0]) - 1) < 1e-6
    np.testing.assert_array_equal(c["depths"], [0.75])
    np.testing.assert_array_equal(c["points"], [[1, 2, 3]])
    assert stats.coincident_centres == 1 and stats.impulses == 0 and stats.response_passes == 1
    assert stats.penetrating_contacts == 1
    assert stats.deepest_penetration == 0.75 and stats.mean_penetration == 0.75
    assert stats.kinetic_energy == 0 and stats.bodies_at_rest == 2 and stats.islands == 0
    np.testing.assert_array_equal(world.velocities(), 0)


def test_world_going_non_finite_stops(sphere_tree):
    # A speed near float's limit carries the one moving body past it within two steps of 1 s
    # (the static one does not integrate). Gravity that large is refused.
    with pytest.raises(sphys.Error, match="gravity must be between -1000 and 1000"):
        sphys.World(gravity=(0, -3e38, 0))
    world = sphys.World()
    world.add_body(sphere_tree(), position=(0, 1, 0), static=True)
    body = world.add_body(sphere_tree(), position=(0, 5, 0), linear_velocity=(0, -3e38, 0))
    assert not world.stopped
    stats = world.step(1.0, steps=10)
    assert world.stopped
    assert stats.non_finite_body == body.index == 1
    assert world.stats.non_finite_body == stats.non_finite_body
    assert stats.to_dict()["non_finite_body"] == stats.non_finite_body
    frozen = world.poses()
    world.step(DT)  # a stopped world no longer steps
    np.testing.assert_array_equal(world.poses(), frozen)


# ---------------------------------------------------------------------------------------------
# Settings


def test_settings_nested_and_dotted_are_the_same():
    nested = sphys.World(solver={"contact_hertz": 20.0, "soft_substeps": 7},
                         sleep={"time": 0.25, "enabled": False}, collision_passes=3, response="paper",
                         gravity=(1.0, 2.0, -3.0), ground_friction=0.75)
    dotted = sphys.World(**{"solver.contact_hertz": 20.0, "solver.soft_substeps": 7,
                            "sleep.time": 0.25, "sleep.enabled": False}, collision_passes=3,
                         response="paper", gravity=np.array([1.0, 2.0, -3.0]),
                         ground_friction=0.75)
    s = nested.settings
    assert s == dotted.settings
    assert s["solver.contact_hertz"] == 20.0 and s["solver.soft_substeps"] == 7
    assert s["sleep.time"] == 0.25 and s["sleep.enabled"] is False
    assert s["collision_passes"] == 3 and s["response"] == "paper" and s["ground_friction"] == 0.75
    assert s["gravity"] == (1.0, 2.0, -3.0)
    # Everything not given keeps its default.
    defaults = sphys.World().settings
    given = {"solver.contact_hertz", "solver.soft_substeps", "sleep.time", "sleep.enabled",
             "collision_passes", "response", "gravity", "ground_friction"}
    assert {k: v for k, v in s.items() if k not in given} == {
        k: v for k, v in defaults.items() if k not in given}
    # A world's settings make the same world again.
    assert sphys.World(**s).settings == s
    # numpy scalars are numbers too.
    w = sphys.World(collision_pass_travel=np.float64(0.25), threads=np.int64(2))
    assert w.settings["collision_pass_travel"] == 0.25 and w.settings["threads"] == 2


def test_settings_table():
    table = sphys.settings_table()
    defaults = sphys.World().settings
    assert [row["field"] for row in table] == list(defaults)
    for row in table:
        assert set(row) == {"field", "unit", "valid", "default", "doc"}
        assert row["default"] == defaults[row["field"]], row["field"]
        assert row["doc"]
    rows = {row["field"]: row for row in table}
    assert rows["collision_passes"]["valid"] == "1 to 64"
    assert rows["collision_passes"]["unit"] == "collision passes"
    assert rows["collision_passes"]["default"] == 1
    assert rows["solver.soft_substeps"]["default"] == 6
    assert rows["sleep.enabled"]["default"] is True
    assert rows["solver.linear_slop"]["default"] == 0.0004 and rows["solver.linear_slop"]["unit"] == "m"
    # The default gravity (a float32 vector: compared as float32, whichever double shows it).
    gravity = rows["gravity"]["default"]
    assert isinstance(gravity, tuple) and len(gravity) == 3
    np.testing.assert_array_equal(np.float32(gravity), np.float32([0.0, -9.81, 0.0]))
    assert rows["gravity"]["unit"] == "m/s²"


def test_settings_take_effect(sphere_tree):
    # Gravity along x; and sleep off keeps a resting sphere awake.
    world = sphys.World(gravity=(2.0, 0.0, 0.0), max_collision_passes=1)
    world.add_body(sphere_tree())
    world.step(DT, steps=30)
    v = world.velocities()[0]
    assert v[0] == pytest.approx(2.0 * 30 * DT, rel=1e-5) and v[1] == 0 and v[2] == 0
    awake = sphys.World(ground_plane=0.0, sleep={"enabled": False})
    sleepy = sphys.World(ground_plane=0.0)
    ids = [w.add_body(sphere_tree(), position=(0, 0.5, 0)) for w in (awake, sleepy)]
    awake.step(DT, steps=90)
    sleepy.step(DT, steps=90)
    assert not awake.asleep(ids[0]) and sleepy.asleep(ids[1])


@pytest.mark.parametrize("settings, names", [
    ({"bogus": 1}, "bogus"),
    ({"solver": {"bogus": 1}}, "solver.bogus"),
    ({"solver.method": "soft_step"}, "solver.method was removed"),
    ({"solver": {"velocity_iterations": 20}}, "solver.velocity_iterations was removed"),
    ({"substeps": 2}, "substeps was removed: renamed collision_passes"),
    ({"collision_passes": 0}, "collision_passes"),
    ({"collision_passes": 2.5}, "collision_passes"),
    ({"sleep": {"time": -1.0}}, "sleep.time"),
    ({"sleep.enabled": "maybe"}, "sleep.enabled"),
    ({"gravity": (0, 1)}, "gravity"),
    ({"gravity": (0, float("nan"), 0)}, "gravity"),
    ({"solver": 3}, "solver"),
    ({"ground_plane": float("nan")}, "ground_plane"),
])
def test_bad_settings_raise_naming_the_setting(settings, names):
    with pytest.raises(sphys.Error, match=names.replace(".", r"\.")):
        sphys.World(**settings)
    assert issubclass(sphys.Error, ValueError)


def test_ground_plane_of_the_wrong_type_raises_naming_it():
    # A ground plane height that is not a number is a bad argument like a NaN one.
    with pytest.raises((sphys.Error, TypeError), match="ground_plane"):
        sphys.World(ground_plane="high")


def test_bad_body_arguments_raise_naming_them(sphere_tree):
    world = sphys.World()
    tree = sphere_tree()
    cases = [
        (dict(mass=-1.0), "mass"),
        (dict(mass=0.0), "mass"),
        (dict(mass=float("nan")), "mass"),
        (dict(position=(0, float("nan"), 0)), "position"),
        (dict(position=(0, 0)), "position"),
        (dict(position=np.zeros((3, 1, 2))), "position"),
        (dict(position="abc"), "position"),
        (dict(orientation=(0, 0, 0, 2)), "orientation"),
        (dict(orientation=(0, 0, 1)), "orientation"),
        (dict(linear_velocity=(float("inf"), 0, 0)), "linear_velocity"),
        (dict(angular_velocity=(0, 0, 0, 0)), "angular_velocity"),
        (dict(inertia=np.eye(2)), "inertia"),
        (dict(inertia=np.ones((3, 4))), "inertia"),
        (dict(inertia=-np.eye(3)), "inertia"),
        (dict(inertia=[[1, 2, 0], [0, 1, 0], [0, 0, 1]]), "inertia"),
        (dict(restitution=2.0), "restitution"),
        (dict(friction=-1.0), "friction"),
    ]
    for kwargs, name in cases:
        with pytest.raises(sphys.Error, match=name):
            world.add_body(tree, **kwargs)
    with pytest.raises(sphys.Error, match="sphere-tree"):
        world.add_body(None)
    assert len(world) == 0  # nothing was added by a refused call
    body = world.add_body(tree)
    with pytest.raises(sphys.Error, match="linear"):
        world.set_velocity(body, (float("nan"), 0, 0))
    with pytest.raises(sphys.Error, match="angular"):
        world.set_velocity(body, (0, 0, 0), (1, 2))
    with pytest.raises(sphys.Error, match="impulse"):
        world.apply_impulse(body, (1, 2), (0, 0, 0))
    with pytest.raises(sphys.Error, match="point"):
        world.apply_impulse(body, (1, 0, 0), (0, float("nan"), 0))
    with pytest.raises(sphys.Error, match="time step"):
        world.step(0.0)
    with pytest.raises(sphys.Error, match="time step"):
        world.step(float("nan"))
    with pytest.raises(sphys.Error, match="steps"):
        world.step(DT, steps=0)
    np.testing.assert_array_equal(world.velocities(), 0)  # nothing was changed either


def test_removed_body_id_raises(sphere_tree):
    world = sphys.World()
    keep = world.add_body(sphere_tree())
    gone = world.add_body(sphere_tree(), position=(3, 0, 0))
    world.remove_body(gone)
    # The slot is reused: the old id still names nothing.
    again = world.add_body(sphere_tree(), position=(6, 0, 0))
    assert again.index == gone.index and again != gone
    for call in _calls_taking_an_id(world, gone, keep):
        with pytest.raises(sphys.Error,
                           match=f"no body with id {gone.index}.{gone.generation} in the world"):
            call()
    assert world.body_ids() == [keep, again]


def _calls_taking_an_id(world, body, other):
    return (lambda: world.remove_body(body),
            lambda: world.asleep(body),
            lambda: world.set_velocity(body, (1, 0, 0)),
            lambda: world.apply_impulse(body, (1, 0, 0), (0, 0, 0)),
            lambda: world.set_pair_material(body, other, friction=0.5, restitution=0.5),
            lambda: world.set_pair_material(other, body, friction=0.5, restitution=0.5),
            lambda: world.poses([other, body]),
            lambda: world.velocities([body]))


def test_the_null_body_id_names_no_body(sphere_tree):
    world = sphys.World()
    first = world.add_body(sphere_tree())
    none = sphys.BodyId()
    assert none.is_null and (none.index, none.generation) == (0, 0)
    assert none != first and not world.alive(none)
    for call in _calls_taking_an_id(world, none, first):
        with pytest.raises(sphys.Error, match=r"the null body id \(BodyId\{\}\) names no body"):
            call()
    assert world.alive(first) and world.body_ids() == [first]


# ---------------------------------------------------------------------------------------------
# The GIL is released while stepping


def _stack_simulations(count):
    scene = sphys.load_scene("stacks:4x50")
    return scene, [sphys.Simulation(scene) for _ in range(count)]


@pytest.mark.parametrize("stepper", ["Simulation.step", "World.step"])
def test_two_threads_step_concurrently_and_deterministically(stepper, side_by_side):
    # Two 200-bunny worlds, each stepped by its own thread. With a switch interval of 1000 s a
    # thread that holds the GIL keeps it until it blocks or releases it, so were the GIL held
    # during a step, the threads' step calls could never overlap in time. They must, and each
    # world must end bit for bit where the same simulation stepped alone ends.
    frames = 30
    scene, (first, second, alone) = _stack_simulations(3)
    assert len(scene) == 200 and len(first.world) == 200  # the bunnies (the plane is no body)
    dt = scene.time_step
    intervals = [[], []]
    barrier = threading.Barrier(2)
    errors = []

    def work(k, sim):
        try:
            step = sim.step if stepper == "Simulation.step" else (lambda: sim.world.step(dt))
            barrier.wait()
            for _ in range(frames):
                start = time.perf_counter()
                step()
                intervals[k].append((start, time.perf_counter()))
        except BaseException as error:  # reported by the main thread
            errors.append(error)

    side_by_side(lambda k: work(k, (first, second)[k]))
    assert not errors, errors
    assert len(intervals[0]) == len(intervals[1]) == frames
    overlapping = [(a, b) for a in intervals[0] for b in intervals[1]
                   if a[0] < b[1] and b[0] < a[1]]
    assert overlapping, "no step of one thread overlapped a step of the other: the GIL was held"

    alone.step(frames)
    expected = alone.world.poses()
    assert alone.world.stats.contacts > 0  # the piles are colliding by then
    for sim in (first, second):
        np.testing.assert_array_equal(sim.world.poses(), expected)
        np.testing.assert_array_equal(sim.world.velocities(), alone.world.velocities())


def test_world_outlives_its_simulation(isolated):
    # Simulation.world is a reference into the simulation; it keeps the simulation alive.
    isolated(textwrap.dedent("""
        import gc, sphys
        world = sphys.Simulation("stacks:1x2").world
        gc.collect()
        world.step(1 / 60, steps=5)
        assert len(world) == 2, len(world)
        assert world.poses().shape == (2, 7)
    """))


def test_the_solver_lanes_are_chosen_when_a_world_is_made_and_named():
    world = sphys.World()
    assert world.settings["solver.lanes"] == "auto"  # as given
    assert world.solver_lanes in ("avx2", "sse2", "portable")
    assert sphys.World(solver={"lanes": "portable"}).solver_lanes == "portable"
    with pytest.raises(sphys.Error, match="solver.lanes"):
        sphys.World(solver={"lanes": "avx512"})
