"""A scene's history across benchmark runs, as a PNG: one line per engine, each run's figure at
the date of its run, from the CSV files that sphys-compare writes beside its tables
(bench/results/<machine>/*.csv, docs/performance.md).

Usage:
  /usr/bin/python3 bench/plot_results.py FOLDER_OR_CSV... --layout 100x10 --depth 2
      [--column mean_ms] [--engines sphys,ode] --out history.png

Exit code 2, with the file or argument named, for a CSV that is not sphys-compare's, a column
it lacks, or a scene no run measured.
"""
import argparse
import csv
import datetime
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only: no display
import matplotlib.dates  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

# The columns every run's CSV has, whatever else it holds.
NEEDED = ("date", "layout", "depth", "engine")


class BadInput(Exception):
    pass


def csv_files(paths):
    files = []
    for path in map(pathlib.Path, paths):
        if path.is_dir():
            files += sorted(path.glob("*.csv"))
        elif path.is_file():
            files.append(path)
        else:
            raise BadInput(f"{path}: no such file or folder")
    if not files:
        raise BadInput(f"no CSV file in {', '.join(paths)}")
    return files


def read_rows(path, column):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [name for name in NEEDED + (column,) if name not in (reader.fieldnames or [])]
        if missing:
            raise BadInput(f"{path}: not a sphys-compare results file: no column "
                           f"{', '.join(missing)}")
        rows = []
        for line, row in enumerate(reader, start=2):
            try:
                date = datetime.date.fromisoformat(row["date"])
                value = float(row[column])
            except ValueError as error:
                raise BadInput(f"{path}:{line}: {error}") from None
            rows.append((date, row["layout"], row["depth"], row["engine"], value))
        return rows


def history(files, layout, depth, column, engines):
    """Per engine, its (date, value) points for the scene, in date order; failed runs left out."""
    points = {}
    for path in files:
        for date, row_layout, row_depth, engine, value in read_rows(path, column):
            if row_layout != layout or row_depth != str(depth) or math.isnan(value):
                continue
            if engines and engine not in engines:
                continue
            points.setdefault(engine, []).append((date, value))
    if not points:
        raise BadInput(f"--layout {layout} --depth {depth}: no run measured this scene"
                       + (f" with the engines {','.join(engines)}" if engines else ""))
    return {engine: sorted(series) for engine, series in sorted(points.items())}


def plot(points, layout, depth, column, out):
    figure, axes = plt.subplots(figsize=(8, 4.5))
    for engine, series in points.items():
        dates, values = zip(*series)
        axes.plot(dates, values, marker="o", label=engine)
    axes.set_title(f"{layout} bunnies' layout, depth {depth}")
    axes.set_ylabel(column)
    axes.set_xlabel("date of the run")
    axes.xaxis.set_major_formatter(matplotlib.dates.DateFormatter("%Y-%m-%d"))
    axes.grid(True, alpha=0.3)
    axes.legend()
    figure.autofmt_xdate()
    figure.tight_layout()
    # Whole or not at all: drawn into a temporary file beside the output, then renamed.
    out = pathlib.Path(out)
    partial = out.with_name(out.name + ".partial.png")
    try:
        figure.savefig(partial, format="png")
        partial.replace(out)
    finally:
        partial.unlink(missing_ok=True)
        plt.close(figure)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("inputs", nargs="+", help="CSV files, or folders of them")
    parser.add_argument("--layout", required=True, help="the scene's layout, SxN (e.g. 100x10)")
    parser.add_argument("--depth", required=True, type=int, help="the sphere-trees' depth")
    parser.add_argument("--column", default="mean_ms", help="the figure to plot (default mean_ms)")
    parser.add_argument("--engines", default="", help="only these engines, comma-separated")
    parser.add_argument("--out", required=True, help="the PNG to write")
    args = parser.parse_args(argv)
    engines = [e for e in args.engines.split(",") if e]
    try:
        points = history(csv_files(args.inputs), args.layout, args.depth, args.column, engines)
        plot(points, args.layout, args.depth, args.column, args.out)
    except (BadInput, OSError) as error:
        print(f"plot_results.py: error: {error}", file=sys.stderr)
        return 2
    for engine, series in points.items():
        print(f"{engine}: {len(series)} runs, {series[0][0]} to {series[-1][0]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
