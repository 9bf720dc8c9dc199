"""The paper's evaluation (§5) from Python: run rows, then Table 1 and the statistics beside the
paper's, as pandas DataFrames when pandas is installed (lists of dicts otherwise)."""

from . import _sphys


def _frame(rows, index, columns):
    """A DataFrame indexed by `index` when pandas is there (empty, with its columns, for no
    rows), else the rows as they are."""
    try:
        import pandas
    except ImportError:
        return rows
    return pandas.DataFrame(rows, columns=columns).set_index(index)


TABLE_COLUMNS = ("row", "contacts_per_frame", "paper_contacts_per_frame", "fps", "paper_fps",
                 "frame_time_sd_ms", "paper_frame_time_sd_ms", "detection_share_percent",
                 "response_share_percent", "bodies_below_plane")


def run(rows=None, *, frames=880, ground="octree", response="paper", contacts=None, cache=True):
    """Runs rows of the experiment (ids such as "d2-4x25", as a list or one comma-separated
    string; all eight by default) one after the other in the paper's order, as `sphys
    experiment` does, and returns their RowResults."""
    if rows is not None and not isinstance(rows, str):
        rows = ",".join(rows)
    ids = _sphys.experiment_rows(rows)
    return [
        _sphys.run_experiment_row(row, frames=frames, ground=ground, response=response,
                                  contacts=contacts, cache=cache)
        for row in ids
    ]


def table(results):
    """Table 1: per row, our contacts per frame, FPS (physics only) and frame-time sd beside the
    paper's, with our detection and response shares of the frame time (%)."""
    paper = {row["id"]: row for row in _sphys.paper_table()}
    rows = []
    for result in results:
        ours = result.summary()
        published = paper.get(ours["id"], {})
        rows.append({
            "row": ours["id"],
            "contacts_per_frame": ours["contacts_per_frame"],
            "paper_contacts_per_frame": published.get("contacts_per_frame"),
            "fps": ours["fps"],
            "paper_fps": published.get("fps"),
            "frame_time_sd_ms": ours["frame_time_sd_ms"],
            "paper_frame_time_sd_ms": published.get("frame_time_sd_ms"),
            "detection_share_percent": ours["detection_share_percent"],
            "response_share_percent": ours["response_share_percent"],
            "bodies_below_plane": ours["bodies_below_plane"],
        })
    return _frame(rows, "row", TABLE_COLUMNS)


def statistics(results):
    """The §5 statistics of our rows beside the paper's: a row per statistic, columns "ours" and
    "paper"."""
    ours = _sphys.experiment_statistics(results)
    paper = _sphys.paper_statistics()
    rows = [{"statistic": name, "ours": value, "paper": paper[name]} for name, value in ours.items()]
    return _frame(rows, "statistic", ("statistic", "ours", "paper"))
