"""The paper's evaluation from Python: Table 1 and the §5 statistics as published, rows run as
`sphys experiment` runs them (the same contacts frame by frame, the same end state), the figures
derived from a row's frames, and sphys.experiment's DataFrames.

Contacts, poses and everything derived from them are the same on every run of a build; times are
not, so times are only checked against the formulas that derive figures from them."""

import csv
import json
import re
import threading

import numpy as np
import pandas
import pytest

import sphys
import sphys.experiment

# The paper's Table 1 (Rocha & Rodrigues, SAC 2008; docs/experiment.md): row id, contacts per
# frame, FPS, frame-time sd (ms), in the paper's order.
PAPER_TABLE_1 = [
    ("d2-4x25", 2, 4, 25, 4216.81, 57.47, 5.89),
    ("d2-4x50", 2, 4, 50, 5621.16, 33.29, 7.79),
    ("d3-4x25", 3, 4, 25, 122445.31, 12.70, 35.96),
    ("d3-4x50", 3, 4, 50, 542613.84, 3.34, 302.89),
    ("d2-8x10", 2, 8, 10, 16381.50, 43.80, 9.25),
    ("d2-8x20", 2, 8, 20, 12771.69, 31.50, 8.29),
    ("d3-8x10", 3, 8, 10, 77246.49, 17.41, 18.92),
    ("d3-8x20", 3, 8, 20, 265562.60, 6.91, 69.29),
]
ROW_IDS = [row[0] for row in PAPER_TABLE_1]

# The paper's §5 statistics (docs/experiment.md).
PAPER_STATISTICS = {
    "contacts_fps_correlation": 0.75,
    "contacts_frame_sd_correlation": 0.96,
    "detection_share_mean_percent": 23.0,
    "detection_share_sd_points": 0.08,
    "response_share_mean_percent": 40.0,
    "response_share_sd_points": 0.26,
    "detection_share_contacts_correlation": -0.59,
    "response_share_contacts_correlation": 0.88,
}

# docs/experiment.md, "A run": the eight rows at 880 frames in paper mode on the octree ground.
# Contacts and the end state are the same on every machine with this build.
DOCUMENTED_RUN = {
    "d2-4x25": (153.12, 59, 100),
    "d2-4x50": (205.54, 179, 200),
    "d3-4x25": (221.22, 50, 100),
    "d3-4x50": (1600.22, 170, 200),
    "d2-8x10": (236.92, 11, 80),
    "d2-8x20": (455.03, 81, 160),
    "d3-8x10": (646.64, 6, 80),
    "d3-8x20": (1331.49, 59, 160),
}

# A row of the text report's Table 1: depth, then "S × N".
ROW_LINE = re.compile(r"^\s*\d+\s+\d+ × \d+\s")

# RowResult.summary(), as `sphys experiment --json` prints a row, in order.
SUMMARY_KEYS = ["id", "depth", "stacks", "per_stack", "frames", "contacts_per_frame",
                "mean_frame_ms", "fps", "frame_time_sd_ms", "detection_share_percent",
                "response_share_percent", "frames_drawn", "fps_with_drawing", "drawing_share_percent",
                "detection_share_of_drawn_frame_percent", "response_share_of_drawn_frame_percent",
                "bodies", "bodies_below_plane", "lowest_center_y_end_m",
                "deepest_penetration_m", "deepest_penetration_frame", "mean_penetration_m",
                "penetrating_frames", "movable_bodies", "bodies_at_rest", "bodies_asleep", "bodies_still_moving",
                "all_at_rest_from_frame", "jitter_m_per_s", "final_kinetic_energy_J",
                "stopped_non_finite", "ground", "tree_builder", "first_picture", "last_picture",
                "pictures_missing"]
# The summary's figures that measure time: the rest is the same on every run of a build.
TIMING_KEYS = {"mean_frame_ms", "fps", "frame_time_sd_ms", "detection_share_percent",
               "response_share_percent"}

# The bunny of the stacks presets: 0.1988 m³ at 1000 kg/m³ (docs/experiment.md). unit: kg
BUNNY_MASS = 198.8
G = 9.81
DT = 1.0 / 60.0


def untimed(summary):
    """A row's summary without the figures that measure time."""
    return {key: value for key, value in summary.items() if key not in TIMING_KEYS}


def run_cli_experiment(cli, out, *args):
    """`sphys experiment ARGS --json --no-plots --no-pictures --out OUT`: the JSON and the rows'
    per-frame CSVs by row id."""
    done = cli("experiment", *args, "--json", "--no-plots", "--no-pictures", "--out", out,
               timeout=300)
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    frames = {}
    for row in report["rows"]:
        with open(out / f"{row['id']}.csv", newline="") as f:
            frames[row["id"]] = list(csv.DictReader(f))
    return report, frames


def assert_matches_cli_row(result, cli_row, cli_frames):
    """A RowResult against the command line's JSON row and per-frame CSV of the same row: the
    same keys, and every figure that does not measure time equal."""
    summary = result.summary()
    assert list(cli_row) == list(summary) == SUMMARY_KEYS
    assert cli_row["id"] == result.row
    assert untimed(cli_row) == untimed(summary)
    assert cli_row["frames"] == len(result.frames["contacts"]) == len(cli_frames)
    np.testing.assert_array_equal(result.frames["contacts"],
                                  [int(frame["contacts"]) for frame in cli_frames])
    assert [int(frame["frame"]) for frame in cli_frames] == list(range(1, len(cli_frames) + 1))


@pytest.fixture(scope="module")
def full_run():
    """The whole experiment as published: the eight rows, 880 frames each, paper mode, octree
    ground (a few seconds)."""
    return sphys.experiment.run()


@pytest.fixture(scope="module")
def full_cli(cli, tmp_path_factory):
    """`sphys experiment --json` of the whole experiment, and its per-frame CSVs."""
    return run_cli_experiment(cli, tmp_path_factory.mktemp("experiment"))


@pytest.fixture(scope="module")
def short_row():
    """d3-8x10 for 40 frames, paper mode."""
    return sphys.run_experiment_row("d3-8x10", frames=40)


# ---------------------------------------------------------------------------------------------
# The paper's figures


def test_paper_table_is_the_papers_table_1():
    table = sphys.paper_table()
    assert all(list(row) == ["id", "depth", "stacks", "per_stack", "contacts_per_frame", "fps",
                             "frame_time_sd_ms"] for row in table)
    assert [tuple(row.values()) for row in table] == PAPER_TABLE_1
    for row in table:
        assert row["id"] == f"d{row['depth']}-{row['stacks']}x{row['per_stack']}"
    # The paper prints +0.75 for contacts vs FPS; its own Table 1 gives -0.75 (docs/experiment.md).
    r = np.corrcoef([row["contacts_per_frame"] for row in table], [row["fps"] for row in table])[0, 1]
    assert round(r, 2) == -0.75
    # A fresh list each call: changing one does not change the next.
    table[0]["fps"] = 0.0
    assert sphys.paper_table()[0]["fps"] == 57.47


def test_paper_statistics_are_the_papers():
    statistics = sphys.paper_statistics()
    assert statistics == PAPER_STATISTICS
    assert list(statistics) == list(PAPER_STATISTICS)


def test_experiment_rows_are_given_in_the_papers_order():
    assert sphys.experiment_rows() == ROW_IDS
    assert sphys.experiment_rows(None) == ROW_IDS
    assert sphys.experiment_rows("d3-8x20,d2-4x25,d2-4x25") == ["d2-4x25", "d3-8x20"]
    assert sphys.experiment_rows(",".join(reversed(ROW_IDS))) == ROW_IDS
    assert sphys.experiment_rows("d2-8x10") == ["d2-8x10"]


@pytest.mark.parametrize("ids, named", [("d4-4x25", "d4-4x25"), ("d2-4x25,d2-4x26", "d2-4x26"),
                                        ("", ""), ("d2-4x25,", "")])
def test_unknown_experiment_rows_raise(ids, named):
    with pytest.raises(sphys.Error, match=f"unknown experiment row '{named}'; rows: d2-4x25, "):
        sphys.experiment_rows(ids)


# ---------------------------------------------------------------------------------------------
# One row


def test_row_result_describes_the_row(short_row):
    r = short_row
    assert r.row == "d3-8x10"
    assert repr(r) == "<sphys.RowResult d3-8x10: 40 frames>"
    summary = r.summary()
    assert list(summary) == SUMMARY_KEYS
    assert ({key: summary[key] for key in ("id", "depth", "stacks", "per_stack", "frames", "bodies")}
            == {"id": "d3-8x10", "depth": 3, "stacks": 8, "per_stack": 10, "frames": 40, "bodies": 80})
    assert summary["tree_builder"] == "combined, branching 8, depth 3"
    assert summary["ground"] == "octree of a 16 m box, 5 levels"
    assert summary["stopped_non_finite"] is False
    frames = r.frames
    assert set(frames) == {"step_ms", "detection_ms", "response_ms", "contacts"}
    for name in ("step_ms", "detection_ms", "response_ms"):
        assert frames[name].dtype == np.float64 and frames[name].shape == (40,)
        assert np.all(np.isfinite(frames[name])) and np.all(frames[name] >= 0.0)
    assert frames["contacts"].dtype == np.uint32 and frames["contacts"].shape == (40,)
    assert np.all(frames["step_ms"] > 0.0)
    # The bunnies fall onto the octree ground's spheres (up to 0.59 m above the plane) and onto
    # one another: contacts appear and grow as they pile up.
    assert frames["contacts"][-1] > frames["contacts"][0]
    assert frames["contacts"].sum() > 0
    # The property gives a fresh copy each time.
    frames["contacts"][:] = 0
    assert r.frames["contacts"].sum() > 0


def test_summary_is_table_1_of_the_rows_frames(short_row):
    frames = short_row.frames
    summary = short_row.summary()
    step = frames["step_ms"]
    assert summary["contacts_per_frame"] == pytest.approx(frames["contacts"].mean(), rel=1e-12)
    assert summary["mean_frame_ms"] == pytest.approx(step.mean(), rel=1e-12)
    assert summary["fps"] == pytest.approx(1000.0 / step.mean(), rel=1e-12)
    assert summary["frame_time_sd_ms"] == pytest.approx(step.std(ddof=1), rel=1e-9)
    assert summary["detection_share_percent"] == pytest.approx(
        100.0 * frames["detection_ms"].sum() / step.sum(), rel=1e-12)
    assert summary["response_share_percent"] == pytest.approx(
        100.0 * frames["response_ms"].sum() / step.sum(), rel=1e-12)


def test_one_frame_has_no_frame_time_spread():
    summary = sphys.run_experiment_row("d2-4x25", frames=1).summary()
    assert summary["frames"] == 1
    assert summary["frame_time_sd_ms"] is None  # the sample sd of one frame: none (null)
    assert summary["fps"] == pytest.approx(1000.0 / summary["mean_frame_ms"], rel=1e-12)


def test_plausibility_figures_are_consistent(short_row):
    p = short_row.summary()
    assert 1 <= p["deepest_penetration_frame"] <= 40
    assert 1 <= p["penetrating_frames"] <= 40
    assert p["deepest_penetration_m"] >= p["mean_penetration_m"] > 0.0
    assert p["movable_bodies"] == p["bodies"] == 80
    # Paper mode has no sleeping, and falling bunnies are not at rest after 40 frames.
    assert p["bodies_asleep"] == 0 and p["bodies_at_rest"] == 0
    assert p["all_at_rest_from_frame"] is None
    assert p["final_kinetic_energy_J"] > 0.0 and p["jitter_m_per_s"] >= 0.0
    assert p["bodies_below_plane"] == 0 and p["lowest_center_y_end_m"] > 0.0


def test_free_fall_on_the_exact_plane():
    # The lowest bunnies start 1 m up and cannot reach the exact plane in 5 frames: no contact,
    # so every bunny falls freely. Semi-implicit Euler: after n steps v = n g dt and the drop is
    # g dt² n (n + 1) / 2.
    n = 5
    r = sphys.run_experiment_row("d2-4x25", frames=n, ground="plane")
    p = r.summary()
    assert p["ground"] == "exact plane"
    np.testing.assert_array_equal(r.frames["contacts"], 0)
    assert p["contacts_per_frame"] == 0.0
    assert p["penetrating_frames"] == 0 and p["deepest_penetration_frame"] == 0
    assert p["deepest_penetration_m"] == 0.0 and p["mean_penetration_m"] == 0.0
    assert p["lowest_center_y_end_m"] == pytest.approx(1.0 - G * DT * DT * n * (n + 1) / 2, abs=1e-5)
    assert p["bodies_below_plane"] == 0
    mass = p["bodies"] * BUNNY_MASS
    assert p["final_kinetic_energy_J"] == pytest.approx(0.5 * mass * (n * G * DT) ** 2, rel=1e-3)


def test_rows_are_deterministic_and_the_tree_cache_changes_nothing(short_row):
    for again in (sphys.run_experiment_row("d3-8x10", frames=40),
                  sphys.run_experiment_row("d3-8x10", frames=40, cache=False)):
        np.testing.assert_array_equal(again.frames["contacts"], short_row.frames["contacts"])
        assert untimed(again.summary()) == untimed(short_row.summary())


def test_rows_run_at_once_on_threads_give_the_results_they_give_alone():
    # run_experiment_row releases the GIL: two rows on two threads at once must not disturb
    # one another.
    rows = ["d2-8x20", "d3-4x25"]
    alone = {row: sphys.run_experiment_row(row, frames=60) for row in rows}
    together = {}
    errors = []

    def work(row):
        try:
            together[row] = sphys.run_experiment_row(row, frames=60)
        except Exception as error:  # noqa: BLE001  (reported below)
            errors.append(error)

    threads = [threading.Thread(target=work, args=(row,)) for row in rows]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not errors
    for row in rows:
        np.testing.assert_array_equal(together[row].frames["contacts"], alone[row].frames["contacts"])
        assert untimed(together[row].summary()) == untimed(alone[row].summary())


@pytest.mark.parametrize("kwargs, message", [
    (dict(row="d5-4x25"), "unknown experiment row 'd5-4x25'"),
    (dict(row="d2-4x25,d2-4x50"), "row: expected one row id"),
    (dict(row=""), "unknown experiment row ''"),
    (dict(row="d2-4x25", frames=0), "at least 1 frame, got 0"),
    (dict(row="d2-4x25", frames=-5), "at least 1 frame, got -5"),
    (dict(row="d2-4x25", response="bogus"), "unknown response mode 'bogus'; response modes: paper, plausible"),
    (dict(row="d2-4x25", response="plausible", contacts="some"),
     "unknown contact set 'some'; contact sets: all, reduced"),
    (dict(row="d2-4x25", ground="sand"), "ground must be octree or plane, got 'sand'"),
])
def test_bad_row_arguments_raise_naming_them(kwargs, message):
    kwargs = {"frames": 2, **kwargs}
    row = kwargs.pop("row")
    with pytest.raises(sphys.Error, match=message) as raised:
        sphys.run_experiment_row(row, **kwargs)
    assert isinstance(raised.value, ValueError)


def test_wrong_argument_types_raise_type_errors():
    with pytest.raises(TypeError):
        sphys.run_experiment_row("d2-4x25", frames="10")
    with pytest.raises(TypeError):
        sphys.run_experiment_row("d2-4x25", 10)  # frames is keyword-only
    with pytest.raises(TypeError):
        sphys.experiment_statistics([1, 2])


# ---------------------------------------------------------------------------------------------
# Against the command line


def test_the_whole_experiment_matches_the_command_line(full_run, full_cli):
    report, frames = full_cli
    assert report["response"] == "paper" and report["contacts"] == "reduced"
    assert [row["id"] for row in report["rows"]] == [r.row for r in full_run] == ROW_IDS
    for result, cli_row in zip(full_run, report["rows"]):
        assert len(result.frames["contacts"]) == 880
        assert_matches_cli_row(result, cli_row, frames[result.row])


def test_the_whole_experiment_gives_the_documented_run(full_run):
    for result in full_run:
        contacts, below, bodies = DOCUMENTED_RUN[result.row]
        summary = result.summary()
        assert round(summary["contacts_per_frame"], 2) == contacts
        assert (summary["bodies_below_plane"], summary["bodies"]) == (below, bodies)


@pytest.mark.parametrize("options", [
    dict(response="plausible", contacts="all"),
    dict(response="plausible", contacts="reduced", ground="plane"),
    dict(response="paper", ground="plane"),
])
def test_modes_and_grounds_match_the_command_line(cli, tmp_path, options):
    rows = ["d3-4x25", "d2-8x10"]
    args = ["--only", ",".join(rows), "--frames", 90]
    if "response" in options:
        args += ["--mode", options["response"]]
    if "contacts" in options:
        args += ["--contacts", options["contacts"]]
    if "ground" in options:
        args += ["--ground", options["ground"]]
    report, frames = run_cli_experiment(cli, tmp_path, *args)
    assert report["response"] == options["response"]
    results = sphys.experiment.run(rows, frames=90, **options)
    assert [r.row for r in results] == rows
    for result, cli_row in zip(results, report["rows"]):
        assert_matches_cli_row(result, cli_row, frames[result.row])


def test_the_response_modes_differ():
    # The options reach the run: the paper's response, the plausible one on every leaf pair and
    # on reduced manifolds give different contacts once bunnies pile up.
    runs = [sphys.run_experiment_row("d2-8x10", frames=90, response=response, contacts=contacts)
            for response, contacts in (("paper", None), ("plausible", "all"),
                                       ("plausible", "reduced"))]
    contacts = [r.frames["contacts"] for r in runs]
    assert not np.array_equal(contacts[0], contacts[1])
    assert not np.array_equal(contacts[1], contacts[2])
    # The paper's response never puts a body to sleep.
    assert runs[0].summary()["bodies_asleep"] == 0


# ---------------------------------------------------------------------------------------------
# Statistics and the text report


def words(line):
    """A line of a text table as its words; a rule as "rule", whatever its length."""
    return ["rule"] if line and set(line) == {"-"} else line.split()


def pearson(x, y):
    return float(np.corrcoef(x, y)[0, 1])


def test_experiment_statistics_are_those_of_the_rows_summaries(full_run):
    summaries = [r.summary() for r in full_run]
    ours = sphys.experiment_statistics(full_run)
    assert list(ours) == list(PAPER_STATISTICS)

    def column(key):
        return np.array([s[key] for s in summaries])

    contacts = column("contacts_per_frame")
    detection = column("detection_share_percent")
    response = column("response_share_percent")
    expected = {
        "contacts_fps_correlation": pearson(contacts, column("fps")),
        "contacts_frame_sd_correlation": pearson(contacts, column("frame_time_sd_ms")),
        "detection_share_mean_percent": detection.mean(),
        "detection_share_sd_points": detection.std(ddof=1),
        "response_share_mean_percent": response.mean(),
        "response_share_sd_points": response.std(ddof=1),
        "detection_share_contacts_correlation": pearson(detection, contacts),
        "response_share_contacts_correlation": pearson(response, contacts),
    }
    for key, value in expected.items():
        assert ours[key] == pytest.approx(value, rel=1e-9, abs=1e-12), key


def test_statistics_of_one_row_and_of_none():
    row = sphys.run_experiment_row("d2-4x25", frames=10)
    one = sphys.experiment_statistics([row])
    summary = row.summary()
    assert one["detection_share_mean_percent"] == summary["detection_share_percent"]
    assert one["response_share_mean_percent"] == summary["response_share_percent"]
    # Spreads and correlations of one row: none (null, as `sphys experiment --json` writes them).
    for key in ("contacts_fps_correlation", "contacts_frame_sd_correlation",
                "detection_share_sd_points", "response_share_sd_points",
                "detection_share_contacts_correlation", "response_share_contacts_correlation"):
        assert one[key] is None, key
    none = sphys.experiment_statistics([])
    assert list(none) == list(PAPER_STATISTICS)
    assert all(value is None for value in none.values())


def test_experiment_text_is_the_command_lines_report(cli, tmp_path):
    rows = "d2-4x25,d3-8x10"
    for response, contacts in (("paper", None), ("plausible", "all")):
        args = ["experiment", "--only", rows, "--frames", 30, "--no-plots", "--out", tmp_path,
                "--mode", response]
        if contacts:
            args += ["--contacts", contacts]
        done = cli(*args)
        assert done.returncode == 0, done.stderr
        results = sphys.experiment.run(rows, frames=30, response=response, contacts=contacts)
        text = sphys.experiment_text(results, response=response, contacts=contacts)
        ours = text.splitlines()
        theirs = done.stdout.splitlines()
        # The command line adds the machine and the report's path after a blank line.
        assert theirs[-2].startswith("machine: ") and theirs[-1].startswith("report: ")
        theirs = theirs[:-3]
        assert len(ours) == len(theirs)
        # The mode lines and the tables' headers are the same; in the rows, every column but our
        # FPS and frame-time sd (times); in the statistics, the labels and the paper's column.
        assert ours[0] == theirs[0] and ours[0].startswith(f"Response: {response} ")
        assert ours[1] == theirs[1]
        table_start = ours.index("Table 1: the paper's figures beside ours (our FPS: the physics "
                                 "step only, no rendering)")
        assert theirs[table_start] == ours[table_start]
        row_lines = [i for i, line in enumerate(ours) if ROW_LINE.match(line)]
        assert row_lines == [i for i, line in enumerate(theirs) if ROW_LINE.match(line)]
        assert len(row_lines) == 2
        # Headers and rules: the columns' widths follow the widest figure, so times change them.
        assert ([words(line) for line in ours[table_start:row_lines[0]]]
                == [words(line) for line in theirs[table_start:row_lines[0]]])
        for i, paper in zip(row_lines, (PAPER_TABLE_1[0], PAPER_TABLE_1[6])):
            a, b = ours[i].split(), theirs[i].split()
            assert a[:7] + a[8:10] + a[11:] == b[:7] + b[8:10] + b[11:]
            assert a[:4] == [str(paper[1]), str(paper[2]), "×", str(paper[3])]
            assert a[4] == f"{paper[4]:.2f}" and a[6] == f"{paper[5]:.2f}" and a[9] == f"{paper[6]:.2f}"
            assert a[8] == b[8] == "n/a"
        row_lines = [ours[i] for i in row_lines]
        summary = results[0].summary()
        assert row_lines[0].split()[5] == f"{summary['contacts_per_frame']:.2f}"
        assert f"{summary['bodies_below_plane']} of {summary['bodies']}" in row_lines[0]
        statistics_start = ours.index(next(line for line in ours if line.startswith("§5 statistic")))
        for a, b in zip(ours[statistics_start:], theirs[statistics_start:]):
            if words(a) != ["rule"]:
                assert words(a)[:-1] == words(b)[:-1]


def test_experiment_text_rejects_unknown_modes():
    with pytest.raises(sphys.Error, match="unknown response mode 'fast'"):
        sphys.experiment_text([], response="fast")
    with pytest.raises(sphys.Error, match="unknown contact set 'most'"):
        sphys.experiment_text([], contacts="most")


# ---------------------------------------------------------------------------------------------
# sphys.experiment: run, table, statistics


def test_experiment_run_takes_ids_as_a_list_or_a_string():
    by_list = sphys.experiment.run(["d3-4x25", "d2-4x25"], frames=15)
    by_text = sphys.experiment.run("d3-4x25,d2-4x25", frames=15)
    one = sphys.experiment.run("d2-4x25", frames=15)
    assert [r.row for r in by_list] == [r.row for r in by_text] == ["d2-4x25", "d3-4x25"]
    assert [r.row for r in one] == ["d2-4x25"]
    for a, b in zip(by_list, by_text):
        np.testing.assert_array_equal(a.frames["contacts"], b.frames["contacts"])
    np.testing.assert_array_equal(one[0].frames["contacts"], by_list[0].frames["contacts"])
    assert all(len(r.frames["contacts"]) == 15 for r in by_list + by_text + one)


@pytest.mark.parametrize("kwargs, message", [
    (dict(rows=["d2-4x25", "d9-9x9"]), "unknown experiment row 'd9-9x9'"),
    (dict(rows=[]), "unknown experiment row ''"),
    (dict(rows="d2-4x25", frames=0), "at least 1 frame"),
    (dict(rows="d2-4x25", response="nope"), "unknown response mode 'nope'"),
    (dict(rows="d2-4x25", contacts="nope"), "unknown contact set 'nope'"),
])
def test_experiment_run_rejects_bad_arguments(kwargs, message):
    with pytest.raises(sphys.Error, match=message):
        sphys.experiment.run(**kwargs)


def test_experiment_table_is_table_1_beside_the_paper(full_run):
    table = sphys.experiment.table(full_run)
    assert isinstance(table, pandas.DataFrame)
    assert list(table.index) == ROW_IDS and table.index.name == "row"
    assert list(table.columns) == [
        "contacts_per_frame", "paper_contacts_per_frame", "fps", "paper_fps", "frame_time_sd_ms",
        "paper_frame_time_sd_ms", "detection_share_percent", "response_share_percent",
        "bodies_below_plane"]
    for result, paper in zip(full_run, PAPER_TABLE_1):
        row = table.loc[result.row]
        summary = result.summary()
        assert row["contacts_per_frame"] == summary["contacts_per_frame"]
        assert row["fps"] == summary["fps"]
        assert row["frame_time_sd_ms"] == summary["frame_time_sd_ms"]
        assert row["detection_share_percent"] == summary["detection_share_percent"]
        assert row["response_share_percent"] == summary["response_share_percent"]
        assert (row["paper_contacts_per_frame"], row["paper_fps"],
                row["paper_frame_time_sd_ms"]) == paper[4:]
        assert row["bodies_below_plane"] == DOCUMENTED_RUN[result.row][1]


def test_experiment_table_of_no_rows_is_empty():
    table = sphys.experiment.table([])
    assert isinstance(table, pandas.DataFrame) and len(table) == 0
    assert table.index.name == "row" and "paper_fps" in table.columns


def test_experiment_statistics_frame_is_ours_beside_the_papers(full_run):
    frame = sphys.experiment.statistics(full_run)
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.index) == list(PAPER_STATISTICS) and frame.index.name == "statistic"
    assert list(frame.columns) == ["ours", "paper"]
    ours = sphys.experiment_statistics(full_run)
    for name in PAPER_STATISTICS:
        assert frame.loc[name, "paper"] == PAPER_STATISTICS[name]
        assert frame.loc[name, "ours"] == ours[name]
