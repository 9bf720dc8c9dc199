"""bench/plot_results.py: a scene's history from the benchmark CSVs, checked against hand-made
tables whose points are known, and against the committed results."""
import csv
import datetime
import importlib.util
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPEC = importlib.util.spec_from_file_location("plot_results", ROOT / "bench" / "plot_results.py")
plot_results = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(plot_results)

COLUMNS = ["date", "cpu", "layout", "depth", "engine", "mean_ms", "warnings"]


def write(path, rows):
    with open(path, "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(COLUMNS)
        writer.writerows(rows)
    return path


@pytest.fixture
def results(tmp_path):
    write(tmp_path / "later.csv", [
        ["2026-11-25", "AMD EPYC", "100x10", "2", "sphys", "2.5", ""],
        ["2026-11-25", "AMD EPYC", "100x10", "2", "ode", "nan", "failed: out of memory"],
        ["2026-11-25", "AMD EPYC", "4x25", "2", "sphys", "0.4", ""],
    ])
    write(tmp_path / "earlier.csv", [
        ["2026-11-20", "AMD EPYC", "100x10", "2", "sphys", "3.5", ""],
        ["2026-11-20", "AMD EPYC", "100x10", "2", "ode", "9.0", ""],
        ["2026-11-20", "AMD EPYC", "100x10", "3", "sphys", "7.0", ""],
    ])
    return tmp_path


def test_each_engine_gets_its_runs_of_the_scene_in_date_order(results):
    files = plot_results.csv_files([str(results)])
    points = plot_results.history(files, "100x10", 2, "mean_ms", [])
    day = datetime.date.fromisoformat
    assert points == {"ode": [(day("2026-11-20"), 9.0)],  # the failed run left out
                      "sphys": [(day("2026-11-20"), 3.5), (day("2026-11-25"), 2.5)]}
    only = plot_results.history(files, "100x10", 2, "mean_ms", ["ode"])
    assert list(only) == ["ode"]


def test_the_plot_is_a_png(results, tmp_path, capsys):
    out = tmp_path / "history.png"
    assert plot_results.main([str(results), "--layout", "100x10", "--depth", "2",
                              "--out", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "sphys: 2 runs, 2026-11-20 to 2026-11-25" in capsys.readouterr().out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["earlier.csv", "history.png",
                                                          "later.csv"]


@pytest.mark.parametrize("rows, args, message", [
    (None, ["--layout", "9x9", "--depth", "2"], "--layout 9x9 --depth 2: no run measured"),
    (None, ["--layout", "100x10", "--depth", "2", "--column", "median_ms"],
     "not a sphys-compare results file: no column median_ms"),
    ([["2026-13-01", "AMD EPYC", "100x10", "2", "sphys", "1", ""]],
     ["--layout", "100x10", "--depth", "2"], "bad.csv:2: month must be in 1..12"),
    ([["2026-11-01", "AMD EPYC", "100x10", "2", "sphys", "fast", ""]],
     ["--layout", "100x10", "--depth", "2"], "bad.csv:2: could not convert string to float"),
])
def test_bad_input_exits_2_naming_it(results, tmp_path, capsys, rows, args, message):
    if rows is not None:
        write(results / "bad.csv", rows)
    out = tmp_path / "history.png"
    assert plot_results.main([str(results), *args, "--out", str(out)]) == 2
    assert message in capsys.readouterr().err
    assert not out.exists()


def test_a_missing_folder_exits_2(tmp_path, capsys):
    assert plot_results.main([str(tmp_path / "none"), "--layout", "1x1", "--depth", "2",
                              "--out", str(tmp_path / "h.png")]) == 2
    assert "none: no such file or folder" in capsys.readouterr().err


def test_every_committed_results_file_reads(tmp_path):
    """The committed CSVs (bench/results/<machine>/; a machine's folder may hold reports alone)
    all read: 1,000 bunnies at depth 2 have a history on this project's reference machine."""
    csvs = sorted((ROOT / "bench" / "results").glob("*/*.csv"))
    assert csvs
    for path in csvs:
        assert plot_results.read_rows(path, "mean_ms"), path
    points = plot_results.history(plot_results.csv_files([str(ROOT / "bench" / "results" /
                                                               "amd-epyc-2t")]),
                                  "100x10", 2, "mean_ms", ["sphys"])
    assert len(points["sphys"]) >= 2
