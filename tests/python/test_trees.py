"""Sphere-trees: construction by every method, structure and array views, coverage checked by
brute force with numpy, .sph files, quality measures and errors."""

import math
import textwrap

import numpy as np
import pytest

import sphys

METHODS = ["octree", "grid", "spawn", "hubbard", "merge", "burst", "expand", "combined", "tight"]
QUICK = dict(surface_samples=2000, volume_samples=5000, boundary_samples=50)


def levels_of(tree):
    """[(centres, radii)] per level, as float64 copies."""
    return [tuple(np.array(a, dtype=np.float64) for a in tree.level(k)) for k in range(tree.depth)]


def surface_samples(mesh, count, seed=7):
    """`count` area-weighted uniform random points on the mesh's triangles."""
    rng = np.random.default_rng(seed)
    v = np.asarray(mesh.vertices)[np.asarray(mesh.triangles, dtype=np.int64)]  # (M, 3, 3)
    areas = 0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1)
    chosen = rng.choice(len(v), size=count, p=areas / areas.sum())
    u, w = rng.random(count), rng.random(count)
    flip = u + w > 1.0
    u[flip], w[flip] = 1.0 - u[flip], 1.0 - w[flip]
    t = v[chosen]
    return t[:, 0] + u[:, None] * (t[:, 1] - t[:, 0]) + w[:, None] * (t[:, 2] - t[:, 0])


def uncovered(points, centres, radii):
    """The points inside no sphere. The spheres are float32: a point on a sphere may lie outside
    it by the rounding of its centre and radius, a few float32 ulps of the coordinates."""
    distances = np.linalg.norm(points[:, None, :] - centres[None, :, :], axis=2)
    slack = 4 * np.finfo(np.float32).eps * (np.abs(centres).max() + radii.max())
    return points[~(distances <= radii[None, :] + slack).any(axis=1)]


@pytest.fixture(scope="module")
def ball_mesh():
    return sphys.icosphere(1.0, 2)


@pytest.fixture(scope="module", params=["octree", "combined"])
def deep_tree(request, ball_mesh):
    return request.param, sphys.build_tree(ball_mesh, method=request.param, branching=8, depth=3)


def test_build_methods():
    assert sphys.build_methods() == METHODS


def check_structure(tree, depth, branching):
    assert tree.depth == depth
    assert tree.branching == branching
    levels = levels_of(tree)
    assert sum(len(r) for _, r in levels) == len(tree)
    parents = tree.parents
    assert parents.shape == (len(tree),) and parents.dtype == np.int32
    assert parents[0] == -1
    start = 0
    for k, (centres, radii) in enumerate(levels):
        n = len(radii)
        assert centres.shape == (n, 3) and radii.shape == (n,)
        assert 1 <= n <= branching**k
        assert (radii > 0).all()
        if k > 0:
            # Breadth-first: a level's parents are the nodes of the level above, in order.
            p = parents[start:start + n]
            previous = len(levels[k - 1][1])
            assert ((p >= start - previous) & (p < start)).all()
            assert (np.diff(p) >= 0).all()
            assert np.bincount(p - (start - previous)).max() <= branching
        start += n
    c0, r0 = tree.level(0)
    assert c0.shape == (1, 3) and r0.shape == (1,)  # level 0 is the root alone


@pytest.mark.parametrize("method", METHODS)
def test_every_method_covers_the_mesh(method):
    mesh = sphys.icosphere(1.0, 1)
    tree = sphys.build_tree(mesh, method=method, branching=8, depth=2)
    check_structure(tree, 2, 8)
    vertices = np.asarray(mesh.vertices)
    for centres, radii in levels_of(tree):
        assert len(uncovered(vertices, centres, radii)) == 0
    assert [q.coverage for q in sphys.tree_quality(tree, mesh, **QUICK)] == [1.0, 1.0]


def test_deep_tree_structure_and_coverage(deep_tree, ball_mesh):
    method, tree = deep_tree
    check_structure(tree, 3, 8)
    assert "depth 3" in repr(tree)
    # Every level covers every vertex and the triangles between (build_tree certifies the
    # triangles, not only sample points): brute force over the vertices and random surface points.
    points = np.vstack([ball_mesh.vertices, surface_samples(ball_mesh, 3000)])
    for k, (centres, radii) in enumerate(levels_of(tree)):
        assert len(uncovered(points, centres, radii)) == 0, f"{method} level {k}"
    quality = sphys.tree_quality(tree, ball_mesh, **QUICK)
    assert len(quality) == 3
    for k, q in enumerate(quality):
        assert q.level == k
        assert q.spheres == len(tree.level(k)[1])
        assert q.coverage == 1.0
        assert q.worst_gap == 0.0
        assert q.outside_volume > 0.0  # spheres around a convex solid always stick out
        assert q.worst_protrusion > 0.0


def test_a_bad_method_is_refused_with_the_valid_names(ball_mesh):
    with pytest.raises(sphys.Error) as caught:
        sphys.build_tree(ball_mesh, method="bogus")
    # tools::parse_method's message, listing build_methods() in order.
    assert str(caught.value) == (
        "unknown sphere-tree method 'bogus' (valid: " + ", ".join(sphys.build_methods()) + ")")


def test_bad_method_message_matches_the_command_line(ball_mesh, cli, tmp_path):
    obj = tmp_path / "ball.obj"
    write_obj(obj, ball_mesh)
    done = cli("build-tree", obj, "--method", "bogus", "-o", tmp_path / "x.sph",
               env={"SPHYS_CACHE_DIR": str(tmp_path / "cache")})
    assert done.returncode == 2
    with pytest.raises(sphys.Error) as caught:
        sphys.build_tree(ball_mesh, method="bogus")
    assert done.stderr.strip() == "sphys: error: " + str(caught.value)


def write_obj(path, mesh):
    with open(path, "w") as out:
        for x, y, z in mesh.vertices:
            out.write(f"v {x!r} {y!r} {z!r}\n")
        for a, b, c in mesh.triangles:
            out.write(f"f {a + 1} {b + 1} {c + 1}\n")


@pytest.mark.parametrize("method, branching", [("octree", 8), ("combined", 4)])
def test_build_tree_equals_the_command_lines(method, branching, ball_mesh, cli, tmp_path):
    # The same mesh, options and seed give the same tree, bit for bit, from either front end.
    obj = tmp_path / "ball.obj"
    write_obj(obj, ball_mesh)
    sph = tmp_path / "ball.sph"
    done = cli("build-tree", obj, "--method", method, "--depth", 2, "--branching", branching,
               "--seed", 5, "-o", sph, "--no-cache", env={"SPHYS_CACHE_DIR": str(tmp_path / "cache")})
    assert done.returncode == 0, done.stderr
    ours = sphys.build_tree(sphys.load_mesh(str(obj)), method=method, depth=2, branching=branching,
                            seed=5)
    assert ours.branching == branching
    assert sphys.read_sph(str(sph)) == ours


def test_bad_build_options_raise(ball_mesh):
    with pytest.raises(sphys.Error):
        sphys.build_tree(ball_mesh, branching=9)
    with pytest.raises(sphys.Error, match="the octree method splits every cell in 8"):
        sphys.build_tree(ball_mesh, method="octree", branching=4)
    with pytest.raises(sphys.Error):
        sphys.build_tree(ball_mesh, depth=0)


def test_level_views_are_read_only_and_not_copies(deep_tree):
    _, tree = deep_tree
    centres, radii = tree.level(1)
    assert centres.dtype == np.float32 and radii.dtype == np.float32
    for array in (centres, radii):
        assert not array.flags.writeable
        with pytest.raises(ValueError):
            array[0] = 0
        assert array.base is not None
    again = tree.level(1)
    assert np.shares_memory(centres, again[0]) and np.shares_memory(radii, again[1])
    with pytest.raises(sphys.Error, match="level must be 0 to 2, got 3"):
        tree.level(3)
    with pytest.raises(sphys.Error, match="level must be 0 to 2, got -1"):
        tree.level(-1)


def test_whole_tree_views(isolated):
    # SphereTree.centres and .radii: every node, breadth-first, as read-only float32 views equal
    # to the levels side by side. In a fresh interpreter: a broken view may crash it.
    isolated(textwrap.dedent("""
        import numpy as np, sphys
        tree = sphys.build_tree(sphys.icosphere(1.0, 1), method="octree", depth=3)
        centres, radii = tree.centres, tree.radii
        assert isinstance(centres, np.ndarray), type(centres)
        assert isinstance(radii, np.ndarray), type(radii)
        assert centres.shape == (len(tree), 3) and centres.dtype == np.float32
        assert radii.shape == (len(tree),) and radii.dtype == np.float32
        assert not centres.flags.writeable and not radii.flags.writeable
        assert np.shares_memory(centres, tree.centres)
        levels = [tree.level(k) for k in range(tree.depth)]
        assert np.array_equal(centres, np.concatenate([c for c, _ in levels]))
        assert np.array_equal(radii, np.concatenate([r for _, r in levels]))
    """))


def test_truncated(deep_tree):
    _, tree = deep_tree
    cut = tree.truncated(2)
    assert cut.depth == 2
    assert len(cut) == 1 + len(tree.level(1)[1])
    for k in range(2):
        np.testing.assert_array_equal(cut.level(k)[0], tree.level(k)[0])
        np.testing.assert_array_equal(cut.level(k)[1], tree.level(k)[1])
    assert cut != tree
    assert tree.truncated(3) == tree


def test_sph_round_trip(deep_tree, tmp_path):
    _, tree = deep_tree
    path = tmp_path / "tree.sph"
    sphys.write_sph(str(path), tree)
    back = sphys.read_sph(str(path))
    assert back == tree
    np.testing.assert_array_equal(back.parents, tree.parents)
    # shift is added to every centre (the toolkit's centres are relative to the box centre).
    shift = (0.25, -1.0, 2.0)
    moved = sphys.read_sph(str(path), shift=shift)
    for (c, r), (c0, r0) in zip(levels_of(moved), levels_of(tree)):
        np.testing.assert_allclose(c, c0 + shift, atol=1e-6)
        np.testing.assert_array_equal(r, r0)


def test_read_sph_errors(tmp_path):
    missing = tmp_path / "missing.sph"
    with pytest.raises(sphys.Error, match="missing.sph"):
        sphys.read_sph(str(missing))
    bad = tmp_path / "bad.sph"
    bad.write_text("this is not a sphere-tree\n")
    with pytest.raises(sphys.Error, match="bad.sph:1: the header must be two integers"):
        sphys.read_sph(str(bad))


# ---------------------------------------------------------------------------------------------
# Trees from arrays


def test_from_arrays_three_nodes():
    centres = [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [-0.5, 0.0, 0.0]]
    radii = [1.0, 0.5, 0.5]
    tree = sphys.SphereTree.from_arrays(centres, radii, [-1, 0, 0], 2)
    assert (tree.depth, tree.branching, len(tree)) == (2, 2, 3)
    np.testing.assert_array_equal(tree.parents, [-1, 0, 0])
    np.testing.assert_array_equal(tree.level(0)[0], [centres[0]])
    np.testing.assert_array_equal(tree.level(1)[0], centres[1:])
    np.testing.assert_array_equal(tree.level(1)[1], radii[1:])
    same = sphys.SphereTree.from_arrays(np.array(centres), np.array(radii), np.array([-1, 0, 0]), 2)
    assert same == tree
    other = sphys.SphereTree.from_arrays(centres, [1.0, 0.5, 0.25], [-1, 0, 0], 2)
    assert other != tree


@pytest.mark.parametrize("centres, radii, parents, branching, message", [
    ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [1, 1, 1], [-1, 0, 5], 8,
     r"parents\[2\] must be -1 or a node index, got 5"),
    ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [1, 1, 1], [-1, 0, -2], 8,
     r"parents\[2\] must be -1 or a node index, got -2"),
    ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [1, 1, 1], [0, 0, 0], 8,
     "sphere-tree node 0: the root must have no parent"),
    ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [1, 1, 1], [-1, 2, 0], 8,
     "sphere-tree node 1: parent 2 does not come before it"),
    ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [1, 0, 1], [-1, 0, 0], 8,
     "sphere-tree node 1: radius must be positive and finite"),
    ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [1, 1, 1], [-1, 0, 0], 9,
     r"branching factor 9 is outside 2..8"),
    ([[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]], [1, 1, 1, 1], [-1, 0, 0, 0], 2,
     "sphere-tree node 0: has more than 2 children"),
    ([[0, 0, 0], [1, 0, 0]], [1, 1, 1], [-1, 0], 8, r"radii must be an array of shape \(N,\)"),
    ([[0, 0, 0], [1, 0, 0]], [1, 1], [-1, 0, 0], 8, r"parents must be an array of shape \(N,\)"),
    ([[0, 0], [1, 0]], [1, 1], [-1, 0], 8, r"centres must be an array of shape \(N, 3\)"),
    (np.zeros((0, 3)), np.zeros(0), np.zeros(0, dtype=int), 8, "at least a root sphere"),
])
def test_from_arrays_errors(centres, radii, parents, branching, message):
    with pytest.raises(sphys.Error, match=message):
        sphys.SphereTree.from_arrays(centres, radii, parents, branching)


# ---------------------------------------------------------------------------------------------
# Quality of a sphere set


def test_sphere_quality_of_one_sphere_around_a_unit_cube():
    r = 0.9  # more than the half diagonal sqrt(3)/2 = 0.866: the cube is inside
    cube = sphys.box((1.0, 1.0, 1.0))
    n = 20000
    q = sphys.sphere_quality([[0.0, 0.0, 0.0]], [r], cube, surface_samples=2000, volume_samples=n,
                             boundary_samples=400, seed=11)
    assert q.spheres == 1
    assert q.coverage == 1.0
    assert q.worst_gap == 0.0
    # Outside volume in cube volumes (1 m³): the ball less the cube. Monte Carlo over the
    # sphere's bounding box (2r)³ with p the fraction of it counted: standard error
    # (2r)³ · sqrt(p (1 - p) / n) (tree_quality.h); 5 of them.
    ball = 4.0 / 3.0 * math.pi * r**3
    expected = ball - 1.0
    p = expected / (2 * r) ** 3
    sigma = (2 * r) ** 3 * math.sqrt(p * (1 - p) / n)
    assert abs(q.outside_volume - expected) < 5 * sigma
    # Farthest from the cube: where an axis meets the sphere, r - 1/2 beyond a face, in bounding-
    # box diagonals (sqrt 3). The lattice of 400 points can only miss it by r (1 - cos √(4π/400)).
    diagonal = math.sqrt(3.0)
    worst = (r - 0.5) / diagonal
    missed = r * (1 - math.cos(math.sqrt(4 * math.pi / 400))) / diagonal
    assert worst - missed - 1e-9 <= q.worst_protrusion <= worst + 1e-9


def test_sphere_quality_of_a_small_sphere_finds_gaps():
    cube = sphys.box((1.0, 1.0, 1.0))
    q = sphys.sphere_quality(np.zeros((1, 3)), np.array([0.5]), cube, **QUICK)
    # Radius 1/2 touches the faces' centres only: almost no surface is inside, and the corners
    # are sqrt(3)/2 - 1/2 away from the sphere, in diagonals.
    assert q.coverage < 0.05
    assert q.worst_gap == pytest.approx((math.sqrt(3) / 2 - 0.5) / math.sqrt(3), rel=0.05)
    assert "coverage" in repr(q)


def test_sphere_quality_errors():
    cube = sphys.box((1.0, 1.0, 1.0))
    with pytest.raises(sphys.Error):
        sphys.sphere_quality(np.zeros((0, 3)), np.zeros(0), cube, **QUICK)
    with pytest.raises(sphys.Error):
        sphys.sphere_quality([[0, 0, 0]], [1.0], cube, surface_samples=0)
