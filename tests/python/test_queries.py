"""Queries from Python: ray casts, overlaps, distances and batched configuration checks against
numpy loops over every leaf sphere, bad input as sphys.Error naming the argument, and the batched
check running with the GIL released."""

import threading
import time

import numpy as np
import pytest

import sphys
from test_world import rotation_matrix


def random_tree(rng, leaves):
    """A depth-2 tree: a root of radius 0.4 m and `leaves` leaves around it."""
    centres = np.vstack([[0.0, 0.0, 0.0], rng.uniform(-0.25, 0.25, (leaves, 3))])
    radii = np.concatenate([[0.4], rng.uniform(0.05, 0.15, leaves)])
    return sphys.SphereTree.from_arrays(centres, radii, [-1] + [0] * leaves, 8)


@pytest.fixture(scope="module")
def scene():
    """30 bodies at random poses (no gravity) and their leaf spheres in the world frame."""
    rng = np.random.default_rng(3)
    world = sphys.World(gravity=(0, 0, 0))
    leaves = []  # (slot, centre, radius)
    for _ in range(30):
        tree = random_tree(rng, int(rng.integers(2, 9)))
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        position = rng.uniform(-2, 2, 3)
        body = world.add_body(tree, position=position, orientation=q)
        rotation = rotation_matrix(q)
        for centre, radius in zip(tree.centres[1:], tree.radii[1:]):
            leaves.append((body.index, rotation @ centre + position, float(radius)))
    return world, leaves


def test_nearest_ray_hit_is_the_nearest_leaf_sphere(scene):
    world, leaves = scene
    query = world.query()
    rng = np.random.default_rng(5)
    hits = 0
    for _ in range(300):
        origin = rng.uniform(-4, 4, 3)
        # Aimed at a body's centre, give or take: most rays hit something.
        direction = leaves[int(rng.integers(len(leaves)))][1] + rng.uniform(-0.3, 0.3, 3) - origin
        unit = direction / np.linalg.norm(direction)
        best = None
        for slot, centre, radius in leaves:
            m = origin - centre
            b = m @ unit
            disc = b * b - (m @ m - radius * radius)
            if m @ m <= radius * radius:
                t = 0.0
            elif b >= 0 or disc < 0:
                continue
            else:
                t = -b - np.sqrt(disc)
            if best is None or t < best[1]:
                best = (slot, t)
        hit = query.cast_ray(origin, direction)
        assert (hit is None) == (best is None)
        if hit is not None:
            hits += 1
            assert hit["distance"] == pytest.approx(best[1], abs=1e-5)
            assert hit["body"].index == best[0]
    assert hits > 100

    # Many rays at once give the same answers, on two threads.
    origins = rng.uniform(-4, 4, (200, 3)).astype(np.float32)
    directions = -origins + rng.uniform(-1, 1, (200, 3)).astype(np.float32)
    many = query.cast_rays(origins, directions, threads=2)
    for i in range(200):
        one = query.cast_ray(origins[i], directions[i])
        assert many["body"][i] == (-1 if one is None else one["body"].index)
        if one is not None:
            assert many["distance"][i] == pytest.approx(one["distance"], abs=1e-6)


def test_overlaps_and_distances_match_loops(scene):
    world, leaves = scene
    query = world.query()
    rng = np.random.default_rng(7)
    for _ in range(50):
        centre = rng.uniform(-2, 2, 3)
        radius = float(rng.uniform(0, 0.8))
        expected = sorted({s for s, c, r in leaves if np.linalg.norm(c - centre) <= r + radius})
        assert [b.index for b in query.overlap_sphere(centre, radius)] == expected
        low, high = centre - 0.5, centre + 0.3
        expected = sorted({s for s, c, r in leaves
                           if np.linalg.norm(np.clip(c, low, high) - c) <= r})
        assert [b.index for b in query.overlap_aabb(low, high)] == expected
    ids = world.body_ids()
    for a in range(0, 30, 3):
        for b in range(a + 1, 30, 4):
            gap = min(np.linalg.norm(ca - cb) - ra - rb
                      for sa, ca, ra in leaves if sa == a for sb, cb, rb in leaves if sb == b)
            result = query.distance(ids[a], ids[b])
            assert result["exact"]
            assert result["distance"] == pytest.approx(gap, abs=1e-5)
    point = np.array([0.1, 0.2, 0.3])
    gap = min(np.linalg.norm(c - point) - r for s, c, r in leaves if s == 0)
    assert query.distance(ids[0], point)["distance"] == pytest.approx(gap, abs=1e-5)
    lower = query.distance(ids[0], ids[1], max_sphere_tests=1)
    assert not lower["exact"]
    assert lower["distance"] <= query.distance(ids[0], ids[1])["distance"] + 1e-6


def test_filters_leave_bodies_out(scene):
    world, leaves = scene
    query = world.query()
    everything = [b.index for b in query.overlap_sphere((0, 0, 0), 100)]
    assert everything == list(range(30))
    skipped = query.overlap_sphere((0, 0, 0), 100, filter=sphys.QueryFilter(skip=world.body_ids()[:5]))
    assert [b.index for b in skipped] == list(range(5, 30))
    categories = [2 if i % 2 else 1 for i in range(30)]
    odd = query.overlap_sphere((0, 0, 0), 100,
                               filter=sphys.QueryFilter(categories=categories, mask=2))
    assert [b.index for b in odd] == list(range(1, 30, 2))


def oracle_check(leaves, spheres):
    """free per configuration and the first colliding sphere, by loops."""
    free = []
    first = []
    for configuration in spheres:
        hit = -1
        for i, (x, y, z, r) in enumerate(configuration):
            if any(np.linalg.norm(np.array([x, y, z]) - c) <= r + rr for _, c, rr in leaves):
                hit = i
                break
        free.append(hit < 0)
        first.append(hit)
    return np.array(free), np.array(first)


def test_check_configurations_matches_loops_on_threads(scene):
    world, leaves = scene
    rng = np.random.default_rng(11)
    n, s = 300, 6
    base = rng.uniform(-2, 2, (n, 1, 3))
    spheres = np.concatenate([base + rng.uniform(-0.4, 0.4, (n, s, 3)),
                              rng.uniform(0.05, 0.15, (n, s, 1))], axis=2).astype(np.float32)
    links = np.array([0, 0, 1, 1, 2, 2], dtype=np.int32)
    free, first = oracle_check(leaves, spheres)
    for threads in (1, 2):
        result = world.check_configurations(spheres, links, threads=threads)
        assert result["free"].dtype == np.bool_ and result["free"].shape == (n,)
        np.testing.assert_array_equal(result["free"], free)
        np.testing.assert_array_equal(result["sphere"], first)
    assert 0.1 * n < free.sum() < 0.9 * n
    # Self-collision: two spheres of links 0 and 2 on top of each other, far from every body.
    lonely = np.array([[[50, 50, 50, 0.1], [60, 0, 0, 0.1], [50, 50, 50.05, 0.1]]],
                      dtype=np.float32)
    assert world.check_configurations(lonely, [0, 1, 2])["free"][0]
    result = world.check_configurations(lonely, [0, 1, 2], self_collision=True)
    assert not result["free"][0] and result["sphere"][0] == 0 and result["other_sphere"][0] == 2
    allowed = world.check_configurations(lonely, [0, 1, 2], self_collision=True,
                                         allowed_pairs=[(2, 0)])
    assert allowed["free"][0]


def test_a_deeper_level_frees_what_only_the_worlds_leaves_touch():
    """A 3-level tree in a world that uses 2: one leaf of radius 1 m about the centre, and below
    it one sphere of 0.1 m at (0, 0.9, 0). A small sphere at the leaf's bottom touches the world's
    leaf but not the level below; one at its top touches both."""
    world = sphys.World(gravity=(0, 0, 0), collision={"tree_depth": 2})
    tree = sphys.SphereTree.from_arrays([[0, 0, 0], [0, 0, 0], [0, 0.9, 0]], [1.0, 1.0, 0.1],
                                        [-1, 0, 1], 8)
    world.add_body(tree, position=(0, 0, 0), static=True)
    spheres = np.array([[[0, -1.0, 0, 0.01]], [[0, 1.0, 0, 0.01]], [[3, 0, 0, 0.01]]],
                       dtype=np.float32)
    np.testing.assert_array_equal(world.check_configurations(spheres, [0])["free"],
                                  [False, False, True])
    deeper = world.query().check_configurations(spheres, [0], tree_depth=3)
    np.testing.assert_array_equal(deeper["free"], [True, False, True])
    with pytest.raises(sphys.Error, match="tree_depth: 1 levels is shallower than the world's 2"):
        world.check_configurations(spheres, [0], tree_depth=1)


def test_check_configurations_releases_the_gil(scene, side_by_side):
    # With a switch interval of 1000 s a thread that holds the GIL keeps it until it releases
    # it, so were the GIL held during a check, two threads' checks could never overlap in time.
    world, _ = scene
    rng = np.random.default_rng(13)
    spheres = np.concatenate([rng.uniform(-3, 3, (100000, 4, 3)),
                              np.full((100000, 4, 1), 0.05)], axis=2).astype(np.float32)
    intervals = [[], []]
    barrier = threading.Barrier(2)

    def work(k):
        barrier.wait()
        for _ in range(3):
            start = time.perf_counter()
            world.check_configurations(spheres, [0, 0, 1, 1])
            intervals[k].append((start, time.perf_counter()))

    side_by_side(work)
    overlap = any(a0 < b1 and b0 < a1 for a0, a1 in intervals[0] for b0, b1 in intervals[1])
    assert overlap


def test_bad_input_raises_errors_naming_the_argument(scene):
    world, _ = scene
    query = world.query()
    with pytest.raises(sphys.Error, match="ray.origin"):
        query.cast_ray((np.nan, 0, 0), (1, 0, 0))
    with pytest.raises(sphys.Error, match="ray.direction: zero length"):
        query.cast_ray((0, 0, 0), (0, 0, 0))
    with pytest.raises(sphys.Error, match="ray.direction"):
        query.cast_rays(np.zeros((2, 3)), np.array([[1, 0, 0], [0, 0, 0]]))
    with pytest.raises(sphys.Error, match="directions must be an \\(N, 3\\) array"):
        query.cast_rays(np.zeros((2, 3)), np.zeros((3, 3)))
    with pytest.raises(sphys.Error, match="spheres must be an \\(N, S, 4\\) array"):
        world.check_configurations(np.zeros((5, 3)), [0, 0, 0])
    with pytest.raises(sphys.Error, match="links must be 3 link indices"):
        world.check_configurations(np.zeros((5, 3, 4)), [0, 0])
    other = sphys.World()
    stranger = other.add_body(sphys.SphereTree.from_arrays([[0, 0, 0]], [1], [-1], 8))
    other.add_body(sphys.SphereTree.from_arrays([[0, 0, 0]], [1], [-1], 8))
    small = sphys.World()
    small.add_body(sphys.SphereTree.from_arrays([[0, 0, 0]], [1], [-1], 8))
    with pytest.raises(sphys.Error, match="body_b: no body with id 1"):
        small.query().distance(small.body_ids()[0], other.body_ids()[1])
    with pytest.raises(sphys.Error, match="filter.skip"):
        small.query().overlap_sphere((0, 0, 0), 1,
                                     filter=sphys.QueryFilter(skip=[other.body_ids()[1]]))
    assert stranger.index == 0


# ---------------------------------------------------------------------------------------------
# Checks from joint values: a one-link arm from its URDF and spheres, swung into a ball


SWING_URDF = """<?xml version="1.0"?>
<robot name="swing">
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="arm"><collision><origin xyz="0.5 0 0"/><geometry><box size="1 0.1 0.1"/></geometry>
  </collision></link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 1 0"/><limit lower="-3.14" upper="3.14" effort="1" velocity="1"/></joint>
</robot>
"""

# One sphere of 0.1 m at the arm's tip, one at the base: ((x, y, z), radius). unit: m
SWING_SPHERES = {"base": [((0.0, 0.0, 0.0), 0.05)], "arm": [((1.0, 0.0, 0.0), 0.1)]}


@pytest.fixture
def swing(tmp_path, sphere_tree):
    """The arm's model, and a world with a ball of 0.1 m at (0, 0, -1): the tip meets it when the
    arm has turned about y by asin(0.98) to pi - asin(0.98)."""
    model = sphys.robot_model_from_text(SWING_URDF, SWING_SPHERES, tmp_path, "swing")
    world = sphys.World(gravity=(0, 0, 0))
    world.add_body(sphere_tree(0.1), position=(0, 0, -1), static=True)
    return model, world


def test_joint_values_and_motions_from_a_urdf(swing):
    model, world = swing
    assert model.joints == ["turn"] and model.links == ["base", "arm"] and model.spheres == 2
    np.testing.assert_allclose(model.limits, [[-3.14, 3.14]])
    touch = np.arcsin(0.98)
    angles = np.array([0.0, touch - 0.01, touch + 0.01, np.pi / 2, np.pi - touch - 0.01, -1.0])
    got = world.check_joint_values(model, angles[:, None], threads=2)
    np.testing.assert_array_equal(got["free"], [True, True, False, False, False, True])
    assert list(got["sphere"][2:5]) == [1, 1, 1] and got["body"][2] == 0
    # The same from a query, and motions: through the ball, beside it, and from inside it.
    query = world.query()
    np.testing.assert_array_equal(query.check_joint_values(model, angles[:, None])["free"],
                                  got["free"])
    motions = world.check_motions(model, [[0.0], [0.0], [np.pi / 2]], [[3.0], [1.0], [0.0]], 0.01)
    np.testing.assert_array_equal(motions["free"], [False, True, False])
    assert motions["first_collision"][1] == -1 and motions["last_free"][1] == 1.0
    assert motions["first_collision"][2] == 0 and motions["last_free"][2] == 0.0
    # The first colliding state of the first motion is within a step past the first touch.
    step = 3.0 / (motions["states"][0] - 1)
    first = motions["first_collision"][0] * step
    assert touch <= first + 1e-5 < touch + step + 1e-5
    assert motions["last_free"][0] == pytest.approx((motions["first_collision"][0] - 1) * step / 3.0)


def test_bad_joint_values_name_the_joint(swing):
    model, world = swing
    with pytest.raises(sphys.Error, match="joint 'turn'.*outside its limits"):
        world.check_joint_values(model, [[4.0]])
    with pytest.raises(sphys.Error, match=r"values must be an \(N, 1\) array"):
        world.check_joint_values(model, [[0.0, 1.0]])
    with pytest.raises(sphys.Error, match="resolution"):
        world.check_motions(model, [[0.0]], [[1.0]], 0.0)
    # The world uses every level of its trees: none is deeper.
    with pytest.raises(sphys.Error, match="tree_depth: 3 levels is shallower"):
        world.check_joint_values(model, [[0.0]], tree_depth=3)
    with pytest.raises(sphys.Error, match="tree_depth: 3 levels is shallower"):
        world.check_motions(model, [[0.0]], [[1.0]], 0.1, tree_depth=3)
    with pytest.raises(sphys.Error, match="no_such.urdf"):
        sphys.load_robot_model("no_such.urdf", "no_such.yml")
