"""Feature tables: per-capture CSV, JSON lines, run provenance, and the folder summary. Writes are atomic."""

import csv
import json
import math
import os
from dataclasses import asdict
from pathlib import Path

from mdpipe import __version__
from mdpipe.outputs import create_temporary, publish

JSON_KEYS = ("file", "range_m", "class", "doppler_bw_hz", "doppler_bw_mps", "chopping_freq_hz", "rotation_rate_hz",
             "rotation_period_s", "blade_length_m", "body_velocity_mps", "wingbeat_freq_hz", "aliased", "snr_db",
             "notes")
ERROR_SUFFIX = ".error.txt"
FEATURES_SUFFIX = ".features.csv"


def atomic_write(path, write):
    """Call ``write(tmp_path)`` and move the result to ``path`` only when it succeeded.

    The temporary file is new and exclusive (:func:`mdpipe.outputs.create_temporary`); the result
    has the mode the umask gives.
    """
    fd, tmp = create_temporary(path)
    os.close(fd)
    try:
        write(tmp)
        publish(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


def _clean(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if hasattr(value, "item"):
        return _clean(value.item())
    return value


def finite_json(value):
    """``value`` (nested dicts, lists, tuples, numpy scalars) with NaN and +-inf as None: strict JSON."""
    if isinstance(value, dict):
        return {key: finite_json(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite_json(item) for item in value]
    return _clean(value)


def json_record(row):
    """The row as a JSON-ready dict: the documented keys first, then the rest; NaN/inf become null."""
    ordered = {key: _clean(row.get(key)) for key in JSON_KEYS}
    ordered.update({k: _clean(v) for k, v in row.items() if k not in ordered})
    return ordered


def write_features_csv(rows, path):
    """One row per target (stdlib csv: pandas would add 0.3 s of import to every capture)."""
    records = [json_record(r) for r in rows]

    def write(tmp):
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            writer = csv.DictWriter(fh, fieldnames=list(records[0]))
            writer.writeheader()
            writer.writerows(records)
    atomic_write(path, write)


def write_run_json(path, *, capture, params, layout, radar):
    """Provenance: mdpipe version, processing parameters, input file and what was read from it."""
    record = {"mdpipe_version": __version__, "capture": str(capture), "layout": layout,
              "process_params": asdict(params), "radar": {k: _clean(v) for k, v in asdict(radar).items()}}
    atomic_write(path, lambda tmp: Path(tmp).write_text(json.dumps(record, indent=1, default=str)))


def write_error(path, capture, message):
    atomic_write(path, lambda tmp: Path(tmp).write_text(f"{capture}\t{message}\n"))


def summarize(folder):
    """All ``*.features.csv`` under ``folder`` in one table, and the captures that failed.

    Returns
    -------
    features : pandas.DataFrame
    errors : pandas.DataFrame with columns file, error
    """
    import pandas as pd

    folder = Path(folder)
    tables = [pd.read_csv(p) for p in sorted(folder.rglob(f"*{FEATURES_SUFFIX}")) if p.name != "features.csv"]
    features = pd.concat(tables, ignore_index=True) if tables else pd.DataFrame(columns=list(JSON_KEYS))
    errors = [p.read_text().rstrip("\n").split("\t", 1) for p in sorted(folder.rglob(f"*{ERROR_SUFFIX}"))]
    return features, pd.DataFrame(errors, columns=["file", "error"])
