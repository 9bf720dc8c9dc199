"""One world, many threads (docs/python.md): calls on one world from several Python threads take
turns, so stepping, adding, removing, reading, querying and checking configurations at once never
corrupt memory, and where the calls commute the end state is that of the same calls made one
after another. A WorldQuery, once made, answers from many threads while its world steps and
loses bodies. SPHYS_THREAD_ROUNDS repeats every test that many times in one run (default 1)."""

import os
import sys
import threading

import numpy as np
import pytest

import sphys

DT = 1.0 / 60.0
ROUNDS = int(os.environ.get("SPHYS_THREAD_ROUNDS", "1"))
THREAD_COUNTS = [2, 4, 8]


@pytest.fixture(scope="module")
def ball():
    """A small icosphere's octree sphere-tree (radius 0.1 m, 9 spheres), shared by every body."""
    return sphys.build_tree(sphys.icosphere(0.1, 1), method="octree", branching=8, depth=2)


@pytest.fixture(autouse=True)
def busy_switching():
    """Threads hand the GIL over every 10 µs, so that their calls interleave as tightly as the
    library lets them."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-5)
    yield
    sys.setswitchinterval(old)


def run_threads(workers):
    """Runs each callable on its own thread, started together; re-raises the first failure."""
    errors = []
    barrier = threading.Barrier(len(workers))

    def run(work):
        try:
            barrier.wait()
            work()
        except BaseException as error:  # noqa: BLE001 - reported below, on the test's thread
            errors.append(error)

    threads = [threading.Thread(target=run, args=(work,)) for work in workers]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    if errors:
        raise errors[0]


def pile(ball, bodies=60):
    """`bodies` balls dropped in a loose column onto a ground plane: a world that moves."""
    world = sphys.World(ground_plane=0.0)
    rng = np.random.default_rng(5)
    for i in range(bodies):
        x, z = rng.uniform(-0.3, 0.3, 2)
        world.add_body(ball, position=(x, 0.15 + 0.22 * i, z))
    return world


def robot_spheres(count):
    """`count` configurations of 4 spheres in and around the pile, for check_configurations."""
    rng = np.random.default_rng(7)
    centres = rng.uniform((-0.6, 0.0, -0.6), (0.6, 3.0, 0.6), (count, 4, 3))
    return np.concatenate([centres, np.full((count, 4, 1), 0.05)], axis=2).astype(np.float32)


@pytest.mark.parametrize("threads", THREAD_COUNTS)
def test_steps_from_many_threads_make_the_run_of_as_many_steps_on_one(ball, threads):
    # Every call steps once: whichever thread makes it, the world ends as after that many steps.
    per_thread = 30
    for _ in range(ROUNDS):
        alone = pile(ball)
        for _ in range(per_thread * threads):
            alone.step(DT)
        world = pile(ball)

        def stepper():
            for _ in range(per_thread):
                world.step(DT)

        run_threads([stepper] * threads)
        np.testing.assert_array_equal(world.poses(), alone.poses())
        np.testing.assert_array_equal(world.velocities(), alone.velocities())


@pytest.mark.parametrize("threads", THREAD_COUNTS)
def test_readers_beside_a_stepper_leave_the_run_as_it_runs_alone(ball, threads):
    steps = 120
    for _ in range(ROUNDS):
        alone = pile(ball)
        for _ in range(steps):
            alone.step(DT)
        world = pile(ball)
        done = threading.Event()
        spheres = robot_spheres(64)
        origins = np.tile([[0.0, 5.0, 0.0]], (32, 1)).astype(np.float32)
        directions = np.tile([[0.0, -1.0, 0.0]], (32, 1)).astype(np.float32)
        calls = [0] * threads

        def stepper():
            try:
                for _ in range(steps):
                    world.step(DT)
            finally:
                done.set()

        def reader(k):
            def work():
                while not done.is_set() or calls[k] < 50:
                    poses = world.poses()
                    assert poses.shape == (60, 7) and np.isfinite(poses).all()
                    assert np.isfinite(world.velocities()).all()
                    assert len(world) == 60 and len(world.body_ids()) == 60
                    world.contacts()
                    assert world.stats.bodies == 60 or world.stats.bodies == 0
                    query = world.query()
                    hits = query.cast_rays(origins, directions)
                    assert (hits["body"] >= 0).all()
                    check = world.check_configurations(spheres, [0, 0, 1, 1])
                    assert check["free"].shape == (64,)
                    calls[k] += 1
            return work

        run_threads([stepper] + [reader(k) for k in range(1, threads)])
        np.testing.assert_array_equal(world.poses(), alone.poses())
        np.testing.assert_array_equal(world.velocities(), alone.velocities())
        assert sum(calls) >= 50 * (threads - 1)


@pytest.mark.parametrize("threads", THREAD_COUNTS)
def test_adding_and_removing_beside_a_stepper_ends_as_the_same_calls_one_by_one(ball, threads):
    # No gravity and bodies at rest far apart: a step moves nothing, so every order of the calls
    # ends with the same bodies at the same places, while each call still changes what the step
    # walks (the broad phase, the pair cache, the sleep islands).
    per_thread = 300
    for _ in range(ROUNDS):
        world = sphys.World(gravity=(0.0, 0.0, 0.0))
        changers = threads - 1
        # Each changer starts with its own bodies to remove, on its own row of the grid.
        own = [[world.add_body(ball, position=(k * 1.0, 0.0, j * 1.0)) for j in range(per_thread)]
               for k in range(changers)]
        done = threading.Event()
        steps = [0]

        def stepper():
            while not done.is_set() or steps[0] < 20:
                world.step(DT)
                steps[0] += 1

        finished = []

        def changer(k):
            def work():
                try:
                    for j, body in enumerate(own[k]):
                        world.add_body(ball, position=(k * 1.0, 2.0, j * 1.0))
                        if j % 3 == 0:
                            world.set_velocity(body, (0.0, 0.0, 0.0))
                        if j % 3 == 1:
                            world.set_pair_material(body, own[k][j + 1], friction=0.3,
                                                    restitution=0.1)
                        world.remove_body(body)
                        assert not world.alive(body)
                finally:
                    finished.append(k)
                    if len(finished) == changers:
                        done.set()
            return work

        run_threads([stepper] + [changer(k) for k in range(changers)])
        expected = sorted((k * 1.0, 2.0, j * 1.0) for k in range(changers)
                          for j in range(per_thread))
        got = sorted(tuple(float(v) for v in row[:3]) for row in world.poses())
        assert got == expected
        assert len(world) == changers * per_thread
        assert steps[0] >= 20


@pytest.mark.parametrize("threads", THREAD_COUNTS)
def test_one_query_answers_many_threads_while_its_world_steps_and_loses_bodies(ball, threads):
    for _ in range(ROUNDS):
        world = pile(ball)
        for _ in range(30):
            world.step(DT)
        query = world.query()
        rng = np.random.default_rng(3)
        origins = np.concatenate([rng.uniform(-0.4, 0.4, (200, 1)), np.full((200, 1), 20.0),
                                  rng.uniform(-0.4, 0.4, (200, 1))], axis=1).astype(np.float32)
        directions = np.tile([[0.0, -1.0, 0.0]], (200, 1)).astype(np.float32)
        expected = query.cast_rays(origins, directions)
        spheres = robot_spheres(100)
        expected_free = query.check_configurations(spheres, [0, 0, 1, 1])["free"]
        ids = world.body_ids()
        fresh = world.query()
        done = threading.Event()

        def changer():
            try:
                for k, body in enumerate(ids[::2]):
                    world.step(DT)
                    world.remove_body(body)
                    if k % 4 == 0:
                        fresh.refresh()
            finally:
                done.set()

        def asker():
            while not done.is_set():
                hits = query.cast_rays(origins, directions)
                np.testing.assert_array_equal(hits["body"], expected["body"])
                np.testing.assert_array_equal(hits["distance"], expected["distance"])
                np.testing.assert_array_equal(
                    query.check_configurations(spheres, [0, 0, 1, 1])["free"], expected_free)
                hit = query.cast_ray(origins[0], directions[0])
                assert (hit["body"].index if hit else -1) == expected["body"][0]
                # The refreshed query answers from one whole snapshot: every hit is a body it
                # holds, which is one of the world's bodies at some moment.
                assert (fresh.cast_rays(origins, directions)["body"] < 60).all()

        run_threads([changer] + [asker for _ in range(threads - 1)])
        assert len(world) == 30


def test_a_simulation_and_its_world_take_turns(ball):
    for _ in range(ROUNDS):
        alone = sphys.Simulation("stacks:1x3", depth=2)
        alone.step(40)
        sim = sphys.Simulation("stacks:1x3", depth=2)
        done = threading.Event()

        def stepper():
            try:
                for _ in range(40):
                    sim.step()
            finally:
                done.set()

        def reader():
            while not done.is_set():
                assert np.isfinite(sim.poses()).all()
                assert np.isfinite(sim.world.poses()).all()
                sim.summary()
                assert 0 <= sim.frame <= 40

        run_threads([stepper, reader, reader])
        np.testing.assert_array_equal(sim.poses(), alone.poses())
        assert sim.frame == 40


def test_ctrl_c_stops_a_call_waiting_for_its_turn(isolated):
    # The stepper holds the world's turn for a long run of steps; the main thread's call waits
    # for it and is interrupted while the stepper still steps.
    isolated("""
import _thread, os, signal, threading, time
import sphys
# Ctrl-C raises KeyboardInterrupt, as in a terminal, even where the interpreter was started with
# SIGINT ignored (a job a shell sent to the background): interrupt_main() does nothing then.
signal.signal(signal.SIGINT, signal.default_int_handler)
world = sphys.World(ground_plane=0.0)
tree = sphys.SphereTree.from_arrays([[0.0, 0.0, 0.0]], [0.1], [-1], 8)
for i in range(50):
    world.add_body(tree, position=(0.0, 0.1 + 0.25 * i, 0.0))
stepper = threading.Thread(target=lambda: world.step(steps=10**8), daemon=True)
stepper.start()
threading.Timer(0.5, _thread.interrupt_main).start()
try:
    while True:
        world.poses()
except KeyboardInterrupt:
    assert stepper.is_alive()
    print("interrupted while waiting")
    os._exit(0)
""", timeout=60)
