"""Scenes, simulations and recordings: scene files and dicts round trip, presets, Simulation
against `sphys simulate` bit for bit (poses and summary), recordings written and read back, and
the errors, each naming the file or the JSON path."""

import gc
import json
import math
import os
import re
import textwrap

import numpy as np
import pytest

import sphys

# Figures of the summary that are wall-clock times (or made from them): the rest is determined by
# the scene and must agree exactly between runs.
TIMING_KEYS = {"wall_s", "steps_per_s", "step_ms", "time_share_percent", "serial_share_percent"}
# Keys only the command line's summary has: where it wrote its files.
CLI_ONLY_KEYS = {"csv", "recording"}

# A scene that sets something of every kind: settings off their defaults, a nested solver and
# sleep, the exact ground plane, defaults, every orientation form, a pair material.
SCENE = {
    "format": "sphys-scene",
    "version": 1,
    "time_step": 0.01,
    "frames": 7,
    "gravity": [0.0, -9.5, 0.25],
    "response": "plausible",
    "collision_passes": 2,
    "solver": {"contact_hertz": 20, "soft_substeps": 9},
    "sleep": {"time": 0.75},
    "ground": {"type": "plane", "height": -0.5, "friction": 0.6},
    "defaults": {"triangles": 500, "sphere_tree": {"depth": 2}, "density": 800},
    "bodies": [
        {"position": [0.0, 1.0, 0.0]},
        {"position": [0.2, 2.5, 0.0], "orientation": {"yaw_degrees": 30}},
        {"position": [-0.1, 4.0, 0.1], "orientation": {"axis": [1, 0, 1], "angle_degrees": 45},
         "linear_velocity": [0, -1, 0], "angular_velocity": [0, 3.14, 0], "mass": 12.5,
         "static": False},
    ],
    "pair_materials": [{"bodies": [1, 2], "friction": 0.9}],
}


def summary_figures(summary):
    """The deterministic figures of a summary."""
    return {k: v for k, v in summary.items() if k not in TIMING_KEYS | CLI_ONLY_KEYS}


def unit_quaternions(rng, shape):
    q = rng.normal(size=(*shape, 4))
    return (q / np.linalg.norm(q, axis=-1, keepdims=True)).astype(np.float32)


# ---------------------------------------------------------------------------------------------
# Scenes


def test_scene_round_trips_through_json_and_dicts():
    scene = sphys.Scene.from_dict(SCENE)
    assert scene.name == "scene.json"
    assert len(scene) == 3 and scene.frames == 7 and scene.time_step == 0.01
    assert repr(scene) == "<sphys.Scene 'scene.json': 3 bodies, 7 frames>"
    d = scene.to_dict()
    # Every key written out, the given values kept.
    assert d["format"] == "sphys-scene" and d["version"] == 1
    assert d["gravity"] == [0.0, -9.5, 0.25] and d["collision_passes"] == 2
    assert d["solver"]["contact_hertz"] == 20 and d["solver"]["soft_substeps"] == 9
    assert d["solver"]["rolling_resistance"] == 0.01  # a default, written out
    assert d["sleep"] == {"enabled": True, "speed": 0.05, "time": 0.75}
    assert d["ground"]["type"] == "plane" and d["ground"]["height"] == -0.5
    assert [b["position"] for b in d["bodies"]] == [b["position"] for b in SCENE["bodies"]]
    assert [b["triangles"] for b in d["bodies"]] == [500] * 3  # from the defaults
    assert [b["sphere_tree"]["depth"] for b in d["bodies"]] == [2] * 3
    assert d["bodies"][2]["mass"] == 12.5 and d["bodies"][0]["mass"] is None
    # yaw 30° is a turn about +y: (w, x, y, z) = (cos 15°, 0, sin 15°, 0).
    o = d["bodies"][1]["orientation"]
    assert [o["w"], o["x"], o["y"], o["z"]] == pytest.approx(
        [math.cos(math.radians(15)), 0, math.sin(math.radians(15)), 0], abs=1e-7)
    assert d["pair_materials"][0]["bodies"] == [1, 2]
    assert d["pair_materials"][0]["friction"] == 0.9

    text = scene.to_json()
    assert json.loads(text) == d
    again = sphys.Scene.from_json(text)
    assert again.to_json() == text  # every number bit for bit
    from_dict = sphys.Scene.from_dict(d, "elsewhere/drop.json")
    assert from_dict.to_json() == text
    assert from_dict.name == "drop.json"  # the file's name
    # An edited dict makes an edited scene.
    d["frames"] = 11
    d["bodies"].append({**d["bodies"][0], "position": [3.0, 1.0, 0.0]})
    edited = sphys.Scene.from_dict(d)
    assert edited.frames == 11 and len(edited) == 4


def test_scene_frames_time_step_name():
    scene = sphys.load_scene("stacks:1x2")
    assert scene.frames == 880 and scene.time_step == 1.0 / 60.0
    scene.frames = 12
    assert scene.frames == 12 and scene.to_dict()["frames"] == 12
    with pytest.raises(sphys.Error, match="frames"):
        scene.frames = 0
    assert scene.frames == 12
    with pytest.raises(AttributeError):
        scene.time_step = 0.1
    with pytest.raises(AttributeError):
        scene.name = "other"


def test_scene_settings():
    scene = sphys.Scene.from_dict(SCENE)
    s = scene.settings
    assert s["solver.contact_hertz"] == 20 and s["solver.soft_substeps"] == 9
    assert s["sleep.time"] == 0.75 and s["collision_passes"] == 2
    assert s["ground_friction"] == 0.6 and s["ground_restitution"] == 0.3
    np.testing.assert_array_equal(np.float32(s["gravity"]), np.float32([0.0, -9.5, 0.25]))
    assert set(s) == {row["field"] for row in sphys.settings_table()}

    # Nested and dotted, as World() takes them; the scene file follows.
    scene.set_settings({"solver": {"contact_hertz": 45}, "sleep.time": 1.5,
                        "ground_friction": 0.25, "collision_passes": 3})
    s = scene.settings
    assert s["solver.contact_hertz"] == 45 and s["sleep.time"] == 1.5
    assert s["ground_friction"] == 0.25 and s["collision_passes"] == 3
    assert s["solver.soft_substeps"] == 9  # untouched
    d = scene.to_dict()
    assert d["solver"]["contact_hertz"] == 45 and d["sleep"]["time"] == 1.5
    assert d["ground"]["friction"] == 0.25 and d["collision_passes"] == 3

    # A refused change names the setting and changes nothing.
    for bad, name in [({"bogus": 1}, "bogus"), ({"collision_passes": 0}, "collision_passes"),
                      ({"solver": {"method": "soft_step"}}, r"solver\.method was removed")]:
        with pytest.raises(sphys.Error, match=name):
            scene.set_settings(bad)
    assert scene.settings == s

    # The simulation's world runs with the scene's settings (plus the plausibility figures).
    sim = sphys.Simulation(scene)
    world_settings = sim.world.settings
    assert world_settings["plausibility_figures"] is True
    assert {k: v for k, v in world_settings.items() if k != "plausibility_figures"} == {
        k: v for k, v in s.items() if k != "plausibility_figures"}
    assert sim.world.ground_plane == -0.5


def test_presets_and_load_scene():
    text = sphys.presets()
    assert "stacks:SxN" in text and "stacks:4x50" in text
    scene = sphys.load_scene("stacks:2x3")
    assert scene.name == "stacks:2x3" and len(scene) == 6
    bodies = scene.to_dict()["bodies"]
    # 2 stacks of 3: two columns of x, each with 3 heights rising.
    xs = sorted({b["position"][0] for b in bodies})
    assert len(xs) == 2
    for x in xs:
        heights = [b["position"][1] for b in bodies if b["position"][0] == x]
        assert len(heights) == 3 and heights == sorted(heights) and len(set(heights)) == 3
    # The seed draws the yaw angles only; 2008 is the default.
    assert sphys.load_scene("stacks:2x3", seed=2008).to_json() == scene.to_json()
    other = sphys.load_scene("stacks:2x3", seed=5).to_dict()["bodies"]
    assert [b["position"] for b in other] == [b["position"] for b in bodies]
    assert [b["orientation"] for b in other] != [b["orientation"] for b in bodies]
    for b in other:  # a yaw: a turn about y only
        o = b["orientation"]
        assert o["x"] == 0 and o["z"] == 0 and o["w"] ** 2 + o["y"] ** 2 == pytest.approx(1)

    with pytest.raises(sphys.Error, match="stacks:0x1"):
        sphys.load_scene("stacks:0x1")
    with pytest.raises(sphys.Error, match="stacks:abc"):
        sphys.load_scene("stacks:abc")
    with pytest.raises(sphys.Error, match="seed"):
        sphys.load_scene("some.json", seed=3)


def test_load_scene_file_resolves_meshes_beside_it(tmp_path):
    folder = tmp_path / "scenes"
    folder.mkdir()
    scene = {"format": "sphys-scene", "version": 1,
             "bodies": [{"mesh": "cube.obj", "position": [0, 1, 0]}]}
    path = folder / "drop.json"
    path.write_text(json.dumps(scene))
    with pytest.raises(sphys.Error, match=r"/bodies/0/mesh: no such file: .*scenes/cube\.obj"):
        sphys.load_scene(str(path))
    (folder / "cube.obj").write_text(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
        "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n")
    loaded = sphys.load_scene(str(path))
    assert loaded.name == "drop.json" and len(loaded) == 1
    # from_json resolves against the folder of the name it is given.
    assert sphys.Scene.from_json(path.read_text(), str(path)).to_json() == loaded.to_json()
    with pytest.raises(sphys.Error, match="cube.obj"):
        sphys.Scene.from_json(path.read_text(), str(tmp_path / "drop.json"))
    with pytest.raises(sphys.Error, match="missing.json: no such file"):
        sphys.load_scene(str(folder / "missing.json"))


@pytest.mark.parametrize("edit, where", [
    (lambda d: d["bodies"][1].update(density=-1), "/bodies/1/density"),
    (lambda d: d["solver"].update(bogus=1), "/solver/bogus"),
    (lambda d: d.update(version=2), "/version"),
    (lambda d: d["ground"].update(type="lava"), "/ground/type"),
    (lambda d: d["bodies"][0].update(position=[0, 1]), "/bodies/0/position"),
    (lambda d: d.update(time_step=0), "/time_step"),
    (lambda d: d["pair_materials"][0].update(bodies=[1, 7]), "/pair_materials/0/bodies"),
])
def test_bad_scene_raises_naming_the_json_path(edit, where):
    d = json.loads(json.dumps(SCENE))
    edit(d)
    with pytest.raises(sphys.Error, match=f"^bad.json: {where}"):
        sphys.Scene.from_dict(d, "bad.json")
    with pytest.raises(sphys.Error, match=f"^bad.json: {where}"):
        sphys.Scene.from_json(json.dumps(d), "bad.json")


def test_scene_text_that_is_not_json_names_line_and_column():
    with pytest.raises(sphys.Error, match=r"^x\.json:2: column \d+: not valid JSON"):
        sphys.Scene.from_json('{"format": "sphys-scene",\n "version": 1, bodies: []}', "x.json")


# ---------------------------------------------------------------------------------------------
# Simulation against `sphys simulate`


def simulate_frame_by_frame(scene, frames, **options):
    """The poses of a Simulation at frame 0 and after each of `frames` steps: (F + 1, B, 7)."""
    sim = sphys.Simulation(scene, **options)
    poses = [sim.poses()]
    for _ in range(frames):
        sim.step()
        poses.append(sim.poses())
    return sim, np.stack(poses)


@pytest.mark.parametrize("settings", [(), ("solver.soft_substeps=6", "sleep.time=0.25")])
def test_simulation_equals_the_command_line_bit_for_bit(simulate_cli, settings):
    frames = 30
    summary, recording_path = simulate_cli("stacks:1x3", frames, *settings)
    recording = sphys.read_recording(str(recording_path))
    scene = sphys.load_scene("stacks:1x3")
    scene.frames = frames
    scene.set_settings(dict(s.split("=") for s in settings))

    sim, poses = simulate_frame_by_frame(scene, frames)
    # The command line records frame 0 (the start) and every frame after it.
    assert recording.frame_count == frames + 1 and recording.body_count == 3
    assert recording.time_step == scene.time_step
    np.testing.assert_array_equal(recording.poses, poses)
    assert recording.scene().to_json() == scene.to_json()
    assert summary_figures(sim.summary()) == summary_figures(summary)
    assert summary["frames"] == frames and summary["bodies"] == 3
    assert sim.frame == frames and sim.time == pytest.approx(frames * scene.time_step)

    # run() steps to the scene's last frame and returns the same summary.
    runner = sphys.Simulation(scene)
    runner.step(4)
    ran = runner.run()
    assert runner.frame == frames
    assert summary_figures(ran) == summary_figures(summary)
    assert set(ran) == set(summary) - CLI_ONLY_KEYS
    np.testing.assert_array_equal(runner.poses(), recording.poses[-1])
    assert summary_figures(runner.run()) == summary_figures(summary)  # nothing more to run
    assert runner.frame == frames


def test_simulation_depth_equals_the_command_lines(cli, tmp_path):
    frames = 40  # the lower bunny meets the plane at about frame 20
    done = cli("simulate", "stacks:1x2", "--frames", frames, "--depth", 2, "--out", tmp_path,
               "--json")
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)
    assert summary["sphere_trees"] == "combined, branching 8, depth 2"
    scene = sphys.load_scene("stacks:1x2")
    scene.frames = frames
    sim, poses = simulate_frame_by_frame(scene, frames, depth=2)
    recording = sphys.read_recording(str(tmp_path / "recording.sphysrec"))
    np.testing.assert_array_equal(recording.poses, poses)
    assert summary_figures(sim.summary()) == summary_figures(summary)
    # The depth changes the simulation: the default depth 3 ends elsewhere.
    _, deeper = simulate_frame_by_frame(scene, frames)
    assert not np.array_equal(deeper, poses)


def test_simulation_threads_and_cache(tmp_path, monkeypatch):
    # Threads change nothing, bit for bit (the world's threads setting); trees built without the
    # cache are the cached ones, and cache=False neither reads nor writes it.
    cache = tmp_path / "cache"
    monkeypatch.setenv("SPHYS_CACHE_DIR", str(cache))
    scene = sphys.load_scene("stacks:1x3")
    frames = 25
    uncached, base = simulate_frame_by_frame(scene, frames, depth=2, cache=False)
    assert not cache.exists() or not any(cache.iterdir())
    cached, again = simulate_frame_by_frame(scene, frames, depth=2)
    assert cache.is_dir() and any(cache.iterdir())
    threaded, parallel = simulate_frame_by_frame(scene, frames, depth=2, threads=2)
    assert threaded.world.settings["threads"] == 2 and cached.world.settings["threads"] == 1
    np.testing.assert_array_equal(again, base)
    np.testing.assert_array_equal(parallel, base)
    assert uncached.world.stats.contacts > 0  # the bunnies touch, so threads had work to share


def test_simulation_members():
    scene = sphys.load_scene("stacks:1x2")
    scene.frames = 5
    sim = sphys.Simulation(scene)
    assert sim.frame == 0 and sim.time == 0.0
    ids = sim.body_ids
    assert len(ids) == 2 and all(isinstance(i, sphys.BodyId) for i in ids)
    # The world holds the scene's bodies; the preset's exact plane is no body.
    assert len(sim.world) == 2 and all(sim.world.alive(i) for i in ids)
    np.testing.assert_array_equal(sim.poses(), sim.world.poses(ids))
    positions = [b["position"] for b in scene.to_dict()["bodies"]]
    np.testing.assert_allclose(sim.poses()[:, :3], positions, atol=1e-6)
    assert sim.scene.to_json() == scene.to_json()
    stats = sim.step(3)
    assert isinstance(stats, sphys.StepStats) and stats.bodies == 2
    assert sim.frame == 3 and sim.time == pytest.approx(3 * scene.time_step)
    assert sim.summary()["frames"] == 3
    with pytest.raises(sphys.Error, match="frames"):
        sim.step(0)
    assert sim.frame == 3
    assert sim.poses().dtype == np.float32 and sim.poses().shape == (2, 7)
    with pytest.raises(sphys.Error, match="depth"):
        sphys.Simulation(scene, depth=0)
    with pytest.raises(sphys.Error, match="threads"):
        sphys.Simulation(scene, threads=5000)
    with pytest.raises(sphys.Error, match="nonexistent.json: no such file"):
        sphys.Simulation("nonexistent.json")


def test_simulation_takes_a_dict_or_a_path_and_refuses_the_rest(tmp_path):
    # A dict in the scene-file format and a pathlib.Path are scenes as a Scene and a str are.
    scene = sphys.load_scene("stacks:1x2")
    scene.frames = 3
    from_dict = sphys.Simulation(scene.to_dict())
    file = tmp_path / "two.json"
    file.write_text(scene.to_json())
    from_path = sphys.Simulation(file)
    from_scene = sphys.Simulation(scene)
    for sim in (from_dict, from_path, from_scene):
        sim.run()
    assert np.array_equal(from_dict.poses(), from_scene.poses())
    assert np.array_equal(from_path.poses(), from_scene.poses())
    # A dict that is not a scene is refused with the JSON path; a number is no scene at all.
    with pytest.raises(sphys.Error, match="bodies"):
        sphys.Simulation({"format": "sphys-scene", "version": 1})
    with pytest.raises(sphys.Error, match="scene must be a Scene, a dict .* got 42"):
        sphys.Simulation(42)
    with pytest.raises(sphys.Error, match="missing.json"):
        sphys.Simulation(tmp_path / "missing.json")


def test_simulation_going_non_finite_raises_with_the_diagnostic():
    # No scene a file may hold overflows (gravity and speeds are bounded), but the world's own
    # API takes any finite velocity: 3e38 m/s carries the body past float's largest value in
    # the first frame, and the run stops there with the command line's diagnostic.
    scene = sphys.Scene.from_dict({
        "format": "sphys-scene", "version": 1, "frames": 200, "time_step": 1.0,
        "ground": {"type": "none"},
        "bodies": [{"position": [0, 1, 0], "sphere_tree": {"depth": 2}}],
    })
    sim = sphys.Simulation(scene)
    sim.world.set_velocity(sim.body_ids[0], linear=(0, -3e38, 0))
    with pytest.raises(sphys.Error, match=r"non-finite: body 0 \(/bodies/0\) at frame 1:"):
        sim.step(200)
    assert sim.frame == 1 and sim.world.stopped


# ---------------------------------------------------------------------------------------------
# Recordings


def test_recording_members(simulate_cli):
    frames = 30
    _, path = simulate_cli("stacks:1x3", frames)
    recording = sphys.read_recording(str(path))
    poses = recording.poses
    assert poses.shape == (frames + 1, 3, 7) and poses.dtype == np.float32
    positions, orientations = recording.positions, recording.orientations
    assert positions.shape == (frames + 1, 3, 3) and positions.dtype == np.float32
    assert orientations.shape == (frames + 1, 3, 4) and orientations.dtype == np.float32
    np.testing.assert_array_equal(positions, poses[..., :3])
    np.testing.assert_array_equal(orientations, poses[..., 3:])
    np.testing.assert_allclose(np.linalg.norm(orientations, axis=-1), 1.0, atol=1e-6)
    for view in (positions, orientations):
        assert not view.flags.writeable
        with pytest.raises(ValueError):
            view[0, 0, 0] = 1.0
    poses[0, 0, 0] = 123.0  # a copy: writable, and the recording keeps its own
    assert recording.poses[0, 0, 0] != 123.0
    # The metadata is the scene, and scene() reads it.
    scene = recording.scene()
    assert isinstance(scene, sphys.Scene)
    assert json.loads(recording.metadata) == scene.to_dict()
    assert len(scene) == 3 and scene.frames == frames
    # Bodies fall: the first frame is the scene's start, and the top bunny is lower at the end.
    start = [b["position"] for b in scene.to_dict()["bodies"]]
    np.testing.assert_allclose(positions[0], start, atol=1e-6)
    assert positions[-1, 2, 1] < positions[0, 2, 1]


def test_recording_views_outlive_the_recording(simulate_cli, isolated):
    _, path = simulate_cli("stacks:1x3", 30)
    isolated(textwrap.dedent(f"""
        import gc
        import numpy as np
        import sphys
        expected = sphys.read_recording({str(path)!r}).poses.copy()
        positions = sphys.read_recording({str(path)!r}).positions
        orientations = sphys.read_recording({str(path)!r}).orientations
        gc.collect()
        junk = [np.ones(10000) for _ in range(100)]  # reuse freed memory, if any was freed
        assert np.array_equal(positions, expected[..., :3])
        assert np.array_equal(orientations, expected[..., 3:])
    """))


def test_recording_writer_round_trip(tmp_path):
    rng = np.random.default_rng(3)
    frames, bodies = 5, 4
    poses = np.empty((frames, bodies, 7), dtype=np.float32)
    poses[..., :3] = rng.normal(scale=100.0, size=(frames, bodies, 3))
    poses[..., 3:] = unit_quaternions(rng, (frames, bodies))
    metadata = sphys.Scene.from_dict(SCENE).to_json()
    path = tmp_path / "poses.sphysrec"
    writer = sphys.RecordingWriter(str(path), bodies, 1.0 / 30.0, metadata)
    for frame in poses:
        writer.add_frame(frame)
    assert not path.exists()  # only finish() puts the file in place
    writer.finish()
    # The header, the metadata, the joint count (no joints), the frames.
    assert path.stat().st_size == 32 + len(metadata.encode()) + 4 + 28 * bodies * frames
    recording = sphys.read_recording(str(path))
    assert recording.body_count == bodies and recording.frame_count == frames
    assert recording.time_step == 1.0 / 30.0
    assert recording.metadata == metadata
    np.testing.assert_array_equal(recording.poses, poses)  # the same bits
    assert recording.scene().to_json() == metadata
    # A list of rows and float64 arrays are poses too.
    listed = tmp_path / "listed.sphysrec"
    with sphys.RecordingWriter(str(listed), 2, 0.5) as w:
        w.add_frame([[1, 2, 3, 0, 0, 0, 1], [4, 5, 6, 0, 1, 0, 0]])
        w.add_frame(np.array([[1, 2, 3, 0, 0, 0, 1], [4, 5, 6, 0, 1, 0, 0]], dtype=np.float64))
    back = sphys.read_recording(str(listed))
    assert back.metadata == "" and back.frame_count == 2
    np.testing.assert_array_equal(back.poses[1], [[1, 2, 3, 0, 0, 0, 1], [4, 5, 6, 0, 1, 0, 0]])


def test_recording_writer_writes_a_simulation(tmp_path, simulate_cli):
    # Simulation.poses() frames written with the scene's JSON make the command line's recording.
    frames = 30
    _, cli_path = simulate_cli("stacks:1x3", frames)
    scene = sphys.load_scene("stacks:1x3")
    scene.frames = frames
    sim = sphys.Simulation(scene)
    path = tmp_path / "mine.sphysrec"
    with sphys.RecordingWriter(str(path), len(scene), scene.time_step, scene.to_json()) as writer:
        writer.add_frame(sim.poses())
        for _ in range(frames):
            sim.step()
            writer.add_frame(sim.poses())
    assert path.read_bytes() == cli_path.read_bytes()


def test_recording_writer_is_whole_or_nothing(tmp_path):
    pose = np.zeros((2, 7), dtype=np.float32)
    pose[:, 6] = 1.0

    # An exception in the with block: no file, and the temporary goes with the writer.
    path = tmp_path / "failed.sphysrec"
    with pytest.raises(KeyError):
        with sphys.RecordingWriter(str(path), 2, 0.01) as writer:
            writer.add_frame(pose)
            raise KeyError("stop")
    assert not path.exists()
    del writer
    gc.collect()
    assert os.listdir(tmp_path) == []

    # A writer dropped without finish(): no file, no temporary.
    dropped = sphys.RecordingWriter(str(tmp_path / "dropped.sphysrec"), 2, 0.01)
    dropped.add_frame(pose)
    assert len(os.listdir(tmp_path)) == 1  # the temporary, beside the target
    del dropped
    gc.collect()
    assert os.listdir(tmp_path) == []

    # An existing file stays as it was until finish() replaces it.
    target = tmp_path / "kept.sphysrec"
    with sphys.RecordingWriter(str(target), 2, 0.01, "old") as w:
        w.add_frame(pose)
    replacing = sphys.RecordingWriter(str(target), 2, 0.02, "new")
    replacing.add_frame(pose)
    replacing.add_frame(pose)
    assert sphys.read_recording(str(target)).metadata == "old"
    replacing.finish()
    replaced = sphys.read_recording(str(target))
    assert replaced.metadata == "new" and replaced.frame_count == 2
    assert os.listdir(tmp_path) == ["kept.sphysrec"]


def test_recording_writer_errors(tmp_path):
    path = tmp_path / "bad.sphysrec"
    name = "bad.sphysrec"
    writer = sphys.RecordingWriter(str(path), 2, 0.01)
    pose = np.zeros((2, 7), dtype=np.float32)
    pose[:, 6] = 1.0
    with pytest.raises(sphys.Error, match=r"shape \(B, 7\)"):
        writer.add_frame(np.zeros((2, 6)))
    with pytest.raises(sphys.Error, match=r"shape \(B, 7\)"):
        writer.add_frame(np.zeros(7))
    with pytest.raises(sphys.Error, match=f"{name}: frame 0 has 3 poses, the recording has 2"):
        writer.add_frame(np.tile(pose[:1], (3, 1)))
    stretched = pose.copy()
    stretched[1, 3:] = [0, 0, 0, 0.5]
    with pytest.raises(sphys.Error, match=f"{name}: cannot record frame 0, body 1: orientation"):
        writer.add_frame(stretched)
    broken = pose.copy()
    broken[0, 1] = np.nan
    with pytest.raises(sphys.Error, match=f"{name}: cannot record frame 0, body 0: position y"):
        writer.add_frame(broken)
    # The refused frames left nothing: the recording holds only the good one.
    writer.add_frame(pose)
    writer.finish()
    assert sphys.read_recording(str(path)).frame_count == 1

    for time_step in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(sphys.Error, match="other.sphysrec: the time step"):
            sphys.RecordingWriter(str(tmp_path / "other.sphysrec"), 2, time_step)
    with pytest.raises(sphys.Error, match="nodir/x.sphysrec: cannot write"):
        sphys.RecordingWriter(str(tmp_path / "nodir" / "x.sphysrec"), 2, 0.01)
    assert sorted(os.listdir(tmp_path)) == ["bad.sphysrec"]


def test_recording_writer_used_after_finish(tmp_path, isolated):
    # finish() inside a with block is the caller saying "done" early: leaving the block must not
    # finish again, and a frame after finish() is refused for what it is, not as a full disk.
    # (Isolated: the library asserts on both in debug builds.)
    path = tmp_path / "early.sphysrec"
    isolated(textwrap.dedent(f"""
        import numpy as np
        import sphys
        pose = np.zeros((1, 7), dtype=np.float32)
        pose[:, 6] = 1
        with sphys.RecordingWriter({str(path)!r}, 1, 0.01) as w:
            w.add_frame(pose)
            w.finish()
        assert sphys.read_recording({str(path)!r}).frame_count == 1
        try:
            w.add_frame(pose)
        except sphys.Error as error:
            assert "finish" in str(error) and "disk" not in str(error), str(error)
        else:
            raise AssertionError("add_frame after finish() was accepted")
        try:
            w.finish()
        except sphys.Error as error:
            assert "finish" in str(error) and "disk" not in str(error), str(error)
        else:
            raise AssertionError("a second finish() was accepted")
        assert sphys.read_recording({str(path)!r}).frame_count == 1
    """))


def test_read_recording_errors(tmp_path, simulate_cli):
    _, good = simulate_cli("stacks:1x3", 30)
    data = good.read_bytes()
    cases = {
        "missing.sphysrec": (None, "no such file"),
        "empty.sphysrec": (b"", "file is empty, not a sphys recording"),
        "text.sphysrec": (b"hello, this is not a recording at all" * 3,
                          'not a sphys recording \\(it does not start with "SPHYSREC"\\)'),
        "header.sphysrec": (data[:20], "truncated header: the file has 20 bytes"),
        "cut.sphysrec": (data[:-5], "truncated frames"),
        "long.sphysrec": (data + b"xyz", "3 trailing bytes after the last frame"),
        "version.sphysrec": (data[:8] + (3).to_bytes(4, "little") + data[12:],
                             "unsupported recording version 3"),
    }
    for name, (content, message) in cases.items():
        path = tmp_path / name
        if content is not None:
            path.write_bytes(content)
        with pytest.raises(sphys.Error, match=f"^{re.escape(str(path))}: {message}"):
            sphys.read_recording(str(path))
    with pytest.raises(sphys.Error, match="is a directory, not a recording"):
        sphys.read_recording(str(tmp_path))
    # A pose that is not a rotation: the last pose's orientation z (its last 4 bytes) set to 0.5
    # adds at least 0.1 to the length (z was near 0: the bunnies turn about y).
    bad = bytearray(data)
    assert abs(np.frombuffer(data[-4:], dtype="<f4")[0]) < 0.1
    bad[-4:] = np.float32(0.5).tobytes()
    path = tmp_path / "pose.sphysrec"
    path.write_bytes(bytes(bad))
    with pytest.raises(sphys.Error, match=r"frame 30, body 2: orientation has length"):
        sphys.read_recording(str(path))


def test_paths_may_be_pathlib_paths(tmp_path):
    # Every function taking a file takes a pathlib.Path as well as a str.
    poses = np.array([[0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 1.0]], dtype=np.float32)
    path = tmp_path / "one.sphysrec"
    with sphys.RecordingWriter(path, 1, 0.5) as writer:
        writer.add_frame(poses)
    assert np.array_equal(sphys.read_recording(path).poses[0], poses)
    tree = sphys.SphereTree.from_arrays([[0.0, 0.0, 0.0]], [0.25], [-1], 8)
    sphys.write_sph(tmp_path / "one.sph", tree)
    assert sphys.read_sph(tmp_path / "one.sph") == tree
    cube = tmp_path / "cube.off"
    cube.write_text("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
    assert len(sphys.load_mesh(cube).triangles) == 4
    assert len(sphys.load_model(cube).triangles) == 4
    with pytest.raises(sphys.Error, match="spec must be a str or a path"):
        sphys.load_model(3)
