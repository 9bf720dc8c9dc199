"""Sweeps on Dask distributed: the grid of runs, a run alone (against `sphys simulate`), and the
acceptance test of the sweep: the paper's eight Table 1 rows under two responses, 200 frames each,
on a LocalCluster of two worker processes, give every run the figures and final poses of the same
run made alone in this process, and a run whose scene names a missing mesh is reported failed
with its parameters while the others complete. Then the files a sweep writes and
`python3 -m sphys.sweep`."""

import csv
import hashlib
import json
import os
import signal
import subprocess
import sys
import threading
import time

import distributed
import numpy as np
import pandas
import pytest

import sphys
import sphys.sweep as sweep

# The two settings of the acceptance sweep: the experiment's two responses (`sphys experiment
# --mode`): the paper's impulse per contact as published, and the runtime's plausible one.
SETTINGS = [{"response": "paper"}, {"response": "plausible"}]
FRAMES = 200
MISSING_MESH = "no_such_bunny.obj"


def missing_mesh_scene(stacks_scene="stacks:1x2"):
    """A scene dict of the scene-file format: a preset's bodies with the last one's mesh a file
    that is not there."""
    scene = sphys.load_scene(stacks_scene).to_dict()
    scene["bodies"][-1]["mesh"] = MISSING_MESH
    return scene


@pytest.fixture(scope="module")
def missing_mesh_file(tmp_path_factory):
    """A scene file whose second body's mesh (relative: next to the file) does not exist."""
    path = tmp_path_factory.mktemp("scenes") / "missing_mesh.json"
    path.write_text(json.dumps(missing_mesh_scene()))
    return path


@pytest.fixture(scope="module")
def client():
    """A Dask client of a LocalCluster of two single-threaded worker processes."""
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    client = distributed.Client(cluster)
    try:
        yield client
    finally:
        client.close()
        cluster.close()


def alone(run):
    """run_one of a run's parameters in this process."""
    return sweep.run_one({key: run[key] for key in sweep.RUN_KEYS})


def poses_sha256(poses):
    return hashlib.sha256(np.ascontiguousarray(poses, dtype=np.float32).tobytes()).hexdigest()


def assert_same_run(swept, single):
    """A run of a sweep against the same parameters run alone: the same status, figures (but
    times) and final poses."""
    assert swept["status"] == single["status"] == "ok", (swept.get("error"), single.get("error"))
    assert sweep.deterministic(swept["summary"]) == sweep.deterministic(single["summary"])
    assert swept["final_poses_sha256"] == single["final_poses_sha256"]


def assert_failed_on_missing_mesh(record, scene_name):
    assert record["status"] == "failed"
    assert record["error_type"] == "Error"
    assert MISSING_MESH in record["error"] and "no such file" in record["error"]
    assert record["error"].startswith(f"{scene_name}: /bodies/1/mesh: ")
    assert "summary" not in record and "final_poses_sha256" not in record
    assert "traceback" not in record  # a sphys.Error carries the command line's message alone


# ---------------------------------------------------------------------------------------------
# The grid


def test_table1_scenes_are_the_papers_rows():
    scenes = sweep.table1_scenes()
    assert scenes == [
        {"scene": f"stacks:{row['stacks']}x{row['per_stack']}", "depth": row["depth"],
         "label": row["id"]} for row in sphys.paper_table()]
    assert [s["label"] for s in scenes] == sphys.experiment_rows()
    assert scenes[3] == {"scene": "stacks:4x50", "depth": 3, "label": "d3-4x50"}


def test_grid_is_every_scene_with_every_setting_and_seed_in_order():
    settings = [{"response": "paper"}, {"solver.soft_substeps": 6}]
    runs = sweep.grid(["stacks:1x2", {"scene": "stacks:2x1", "depth": 2, "label": "two"}],
                      settings, seeds=[None, 5], frames=7)
    assert len(runs) == 8
    assert [run["run"] for run in runs] == list(range(8))
    assert [(run["label"], run["settings"], run["seed"]) for run in runs] == [
        (label, variant, seed) for label in ("stacks:1x2", "two") for variant in settings
        for seed in (None, 5)]
    assert all(set(run) == set(sweep.RUN_KEYS) and run["frames"] == 7 for run in runs)
    assert [run["depth"] for run in runs] == [None] * 4 + [2] * 4
    assert [run["scene"] for run in runs] == ["stacks:1x2"] * 4 + ["stacks:2x1"] * 4
    # Each run has its own copy of its settings.
    settings[0]["response"] = "plausible"
    runs[1]["settings"]["extra"] = 1
    assert runs[0]["settings"] == {"response": "paper"} and runs[4]["settings"] == {"response": "paper"}


def test_grid_defaults_and_single_scenes():
    assert sweep.grid("stacks:1x1") == [{"run": 0, "label": "stacks:1x1", "scene": "stacks:1x1",
                                        "depth": None, "settings": {}, "seed": None,
                                        "frames": None}]
    runs = sweep.grid({"scene": "stacks:1x1"}, [], [], frames=np.int64(3))
    assert len(runs) == 1 and runs[0]["frames"] == 3 and type(runs[0]["frames"]) is int
    inline = sweep.grid({"scene": {"format": "sphys-scene"}})[0]
    assert inline["label"] == "inline scene" and inline["scene"] == {"format": "sphys-scene"}


@pytest.mark.parametrize("kwargs, message", [
    (dict(scenes=[42]), "a scene is a preset or file name, or a dict with 'scene', got 42"),
    (dict(scenes=[{"path": "stacks:1x1"}]), "a dict with 'scene'"),
    (dict(scenes=[{"scene": "stacks:1x1", "seed": 3}]), r"takes scene, depth and label, not \['seed'\]"),
    (dict(scenes=[{"scene": 7}]), "scene is a preset or file name, or a dict of the scene-file format, got 7"),
    (dict(scenes=[{"scene": "stacks:1x1", "depth": "3"}]), "depth must be a whole number"),
    (dict(scenes=["stacks:1x1"], settings=["response=paper"]), r"settings\[0\] must be a dict"),
    (dict(scenes=["stacks:1x1"], frames=0), "frames must be a whole number of at least 1, got 0"),
    (dict(scenes=["stacks:1x1"], frames=2.5), "frames must be a whole number"),
    (dict(scenes=["stacks:1x1"], frames=True), "frames must be a whole number"),
    (dict(scenes=["stacks:1x1"], seeds=[-1]), "a seed is a whole number of at least 0 or None, got -1"),
    (dict(scenes=["stacks:1x1"], seeds=["7"]), "a seed is a whole number"),
])
def test_grid_rejects_bad_parameters(kwargs, message):
    with pytest.raises(sphys.Error, match=message) as raised:
        sweep.grid(**kwargs)
    assert str(raised.value).startswith("sweep: ")


# ---------------------------------------------------------------------------------------------
# One run


@pytest.mark.parametrize("depth, settings", [(None, {}), (2, {"response": "paper"}),
                                             (3, {"solver.soft_substeps": 6, "sleep.enabled": False})])
def test_a_run_is_the_command_lines_simulate(cli, tmp_path, depth, settings):
    frames = 90
    run = sweep.grid({"scene": "stacks:2x3", "depth": depth}, [settings], frames=frames)[0]
    record = sweep.run_one(run)
    assert record["status"] == "ok" and record["error"] is None
    assert {key: record[key] for key in sweep.RUN_KEYS} == run
    args = ["simulate", "stacks:2x3", "--frames", frames, "--out", tmp_path, "--json"]
    if depth is not None:
        args += ["--depth", depth]
    for field, value in settings.items():
        args += ["--set", f"{field}={str(value).lower() if isinstance(value, bool) else value}"]
    done = cli(*args)
    assert done.returncode == 0, done.stderr
    theirs = json.loads(done.stdout)
    # The command line adds the files it wrote.
    assert theirs.pop("csv") == str(tmp_path / "frames.csv")
    assert theirs.pop("recording") == str(tmp_path / "recording.sphysrec")
    assert sweep.deterministic(record["summary"]) == sweep.deterministic(theirs)
    recording = sphys.read_recording(str(tmp_path / "recording.sphysrec"))
    assert record["final_poses_sha256"] == poses_sha256(recording.poses[-1])
    summary = record["summary"]
    assert summary["frames"] == frames and summary["bodies"] == 6
    assert summary["sphere_trees"].endswith(f"depth {depth or 3}")
    assert summary["response"] == settings.get("response", "plausible")


def test_deterministic_leaves_out_the_times_only():
    record = sweep.run_one(sweep.grid("stacks:1x3", frames=20)[0])
    summary = record["summary"]
    kept = sweep.deterministic(summary)
    assert set(summary) - set(kept) == set(sweep.TIMING_KEYS)
    assert all(kept[key] == summary[key] for key in kept)
    assert record["final_poses_sha256"] == alone(record)["final_poses_sha256"]


def test_a_run_alone_is_the_simulation_of_its_parameters():
    run = sweep.grid({"scene": "stacks:2x2", "depth": 2}, [{"response": "paper"}], seeds=[11],
                     frames=40)[0]
    record = sweep.run_one(run)
    scene = sphys.load_scene("stacks:2x2", seed=11)
    scene.frames = 40
    scene.set_settings({"response": "paper"})
    simulation = sphys.Simulation(scene, depth=2)
    summary = simulation.run()
    assert sweep.deterministic(record["summary"]) == sweep.deterministic(summary)
    assert record["final_poses_sha256"] == poses_sha256(simulation.poses())


def test_seeds_turn_the_presets_bunnies():
    # No seed is the committed layout, seed 2008 (docs/experiment.md); another seed another one.
    runs = sweep.grid("stacks:2x3", seeds=[None, 2008, 7], frames=30)
    sha = [sweep.run_one(run)["final_poses_sha256"] for run in runs]
    assert sha[0] == sha[1] != sha[2]


def test_an_inline_scene_runs_as_its_file_does(tmp_path):
    scene = sphys.load_scene("stacks:1x3").to_dict()
    path = tmp_path / "three.json"
    path.write_text(json.dumps(scene))
    by_dict = sweep.run_one(sweep.grid({"scene": scene, "label": "three"}, frames=25)[0])
    by_file = sweep.run_one(sweep.grid(str(path), frames=25)[0])
    assert by_dict["status"] == by_file["status"] == "ok"
    assert by_dict["label"] == "three" and by_dict["scene"] == scene
    assert by_dict["final_poses_sha256"] == by_file["final_poses_sha256"]
    a, b = sweep.deterministic(by_dict["summary"]), sweep.deterministic(by_file["summary"])
    assert (a.pop("scene"), b.pop("scene")) == ("scene.json", "three.json")
    assert a == b


@pytest.mark.parametrize("case", ["file", "dict", "depth", "setting", "range", "seed", "inline seed"])
def test_a_failing_run_is_reported_not_raised(missing_mesh_file, case):
    scene, kwargs, message = {
        "file": (str(missing_mesh_file), {}, None),
        "dict": ({"scene": missing_mesh_scene(), "label": "broken"}, {}, None),
        "depth": ({"scene": "stacks:1x1", "depth": 9}, {}, "the sphere-tree depth must be 1 to 6, got 9"),
        "setting": ("stacks:1x1", {"settings": [{"responce": "paper"}]}, "settings: no setting responce"),
        "range": ("stacks:1x1", {"settings": [{"solver.soft_substeps": 0}]},
                  "solver.soft_substeps must be between 1 and 64, got 0"),
        "seed": (str(missing_mesh_file), {"seeds": [3]}, "seed: only the stacks:SxN presets take a seed"),
        "inline seed": ({"scene": missing_mesh_scene()}, {"seeds": [3]},
                        "seed: only the stacks:SxN presets take a seed, not an inline scene"),
    }[case]
    run = sweep.grid(scene, frames=5, **kwargs)[0]
    record = sweep.run_one(run)
    assert {key: record[key] for key in sweep.RUN_KEYS} == run
    if message is None:
        assert_failed_on_missing_mesh(record, str(missing_mesh_file) if case == "file" else "scene.json")
    else:
        assert record["status"] == "failed" and record["error_type"] == "Error"
        assert message in record["error"]


def test_an_unexpected_failure_carries_its_traceback():
    run = dict(sweep.grid("stacks:1x1", frames=2)[0], frames="ten")  # past grid()'s checks
    record = sweep.run_one(run)
    assert record["status"] == "failed" and record["error_type"] == "TypeError"
    assert "incompatible function arguments" in record["error"]
    assert record["traceback"].startswith("Traceback") and "scene.frames" in record["traceback"]
    assert {key: record[key] for key in sweep.RUN_KEYS} == run


# ---------------------------------------------------------------------------------------------
# The acceptance test: Table 1 x two responses on two worker processes


def test_acceptance_table_1_sweep_on_two_workers_matches_runs_alone(client, missing_mesh_file,
                                                                     tmp_path):
    runs = (sweep.grid(sweep.table1_scenes(), SETTINGS, frames=FRAMES)
            + sweep.grid({"scene": str(missing_mesh_file), "label": "missing mesh"},
                         [SETTINGS[1]], frames=FRAMES))
    assert len(runs) == 17
    with distributed.get_task_stream(client) as tasks:
        result = sweep.run_sweep(runs, client=client, out=tmp_path / "sweep", progress=False)
    # Every run went to the cluster, and both workers took some.
    assert len(tasks.data) == 17
    assert len({task["worker"] for task in tasks.data}) == 2

    assert len(result.runs) == 17
    for i, (record, run) in enumerate(zip(result.runs, runs)):
        assert record["run"] == i
        assert {key: record[key] for key in sweep.RUN_KEYS if key != "run"} == {
            key: run[key] for key in sweep.RUN_KEYS if key != "run"}

    # The 16 rows: the figures and final poses of each run made alone in this process.
    paper = {row["id"]: row for row in sphys.paper_table()}
    for record in result.runs[:16]:
        assert_same_run(record, alone(record))
        row = paper[record["label"]]
        summary = record["summary"]
        assert summary["scene"] == record["scene"] == f"stacks:{row['stacks']}x{row['per_stack']}"
        assert summary["bodies"] == row["stacks"] * row["per_stack"]
        assert summary["sphere_trees"] == f"combined, branching 8, depth {row['depth']}"
        assert summary["frames"] == FRAMES
        assert summary["response"] == record["settings"]["response"]
        assert summary["contacts_per_frame"]["mean"] > 0
    # The two responses move the bunnies differently.
    for paper_run, plausible_run in zip(result.runs[0:16:2], result.runs[1:16:2]):
        assert paper_run["label"] == plausible_run["label"]
        assert paper_run["final_poses_sha256"] != plausible_run["final_poses_sha256"]

    # The 17th: failed, with its parameters and the missing mesh named.
    assert result.failed == [result.runs[16]]
    failed = result.failed[0]
    assert (failed["label"], failed["scene"], failed["settings"], failed["frames"], failed["seed"]) == (
        "missing mesh", str(missing_mesh_file), SETTINGS[1], FRAMES, None)
    assert_failed_on_missing_mesh(failed, str(missing_mesh_file))

    check_rows_table_and_files(result, tmp_path / "sweep")


def check_rows_table_and_files(result, folder):
    """SweepResult.rows / table and the runs.json and runs.csv the sweep wrote into `folder`."""
    rows = result.rows()
    assert len(rows) == len(result.runs) == 17
    for row, record in zip(rows, result.runs):
        assert row["run"] == record["run"] and row["label"] == record["label"]
        assert row["scene"] == record["scene"] and row["frames"] == FRAMES
        assert json.loads(row["settings"]) == record["settings"]
        assert row["status"] == record["status"] and row["error"] == record["error"]
        assert row["final_poses_sha256"] == record.get("final_poses_sha256")
        if record["status"] == "ok":
            summary = record["summary"]
            assert row["contacts_per_frame.mean"] == summary["contacts_per_frame"]["mean"]
            assert row["time_share_percent.response"] == summary["time_share_percent"]["response"]
            assert row["bodies"] == summary["bodies"]
            # Summary keys that name a parameter are kept apart from it.
            assert row["summary.scene"] == summary["scene"]
            assert row["summary.frames"] == summary["frames"]
            assert row["error_type"] is None
        else:
            assert row["error_type"] == "Error" and "bodies" not in row

    table = result.table()
    assert isinstance(table, pandas.DataFrame)
    assert list(table.index) == list(range(17)) and table.index.name == "run"
    assert (table["status"] == "ok").sum() == 16 and table.loc[16, "status"] == "failed"
    assert MISSING_MESH in table.loc[16, "error"]
    assert list(table.loc[0:15, "final_poses_sha256"]) == [r["final_poses_sha256"] for r in result.runs[:16]]

    assert sorted(os.listdir(folder)) == ["runs.csv", "runs.json"]  # no temporary file left
    with open(folder / "runs.json") as f:
        written = json.load(f)
    assert written == json.loads(json.dumps(result.runs))
    assert len(written) == 17 and written[16]["status"] == "failed"
    with open(folder / "runs.csv", newline="") as f:
        reader = csv.DictReader(f)
        columns = reader.fieldnames
        csv_rows = list(reader)
    assert len(csv_rows) == 17
    assert columns[:11] == ["run", "label", "scene", "depth", "seed", "frames", "settings",
                            "status", "error_type", "error", "final_poses_sha256"]
    assert set(columns) == {key for row in rows for key in row}
    for csv_row, row in zip(csv_rows, rows):
        assert csv_row["run"] == str(row["run"]) and csv_row["status"] == row["status"]
        assert csv_row["final_poses_sha256"] == (row["final_poses_sha256"] or "")
        assert json.loads(csv_row["settings"]) == json.loads(row["settings"])
    assert float(csv_rows[0]["contacts_per_frame.mean"]) == rows[0]["contacts_per_frame.mean"]
    frame = pandas.read_csv(folder / "runs.csv")
    assert frame.shape == (17, len(columns))


# ---------------------------------------------------------------------------------------------
# sweep() and run_sweep(): other ways in


def test_sweep_through_a_scheduler_address(client, capsys):
    scenes = [{"scene": "stacks:1x3", "depth": 2, "label": "a"}, "stacks:2x1"]
    address = client.scheduler.address
    result = sweep.sweep(scenes, [{"response": "paper"}], seeds=[None, 4], frames=30,
                         scheduler=address)
    assert [(r["label"], r["seed"]) for r in result.runs] == [("a", None), ("a", 4),
                                                              ("stacks:2x1", None), ("stacks:2x1", 4)]
    assert not result.failed
    for record in result.runs:
        assert_same_run(record, alone(record))
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 4 and lines[-1].startswith("sweep: 4/4 runs done (0 failed): run ")
    # The sweep closed its own client, not the cluster: this client still works.
    assert client.submit(sum, [1, 2]).result() == 3


def test_an_inline_scene_with_a_missing_mesh_fails_in_a_sweep(client):
    result = sweep.sweep([{"scene": missing_mesh_scene(), "label": "inline"}, "stacks:1x2"],
                         frames=10, client=client, progress=False)
    assert [r["status"] for r in result.runs] == ["failed", "ok"]
    assert result.failed[0]["label"] == "inline"
    assert_failed_on_missing_mesh(result.failed[0], "scene.json")
    assert json.loads(result.rows()[0]["scene"]) == missing_mesh_scene()
    assert_same_run(result.runs[1], alone(result.runs[1]))


def test_run_sweep_numbers_joined_grids_by_place(client):
    runs = sweep.grid("stacks:1x1", frames=3) + sweep.grid("stacks:1x2", frames=3)
    assert [r["run"] for r in runs] == [0, 0]
    result = sweep.run_sweep(runs, client=client, progress=False)
    assert [(r["run"], r["label"]) for r in result.runs] == [(0, "stacks:1x1"), (1, "stacks:1x2")]
    assert [r["run"] for r in runs] == [0, 0]  # the caller's runs are left as they were


def test_a_worker_killed_mid_sweep_loses_no_run():
    """A worker process SIGKILLed while it runs a simulation: Dask runs its work again on a
    worker that lives (the nanny starts a new one), and the sweep reports every run, each the
    same as the run made alone. A cluster of its own, so that no other test meets the kill."""
    runs = sweep.grid(["stacks:8x20"], seeds=[1, 2, 3, 4], frames=800)
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    client = distributed.Client(cluster)
    killed = []

    def kill_a_busy_worker():
        pids = client.run(os.getpid)
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline:
            busy = [worker for worker, tasks in client.processing().items() if tasks]
            if busy:
                time.sleep(0.2)  # into its run
                os.kill(pids[busy[0]], signal.SIGKILL)
                killed.append(pids[busy[0]])
                return
            time.sleep(0.01)

    try:
        killer = threading.Thread(target=kill_a_busy_worker)
        killer.start()
        result = sweep.run_sweep(runs, client=client, progress=False)
        killer.join()
    finally:
        client.close()
        cluster.close()
    assert killed, "no worker was busy within a minute"
    assert result.failed == []
    assert [r["run"] for r in result.runs] == [0, 1, 2, 3]
    for swept, run in zip(result.runs, runs):
        assert_same_run(swept, alone(run))


def test_sweep_argument_errors_raise_before_running(tmp_path):
    with pytest.raises(sphys.Error, match="n_workers must be at least 1, got 0"):
        sweep.sweep("stacks:1x1", n_workers=0)
    with pytest.raises(sphys.Error, match=r"runs\[1\] must be a dict with run, label, scene"):
        sweep.run_sweep(sweep.grid("stacks:1x1") + [{"scene": "stacks:1x1"}])
    with pytest.raises(sphys.Error, match="frames must be"):
        sweep.sweep("stacks:1x1", frames=-1)
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(sphys.Error, match="cannot create the output folder"):
        sweep.sweep("stacks:1x1", out=blocker / "sweep")


def test_a_result_of_no_runs_writes_empty_files(tmp_path):
    result = sweep.SweepResult([])
    assert result.failed == [] and result.rows() == []
    paths = result.write(tmp_path / "empty")
    assert [os.path.basename(p) for p in paths] == ["runs.json", "runs.csv"]
    assert json.loads((tmp_path / "empty" / "runs.json").read_text()) == []


# ---------------------------------------------------------------------------------------------
# python3 -m sphys.sweep


def sweep_cli(*args, cwd):
    """`python3 -m sphys.sweep ARGS` in folder `cwd`, finding this sphys package (its folder
    first on PYTHONPATH, made absolute) in it and in its Dask workers."""
    package_root = os.path.dirname(os.path.dirname(os.path.abspath(sphys.__file__)))
    path = os.pathsep.join([package_root] + [p for p in [os.environ.get("PYTHONPATH")] if p])
    return subprocess.run([sys.executable, "-m", "sphys.sweep", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, timeout=300,
                          env={**os.environ, "PYTHONPATH": path})


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_command_line_sweep(tmp_path):
    done = sweep_cli("stacks:1x3", "stacks:2x1", "--depth", 2, "--frames", 12, "--settings",
                     '{"response": "paper"}', "--workers", 2, "--out", "runs", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "sweep: 2 of 2 runs ok; wrote runs/runs.csv and runs.json"
    assert done.stderr.count("runs done") == 2
    rows = read_csv(tmp_path / "runs" / "runs.csv")
    assert [(r["run"], r["label"], r["depth"], r["frames"], r["status"]) for r in rows] == [
        ("0", "stacks:1x3", "2", "12", "ok"), ("1", "stacks:2x1", "2", "12", "ok")]
    written = json.loads((tmp_path / "runs" / "runs.json").read_text())
    for record in written:
        assert record["settings"] == {"response": "paper"}
        assert_same_run(record, alone(record))


def test_command_line_sweep_with_a_missing_mesh_exits_2(tmp_path, missing_mesh_file):
    done = sweep_cli(str(missing_mesh_file), "stacks:1x2", "--frames", 5, "--workers", 1,
                     "--out", "runs", cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert done.stdout.strip() == "sweep: 1 of 2 runs ok; wrote runs/runs.csv and runs.json"
    assert (f"sweep: run 0 failed ({missing_mesh_file}, settings {{}}, seed None): Error: "
            f"{missing_mesh_file}: /bodies/1/mesh: no such file: ") in done.stderr
    assert MISSING_MESH in done.stderr
    rows = read_csv(tmp_path / "runs" / "runs.csv")
    assert [(r["label"], r["status"], r["error_type"]) for r in rows] == [
        (str(missing_mesh_file), "failed", "Error"), ("stacks:1x2", "ok", "")]
    assert MISSING_MESH in rows[0]["error"]


@pytest.mark.parametrize("args, message", [
    ([], "give scenes, --table1, or both"),
    (["stacks:1x1", "--settings", "response=paper"], "argument --settings: not JSON"),
    (["stacks:1x1", "--settings", "[1, 2]"], "argument --settings: must be a JSON object"),
    (["stacks:1x1", "--frames", "0"], "sphys: error: sweep: frames must be a whole number of at least 1, got 0"),
    (["stacks:1x1", "--frames", "ten"], "argument --frames: invalid int value: 'ten'"),
    (["stacks:1x1", "--seeds", "-2"], "sphys: error: sweep: a seed is a whole number of at least 0"),
    (["stacks:1x1", "--workers", "0"], "--workers must be at least 1, got 0"),
    (["stacks:1x1", "--out", "blocker/runs"], "sphys: error: sweep: cannot create the output folder blocker/runs"),
    (["stacks:1x1", "--bogus"], "unrecognized arguments: --bogus"),
])
def test_command_line_argument_errors_exit_2(tmp_path, args, message):
    (tmp_path / "blocker").write_text("")
    done = sweep_cli(*args, cwd=tmp_path)
    assert done.returncode == 2
    assert message in done.stderr
    assert not (tmp_path / "out").exists()


def test_command_line_table1_on_a_running_scheduler(client, tmp_path, capsys):
    # main() in this process, on the module's cluster by its address: the eight Table 1 rows.
    code = sweep.main(["--table1", "--frames", "4", "--settings", '{"response": "paper"}',
                       "--scheduler", client.scheduler.address, "--out", str(tmp_path / "t1")])
    assert code == 0
    out = capsys.readouterr().out
    assert out.strip() == f"sweep: 8 of 8 runs ok; wrote {tmp_path / 't1'}/runs.csv and runs.json"
    written = json.loads((tmp_path / "t1" / "runs.json").read_text())
    assert [(r["label"], r["scene"], r["depth"]) for r in written] == [
        (s["label"], s["scene"], s["depth"]) for s in sweep.table1_scenes()]
    for record in written:
        assert record["frames"] == 4 and record["settings"] == {"response": "paper"}
        assert_same_run(record, alone(record))
