"""sphys-compare --out X.md also writes X.csv: one row per engine and scene, whose figures are
the tables' and whose columns say how and where they were measured.

Usage: check_compare_csv.py PATH_TO_SPHYS_COMPARE
"""
import csv
import datetime
import pathlib
import subprocess
import sys
import tempfile


def table_rows(markdown):
    """The Markdown tables' rows, as lists of cells, by scene heading."""
    rows = {}
    scene = None
    for line in markdown.splitlines():
        if line.startswith("### "):
            scene = line[4:].split(",")[0] + "," + line.split(",")[1].strip()
        elif line.startswith("| ") and not line.startswith("| engine") and "---" not in line:
            cells = [cell.strip() for cell in line.strip("|").split("|")]
            rows[(scene, cells[0])] = cells
    return rows


def main(compare):
    with tempfile.TemporaryDirectory() as folder:
        out = pathlib.Path(folder) / "results.md"
        subprocess.run([compare, "--layouts", "1x3,1x2", "--depths", "2", "--engines",
                        "sphys,ode", "--frames", "20", "--out", str(out)],
                       check=True, capture_output=True)
        with open(out.with_suffix(".csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        tables = table_rows(out.read_text())
    assert len(rows) == 4, rows
    assert [(r["layout"], r["engine"]) for r in rows] == [
        ("1x3", "sphys"), ("1x3", "ode"), ("1x2", "sphys"), ("1x2", "ode")], rows
    today = datetime.datetime.now(datetime.timezone.utc).date()
    for row in rows:
        assert abs((datetime.date.fromisoformat(row["date"]) - today).days) <= 1, row["date"]
        assert row["command"].startswith("sphys-compare --layouts 1x3,1x2"), row["command"]
        assert row["cpu"] and int(row["hardware_threads"]) >= 1, row
        assert "lanes" in row["build"], row["build"]
        assert row["depth"] == "2" and row["frames"] == "20" and row["runs"] == "1", row
        assert row["reference_engine"] == "sphys", row
        cells = tables[(f"{row['layout']},depth 2", row["engine"])]
        # The same figures as the table's, which rounds them.
        assert f"{float(row['median_ms']):.3f}" == cells[2], (row, cells)
        assert f"{float(row['mean_ms']):.3f}" == cells[5], (row, cells)
        assert f"{float(row['mean_over_reference']):.2f}" == cells[6], (row, cells)
        assert f"{float(row['deepest_m']):.4f}" == cells[9], (row, cells)
        assert f"{row['moving_at_end']} of {row['bodies']}" == cells[13], (row, cells)
        assert int(row["bodies"]) == int(row["layout"][2]), row
    sphys_rows = [r for r in rows if r["engine"] == "sphys"]
    assert all(float(r["median_over_reference"]) == 1.0 for r in sphys_rows), sphys_rows
    print("ok:", len(rows), "rows")


if __name__ == "__main__":
    main(sys.argv[1])
