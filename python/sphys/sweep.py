"""Sweeps: a grid of scenes x settings x seeds run as independent simulations on Dask distributed.

    import sphys.sweep
    if __name__ == "__main__":          # Dask's workers start by spawning: keep the guard
        result = sphys.sweep.sweep(sphys.sweep.table1_scenes(),
                                   settings=[{"response": "paper"}, {"response": "plausible"}],
                                   frames=200, out="out/sweep")
        print(result.table())

Each run builds its scene's world on a worker and steps it alone on one thread, so its figures
are those of the same simulation run by itself (Simulation.run), bit for bit; only the times
differ. A run that fails is reported with its parameters and error, never dropped. Without a
client or a scheduler address the sweep starts a LocalCluster on this machine.

Command line: python3 -m sphys.sweep --help
"""

import argparse
import csv
import hashlib
import itertools
import json
import numbers
import os
import sys
import tempfile
import traceback

from . import _sphys

#: Summary figures that measure time: they differ from run to run, the others never do.
TIMING_KEYS = ("wall_s", "steps_per_s", "step_ms", "time_share_percent", "serial_share_percent")


def table1_scenes():
    """The eight rows of the paper's Table 1 as sweep scenes: the stacks:SxN preset at the row's
    sphere-tree depth, labelled with the row's id ("d2-4x25")."""
    return [
        {"scene": f"stacks:{row['stacks']}x{row['per_stack']}", "depth": row["depth"],
         "label": row["id"]}
        for row in _sphys.paper_table()
    ]


def _whole(value):
    """True for a whole number (an int or a numpy integer), not for a bool."""
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _scene_entry(scene):
    if isinstance(scene, str):
        return {"scene": scene, "depth": None, "label": scene}
    if isinstance(scene, dict) and "scene" in scene:
        unknown = set(scene) - {"scene", "depth", "label"}
        if unknown:
            raise _sphys.Error(f"sweep: a scene entry takes scene, depth and label, not {sorted(unknown)}")
        spec = scene["scene"]
        if not isinstance(spec, (str, dict)):
            raise _sphys.Error("sweep: a scene entry's scene is a preset or file name, or a dict of "
                               f"the scene-file format, got {spec!r}")
        depth = scene.get("depth")
        if depth is not None and not _whole(depth):
            raise _sphys.Error(f"sweep: depth must be a whole number of levels, got {depth!r}")
        label = scene.get("label", spec if isinstance(spec, str) else "inline scene")
        return {"scene": spec, "depth": None if depth is None else int(depth), "label": label}
    raise _sphys.Error(f"sweep: a scene is a preset or file name, or a dict with 'scene', got {scene!r}")


def grid(scenes, settings=({},), seeds=(None,), frames=None):
    """The runs of a sweep, in order: every scene with every settings dict and every seed. Each
    run is a dict of its parameters: run (its number), label, scene, depth, settings, seed,
    frames. A scene is a preset or file name, or a dict {"scene": ..., "depth": ..., "label":
    ...} whose scene is a name or a dict of the scene-file format (docs/scenes.md; its relative
    mesh paths resolve against the worker's working folder)."""
    if isinstance(scenes, (str, dict)):
        scenes = [scenes]
    settings = list(settings) or [{}]
    for i, variant in enumerate(settings):
        if not isinstance(variant, dict):
            raise _sphys.Error(f"sweep: settings[{i}] must be a dict of world settings, got {variant!r}")
    seeds = list(seeds) or [None]
    for seed in seeds:
        if seed is not None and (not _whole(seed) or seed < 0):
            raise _sphys.Error(f"sweep: a seed is a whole number of at least 0 or None, got {seed!r}")
    seeds = [None if seed is None else int(seed) for seed in seeds]
    if frames is not None and (not _whole(frames) or frames < 1):
        raise _sphys.Error(f"sweep: frames must be a whole number of at least 1, got {frames!r}")
    frames = None if frames is None else int(frames)
    runs = []
    for scene, variant, seed in itertools.product(scenes, settings, seeds):
        entry = _scene_entry(scene)
        runs.append({"run": len(runs), "label": entry["label"], "scene": entry["scene"],
                     "depth": entry["depth"], "settings": dict(variant), "seed": seed,
                     "frames": frames})
    return runs


def run_one(run):
    """One run of a sweep on this process: its scene built and stepped to the end on one thread.
    Returns the run's parameters with the figures of `sphys simulate --json` (Simulation.run)
    and a SHA-256 of the bodies' final poses; a failure returns the parameters with status
    "failed" and the error instead of raising, so that a sweep reports it."""
    record = dict(run)
    try:
        if isinstance(run["scene"], dict):
            if run["seed"] is not None:
                raise _sphys.Error("seed: only the stacks:SxN presets take a seed, not an inline scene")
            scene = _sphys.Scene.from_dict(run["scene"])
        else:
            scene = _sphys.load_scene(run["scene"], seed=run["seed"])
        if run["frames"] is not None:
            scene.frames = run["frames"]
        if run["settings"]:
            scene.set_settings(run["settings"])
        simulation = _sphys.Simulation(scene, depth=run["depth"], threads=1)
        summary = simulation.run()
        record["status"] = "ok"
        record["error"] = None
        record["summary"] = summary
        record["final_poses_sha256"] = hashlib.sha256(simulation.poses().tobytes()).hexdigest()
    except Exception as error:  # noqa: BLE001  (every failure is the sweep's to report)
        record["status"] = "failed"
        record["error_type"] = type(error).__name__
        record["error"] = str(error)
        if not isinstance(error, _sphys.Error):
            record["traceback"] = traceback.format_exc()
    return record


def deterministic(summary):
    """A run's summary without its timings: what must be the same bit for bit on any machine."""
    return {key: value for key, value in summary.items() if key not in TIMING_KEYS}


def _flatten(prefix, value, out):
    if isinstance(value, dict):
        for key, item in value.items():
            _flatten(f"{prefix}.{key}" if prefix else key, item, out)
    else:
        out[prefix] = value


class SweepResult:
    """The runs of a sweep in grid order, each a dict: its parameters, status ("ok" or "failed"),
    error, summary and final_poses_sha256."""

    def __init__(self, runs):
        """runs: the run dicts, in grid order."""
        self.runs = runs

    @property
    def failed(self):
        """The runs that failed, with their parameters and error."""
        return [run for run in self.runs if run["status"] != "ok"]

    def rows(self):
        """One flat dict per run, for tables: its parameters (settings and an inline scene as
        JSON text), status, error and poses' hash, then the summary's figures with nested keys
        dotted ("contacts_per_frame.mean"); summary keys that name a parameter ("scene",
        "frames": what the run's scene was called and how many frames it ran) are prefixed
        "summary."."""
        rows = []
        for run in self.runs:
            scene = run["scene"]
            row = {"run": run["run"], "label": run["label"],
                   "scene": json.dumps(scene, sort_keys=True) if isinstance(scene, dict) else scene,
                   "depth": run["depth"], "seed": run["seed"], "frames": run["frames"],
                   "settings": json.dumps(run["settings"], sort_keys=True),
                   "status": run["status"], "error_type": run.get("error_type"),
                   "error": run["error"],
                   "final_poses_sha256": run.get("final_poses_sha256")}
            figures = {}
            _flatten("", run.get("summary", {}), figures)
            for key, value in figures.items():
                row[f"summary.{key}" if key in row else key] = value
            rows.append(row)
        return rows

    def table(self):
        """rows() as a pandas DataFrame indexed by run when pandas is installed, else the list."""
        try:
            import pandas
        except ImportError:
            return self.rows()
        return pandas.DataFrame(self.rows()).set_index("run")

    def write(self, folder):
        """Writes runs.json (every run whole) and runs.csv (rows()) into `folder`, each file whole
        or not at all. Returns their paths."""
        os.makedirs(folder, exist_ok=True)
        rows = self.rows()
        columns = list(dict.fromkeys(key for row in rows for key in row))
        paths = []
        for name, write in (("runs.json", lambda f: json.dump(self.runs, f, indent=2)),
                            ("runs.csv", lambda f: _write_csv(f, columns, rows))):
            path = os.path.join(folder, name)
            handle, temporary = tempfile.mkstemp(dir=folder, prefix=f".{name}.", suffix=".tmp")
            try:
                with os.fdopen(handle, "w", newline="") as f:
                    write(f)
                os.replace(temporary, path)
            except BaseException:
                os.unlink(temporary)
                raise
            paths.append(path)
        return paths


def _write_csv(f, columns, rows):
    writer = csv.DictWriter(f, fieldnames=columns)
    writer.writeheader()
    writer.writerows(rows)


#: The parameters every run dict has (grid() gives them).
RUN_KEYS = ("run", "label", "scene", "depth", "settings", "seed", "frames")


def sweep(scenes, settings=({},), seeds=(None,), *, frames=None, client=None, scheduler=None,
          n_workers=2, out=None, progress=True):
    """Runs every scene with every settings dict and every seed on Dask distributed and gathers
    the results in a SweepResult (written as runs.json and runs.csv into `out` when given):
    run_sweep(grid(scenes, settings, seeds, frames), ...).

    scenes: preset or file names, or dicts {"scene": ..., "depth": levels, "label": ...}
    (table1_scenes() gives the paper's eight rows). settings: dicts of world settings as World()
    takes them. seeds: yaw-angle seeds of the stacks presets (None: the preset's own). frames:
    frames per run (None: the scene's). client: a distributed.Client to use; scheduler: the
    address of a running scheduler ("tcp://host:8786"); neither: a LocalCluster of n_workers
    single-threaded worker processes, closed at the end. progress: a line per finished run on
    stderr.
    """
    return run_sweep(grid(scenes, settings, seeds, frames), client=client, scheduler=scheduler,
                     n_workers=n_workers, out=out, progress=progress)


def run_sweep(runs, *, client=None, scheduler=None, n_workers=2, out=None, progress=True):
    """Runs a list of runs as grid() makes them (grids joined: grid(a) + grid(b, ...)) on Dask
    distributed, as sweep() does; the runs are numbered by their place in the list."""
    from distributed import Client, LocalCluster, as_completed

    runs = list(runs)
    for i, run in enumerate(runs):
        if not isinstance(run, dict) or set(RUN_KEYS) - set(run):
            raise _sphys.Error(f"sweep: runs[{i}] must be a dict with {', '.join(RUN_KEYS)} (as "
                               f"grid() makes them), got {run!r}")
    runs = [dict(run, run=i) for i, run in enumerate(runs)]
    if client is None and scheduler is None and (not _whole(n_workers) or n_workers < 1):
        raise _sphys.Error(f"sweep: n_workers must be at least 1, got {n_workers!r}")
    if out is not None:
        try:
            os.makedirs(out, exist_ok=True)
        except OSError as error:
            raise _sphys.Error(f"sweep: cannot create the output folder {out}: {error}") from None
    cluster = None
    own_client = client is None
    if own_client:
        if scheduler is not None:
            client = Client(scheduler)
        else:
            cluster = LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
    try:
        futures = {client.submit(run_one, run, pure=False): run for run in runs}
        results = {}
        for done, future in enumerate(as_completed(futures), start=1):
            run = futures[future]
            try:
                record = future.result()
            except Exception as error:  # noqa: BLE001  (a worker lost, a task killed)
                record = dict(run, status="failed", error_type=type(error).__name__,
                              error=str(error))
            results[run["run"]] = record
            if progress:
                failed = sum(1 for r in results.values() if r["status"] != "ok")
                print(f"sweep: {done}/{len(runs)} runs done ({failed} failed): run {run['run']} "
                      f"{run['label']} {record['status']}", file=sys.stderr, flush=True)
    finally:
        if own_client:
            client.close()
            if cluster is not None:
                cluster.close()
    result = SweepResult([results[run["run"]] for run in runs])
    if out is not None:
        result.write(out)
    return result


def _settings_argument(text):
    try:
        value = json.loads(text)
    except json.JSONDecodeError as error:
        raise argparse.ArgumentTypeError(f"not JSON: {error}") from None
    if not isinstance(value, dict):
        raise argparse.ArgumentTypeError("must be a JSON object of world settings")
    return value


def main(argv=None):
    """`python3 -m sphys.sweep`: the command line's arguments (argv, else sys.argv's) as sweep()
    takes them; returns the exit status."""
    parser = argparse.ArgumentParser(
        prog="python3 -m sphys.sweep",
        description="Run a grid of scenes x settings x seeds on Dask distributed; write runs.csv "
                    "and runs.json.")
    parser.add_argument("scenes", nargs="*", help="presets (stacks:4x50) or scene files")
    parser.add_argument("--table1", action="store_true", help="add the paper's eight Table 1 rows")
    parser.add_argument("--depth", type=int, help="sphere-tree depth of the scenes named above")
    parser.add_argument("--settings", type=_settings_argument, nargs="+", default=[{}],
                        metavar="JSON", help='world settings variants, e.g. \'{"response": "paper"}\'')
    parser.add_argument("--seeds", type=int, nargs="+", default=[None], help="yaw seeds of presets")
    parser.add_argument("--frames", type=int, help="frames per run (default: the scene's)")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster workers (default 2)")
    parser.add_argument("--out", default="out/sweep", help="folder for runs.csv and runs.json")
    args = parser.parse_args(argv)
    scenes = [{"scene": s, "depth": args.depth, "label": s} for s in args.scenes]
    if args.table1:
        scenes += table1_scenes()
    if not scenes:
        parser.error("give scenes, --table1, or both")
    if args.workers < 1:
        parser.error(f"--workers must be at least 1, got {args.workers}")
    try:
        result = sweep(scenes, args.settings, args.seeds, frames=args.frames,
                       scheduler=args.scheduler, n_workers=args.workers, out=args.out)
    except _sphys.Error as error:
        print(f"sphys: error: {error}", file=sys.stderr)
        return 2
    for run in result.failed:
        print(f"sweep: run {run['run']} failed ({run['label']}, settings {run['settings']}, "
              f"seed {run['seed']}): {run['error_type']}: {run['error']}", file=sys.stderr)
    print(f"sweep: {len(result.runs) - len(result.failed)} of {len(result.runs)} runs ok; "
          f"wrote {args.out}/runs.csv and runs.json")
    if not result.failed:
        return 0
    # Bad input (sphys.Error: a missing mesh, a setting out of range) exits 2, as the command
    # line does; anything else (a worker lost) 1.
    return 2 if all(run["error_type"] == "Error" for run in result.failed) else 1


if __name__ == "__main__":
    sys.exit(main())
