"""Meshes: construction from arrays, loading, checking, decimation, normalisation and mass
properties, against closed forms and numpy's own integrals of the same polyhedra."""

import math

import numpy as np
import pytest

import sphys


def polyhedron_volume(vertices, triangles):
    """The signed volume a closed, outward-oriented triangle mesh bounds (divergence theorem: the
    tetrahedra from the origin to every triangle)."""
    v = np.asarray(vertices, dtype=np.float64)
    t = np.asarray(triangles, dtype=np.int64)
    return np.linalg.det(v[t]).sum() / 6.0


def write_obj(path, vertices, triangles):
    with open(path, "w") as out:
        for x, y, z in vertices:
            out.write(f"v {x!r} {y!r} {z!r}\n")
        for a, b, c in triangles:
            out.write(f"f {a + 1} {b + 1} {c + 1}\n")


@pytest.fixture(scope="module")
def bunny_500():
    return sphys.load_model("bunny", triangles=500)


# ---------------------------------------------------------------------------------------------
# Simple solids and mass properties


def test_box_mass_properties_are_exact():
    a, b, c = 2.0, 3.0, 4.0
    density = 500.0
    box = sphys.box((a, b, c))
    assert box.vertices.shape == (8, 3) and box.triangles.shape == (12, 3)
    props = sphys.mass_properties(box, density=density)
    assert props.method == "polyhedral"
    assert props.volume == pytest.approx(a * b * c, rel=1e-12)
    m = a * b * c * density
    assert props.mass == pytest.approx(m, rel=1e-12)
    np.testing.assert_allclose(props.center_of_mass, 0.0, atol=1e-12)
    # A solid box about its centre: I_xx = m/12 (b² + c²), and the other two by symmetry.
    expected = np.diag([m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b)])
    assert props.inertia.shape == (3, 3)
    np.testing.assert_allclose(props.inertia, expected, rtol=1e-9, atol=1e-9 * m)
    # Principal moments ascending: about z (a, b the smallest sides), then y, then x.
    np.testing.assert_allclose(props.principal_moments, np.sort(np.diag(expected)), rtol=1e-9)
    axes = props.principal_axes
    np.testing.assert_allclose(np.abs(axes), [[0, 0, 1], [0, 1, 0], [1, 0, 0]], atol=1e-9)
    assert np.linalg.det(axes) == pytest.approx(1.0, abs=1e-9)  # right-handed
    lo, hi = box.bounds
    np.testing.assert_array_equal(lo, [-1.0, -1.5, -2.0])
    np.testing.assert_array_equal(hi, [1.0, 1.5, 2.0])


def test_box_by_winding_numbers_matches_the_polyhedral_figures():
    # The winding-number integration is exact for boxes aligned with its grid (mass_properties.h).
    props = sphys.mass_properties(sphys.box((2, 3, 4)), force_winding_number=True, columns=40)
    assert props.method == "winding_number"
    assert props.volume == pytest.approx(24.0, rel=1e-9)
    np.testing.assert_allclose(props.center_of_mass, 0.0, atol=1e-9)


def test_default_density_is_water():
    assert sphys.mass_properties(sphys.box((1, 1, 1))).mass == pytest.approx(1000.0, rel=1e-12)


def test_bad_mass_property_options_raise():
    with pytest.raises(sphys.Error, match="density"):
        sphys.mass_properties(sphys.box((1, 1, 1)), density=-1.0)
    with pytest.raises(sphys.Error):
        sphys.mass_properties(sphys.box((1, 1, 1)), force_winding_number=True, columns=0)


@pytest.mark.parametrize("subdivisions", [0, 2, 3])
def test_icosphere_volume(subdivisions):
    r = 1.5
    sphere = sphys.icosphere(r, subdivisions)
    assert len(sphere.triangles) == 20 * 4**subdivisions
    assert len(sphere.vertices) == 10 * 4**subdivisions + 2  # Euler: V = F/2 + 2
    # Every vertex on the sphere.
    np.testing.assert_allclose(np.linalg.norm(sphere.vertices, axis=1), r, rtol=1e-12)
    props = sphys.mass_properties(sphere)
    assert props.method == "polyhedral"
    # Exactly the volume of its own polyhedron (numpy's integral of the same triangles) ...
    assert props.volume == pytest.approx(polyhedron_volume(sphere.vertices, sphere.triangles), rel=1e-12)
    # ... which is inscribed in the sphere: strictly smaller, and closer with each subdivision
    # (the icosahedron itself holds 60.5% of the sphere, 3 subdivisions within 2%).
    ball = 4.0 / 3.0 * math.pi * r**3
    assert props.volume < ball
    allowed = {0: 0.40, 2: 0.05, 3: 0.02}[subdivisions]
    assert props.volume > (1.0 - allowed) * ball
    np.testing.assert_allclose(props.center_of_mass, 0.0, atol=1e-12)


def test_torus_volume_is_pappus_on_its_polygons():
    R, r, rings, sides = 1.0, 0.25, 32, 16
    torus = sphys.torus(R, r, rings, sides)
    assert len(torus.triangles) == 2 * rings * sides
    assert sphys.check_mesh(torus).watertight
    props = sphys.mass_properties(torus)
    assert props.method == "polyhedral"
    # The mesh is `rings` planar slabs between regular `sides`-gons inscribed in the tube's circle:
    # each slab holds sin(2π/rings) · area(polygon) · R (the polygon's centroid is at R), so the
    # whole is the smooth torus's 2π²Rr² with 2π replaced by rings·sin(2π/rings) and πr² by
    # sides/2 · r² sin(2π/sides).
    polygon_area = sides / 2.0 * r * r * math.sin(2 * math.pi / sides)
    exact = rings * math.sin(2 * math.pi / rings) * polygon_area * R
    assert props.volume == pytest.approx(exact, rel=1e-9)
    smooth = 2 * math.pi**2 * R * r * r
    assert 0.96 * smooth < props.volume < smooth
    np.testing.assert_allclose(props.center_of_mass, 0.0, atol=1e-12)


def test_bad_solids_raise():
    with pytest.raises(sphys.Error, match="side lengths"):
        sphys.box((1, 0, 1))
    with pytest.raises(sphys.Error, match="radius"):
        sphys.icosphere(-1.0)
    with pytest.raises(sphys.Error, match="minor < major"):
        sphys.torus(0.5, 1.0)


# ---------------------------------------------------------------------------------------------
# Mesh from arrays


def test_mesh_from_arrays_round_trip_and_views():
    box = sphys.box((1, 2, 3))
    vertices = np.array(box.vertices)
    triangles = np.array(box.triangles)
    mesh = sphys.Mesh(vertices, triangles, "mine")
    assert mesh.name == "mine"
    assert "mine" in repr(mesh)
    assert mesh.vertices.dtype == np.float64 and mesh.vertices.shape == (8, 3)
    assert mesh.triangles.dtype == np.uint32 and mesh.triangles.shape == (12, 3)
    np.testing.assert_array_equal(mesh.vertices, vertices)
    np.testing.assert_array_equal(mesh.triangles, triangles)
    # Lists and other integer types are converted.
    again = sphys.Mesh(vertices.tolist(), triangles.astype(np.int16))
    np.testing.assert_array_equal(again.vertices, vertices)
    np.testing.assert_array_equal(again.triangles, triangles)
    assert sphys.mass_properties(mesh).volume == pytest.approx(6.0, rel=1e-12)


def test_mesh_arrays_are_read_only_views():
    mesh = sphys.box((1, 2, 3))
    for array in (mesh.vertices, mesh.triangles):
        assert not array.flags.writeable
        with pytest.raises(ValueError):
            array[0, 0] = 7
        assert array.base is not None  # a view of the mesh's memory ...
    # ... the same memory at every read: no copy is made.
    assert np.shares_memory(mesh.vertices, mesh.vertices)
    assert np.shares_memory(mesh.triangles, mesh.triangles)
    assert mesh.vertices.ctypes.data == mesh.vertices.ctypes.data
    # A view keeps its mesh alive.
    view = sphys.box((1, 2, 3)).vertices
    np.testing.assert_array_equal(np.abs(view), np.tile([0.5, 1.0, 1.5], (8, 1)))


def test_sphys_error_is_a_value_error():
    assert issubclass(sphys.Error, ValueError)


def test_bad_mesh_arrays_raise():
    good_v = np.zeros((3, 3))
    good_v[1, 0] = 1.0
    good_v[2, 1] = 1.0
    with pytest.raises(sphys.Error, match=r"vertices must be an array of shape \(N, 3\)"):
        sphys.Mesh(np.zeros((3, 2)), [[0, 1, 2]])
    with pytest.raises(sphys.Error, match=r"triangles must be an array of shape \(M, 3\)"):
        sphys.Mesh(good_v, [0, 1, 2])
    with pytest.raises(sphys.Error, match="triangle 0 refers to vertex 3 of 3"):
        sphys.Mesh(good_v, [[0, 1, 3]])
    with pytest.raises(sphys.Error, match="refers to vertex -1"):
        sphys.Mesh(good_v, [[0, 1, -1]])
    with pytest.raises(sphys.Error, match="no triangles"):
        sphys.Mesh(good_v, np.zeros((0, 3), dtype=np.int64))
    bad_v = good_v.copy()
    bad_v[1, 2] = np.nan
    with pytest.raises(sphys.Error, match="vertex 1 has a non-finite coordinate"):
        sphys.Mesh(bad_v, [[0, 1, 2]])
    # And a ValueError, for code that catches those.
    with pytest.raises(ValueError):
        sphys.Mesh(good_v, [[0, 1, 3]])


# ---------------------------------------------------------------------------------------------
# Files and the bunny


def test_load_mesh_reads_an_obj(tmp_path):
    box = sphys.box((2, 3, 4))
    path = tmp_path / "box.obj"
    write_obj(path, box.vertices, box.triangles)
    mesh = sphys.load_mesh(str(path))
    assert mesh.vertices.shape == (8, 3) and mesh.triangles.shape == (12, 3)
    assert sphys.check_mesh(mesh).watertight
    assert sphys.mass_properties(mesh).volume == pytest.approx(24.0, rel=1e-12)


def test_load_mesh_of_a_missing_file_names_it(tmp_path):
    path = tmp_path / "nowhere" / "missing.obj"
    with pytest.raises(sphys.Error) as caught:
        sphys.load_mesh(str(path))
    assert str(path) in str(caught.value)


def test_load_model_bunny_default_budget():
    bunny = sphys.load_model("bunny")
    # Decimated to the default budget of 2000 triangles: at most that, and not far below.
    assert 1800 <= len(bunny.triangles) <= 2000
    assert sphys.check_mesh(bunny).watertight


def test_load_model_bunny_with_budget(bunny_500):
    assert 400 <= len(bunny_500.triangles) <= 500
    assert sphys.check_mesh(bunny_500).watertight


def test_load_model_of_a_file(tmp_path):
    sphere = sphys.icosphere(1.0, 2)
    path = tmp_path / "ball.obj"
    write_obj(path, sphere.vertices, sphere.triangles)
    whole = sphys.load_model(str(path))  # a file is decimated only when asked
    assert len(whole.triangles) == 320
    assert len(sphys.load_model(str(path), triangles=100).triangles) <= 100


# ---------------------------------------------------------------------------------------------
# Checking, decimating, normalising


def test_check_mesh_of_a_box():
    report = sphys.check_mesh(sphys.box((1, 2, 3)))
    assert report.watertight
    assert (report.triangles, report.vertices) == (12, 8)
    assert report.boundary_edges == 0
    assert report.non_manifold_edges == 0
    assert report.misoriented_edges == 0
    assert report.degenerate_triangles == 0
    assert report.non_finite_vertices == 0
    assert report.unused_vertices == 0
    assert "watertight" in repr(report)


def test_check_mesh_finds_a_hole():
    box = sphys.box((2, 3, 4))
    open_box = sphys.Mesh(box.vertices, box.triangles[1:])
    report = sphys.check_mesh(open_box)
    assert report.boundary_edges == 3  # the missing triangle's edges
    assert report.triangles == 11
    assert not report.watertight
    # A mesh with a hole gets winding-number mass properties; the hole is planar, capped exactly,
    # and the box is aligned with the columns: the volume stays 24.
    props = sphys.mass_properties(open_box)
    assert props.method == "winding_number"
    assert props.volume == pytest.approx(24.0, rel=1e-6)


def test_check_mesh_finds_misoriented_and_unused():
    box = sphys.box((1, 1, 1))
    triangles = np.array(box.triangles)
    triangles[0] = triangles[0][::-1]  # one triangle turned inside out
    vertices = np.vstack([box.vertices, [[5.0, 5.0, 5.0]]])  # one vertex no triangle uses
    report = sphys.check_mesh(sphys.Mesh(vertices, triangles))
    assert report.misoriented_edges == 3
    assert report.unused_vertices == 1
    assert report.boundary_edges == 0
    assert not report.watertight


def test_decimate():
    sphere = sphys.icosphere(1.0, 3)
    assert len(sphere.triangles) == 1280
    coarse = sphys.decimate(sphere, 300)
    assert 0 < len(coarse.triangles) <= 300
    assert sphys.check_mesh(coarse).watertight  # a watertight mesh stays watertight
    # Still a ball of radius 1 or so.
    volume = sphys.mass_properties(coarse).volume
    assert volume == pytest.approx(4.0 / 3.0 * math.pi, rel=0.1)
    # A budget at or above the count changes nothing.
    same = sphys.decimate(sphere, 5000)
    np.testing.assert_array_equal(same.vertices, sphere.vertices)
    np.testing.assert_array_equal(same.triangles, sphere.triangles)


def test_normalize_box():
    box = sphys.box((2, 3, 4))
    shifted = sphys.Mesh(box.vertices + [5.0, 6.0, 7.0], box.triangles)
    normal = sphys.normalize(shifted, 2.0)
    # Longest side 4 becomes 2: scale 1/2; the centre of mass (5, 6, 7)/2 moves to the origin.
    assert normal.scale == pytest.approx(0.5, rel=1e-12)
    np.testing.assert_allclose(normal.translation, [-2.5, -3.0, -3.5], atol=1e-12)
    np.testing.assert_allclose(normal.mesh.vertices, normal.scale * shifted.vertices + normal.translation,
                               atol=1e-12)


def test_normalize_bunny(bunny_500):
    size = 0.7
    normal = sphys.normalize(bunny_500, size, density=300.0)
    lo, hi = normal.mesh.bounds
    assert (hi - lo).max() == pytest.approx(size, rel=1e-12)
    props = sphys.mass_properties(normal.mesh)
    np.testing.assert_allclose(props.center_of_mass, 0.0, atol=1e-9 * size)
    np.testing.assert_allclose(normal.mesh.vertices,
                               normal.scale * bunny_500.vertices + normal.translation, atol=1e-12)
    with pytest.raises(sphys.Error):
        sphys.normalize(bunny_500, -1.0)
