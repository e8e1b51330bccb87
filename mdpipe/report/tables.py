"""Feature tables: per-capture CSV, JSON lines, run provenance, the folder summary, and publishing.

Every file appears only when complete (written under a temporary name, then renamed) and gets the
mode the umask gives (0644 under umask 022). A capture's outputs are published together: written
into a hidden temporary folder beside their final folder, which is then renamed into place.
"""

import contextlib
import csv
import errno
import io
import json
import math
import os
import re
import secrets
import shutil
import signal
import tempfile
from dataclasses import asdict
from pathlib import Path

from mdpipe import __version__
from mdpipe.outputs import create_temporary, file_mode

JSON_KEYS = ("file", "range_m", "class", "doppler_bw_hz", "doppler_bw_mps", "chopping_freq_hz", "rotation_rate_hz",
             "rotation_period_s", "blade_length_m", "body_velocity_mps", "wingbeat_freq_hz", "aliased", "snr_db",
             "notes")
ERROR_SUFFIX = ".error.txt"
FEATURES_SUFFIX = ".features.csv"
RUN_SUFFIX = ".run.json"
SUMMARY_TABLE = "features.csv"
SUMMARY_PNG = "summary.png"
PARTIAL_PREFIX = ".mdpipe-partial-"  # temporary folders and files; removed by the next run on the same folder


def atomic_write(path, write):
    """Call ``write(tmp_path)`` and move the result to ``path`` only when it succeeded.

    The temporary file is new and exclusive (:func:`mdpipe.outputs.create_temporary`, named with
    ``PARTIAL_PREFIX`` so :func:`remove_partials` finds it after a kill); the result has the mode the
    umask gives.
    """
    fd, tmp = create_temporary(path, prefix=PARTIAL_PREFIX)
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


STOP_SIGNALS = {signal.SIGINT, signal.SIGTERM}


@contextlib.contextmanager
def stops_deferred():
    """SIGINT and SIGTERM held back in this thread (delivered on exit): a rename pair is never cut in two,
    a pool's worker never meets them before its initializer has set them up, a helper thread never takes
    them."""
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, STOP_SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


MARKER = ".mdpipe-outputs"  # in every folder :func:`publish` writes; a folder without it is never replaced


class NotOursError(OSError):
    """A folder in the way of a capture's outputs that mdpipe did not write: left alone."""


def _trash_name(folder):
    return folder.with_name(f"{PARTIAL_PREFIX}{folder.name}.old.{secrets.token_hex(4)}")


def _set_aside(folder):
    """Rename mdpipe's output ``folder`` to a temporary name and return it; None when there is none.

    Raises :class:`NotOursError` when ``folder`` is anything but a folder holding :data:`MARKER`.
    """
    if not os.path.lexists(folder):
        return None
    if folder.is_symlink() or not folder.is_dir() or not (folder / MARKER).is_file():
        raise NotOursError(f"{folder} is in the way and was not written by mdpipe (left as it is); "
                           "choose another --out")
    trash = _trash_name(folder)
    try:
        os.rename(folder, trash)
    except FileNotFoundError:
        return None
    return trash


def temporary_folder(folder):
    """A new hidden folder beside ``folder`` (its parents made), named so that :func:`remove_partials` removes
    it after a kill."""
    folder = Path(folder)
    folder.parent.mkdir(parents=True, exist_ok=True)
    return Path(tempfile.mkdtemp(prefix=f"{PARTIAL_PREFIX}{folder.name}.", dir=folder.parent))


def publish(folder, write):
    """Publish one capture's outputs: ``write(tmp_folder)`` fills a hidden temporary folder, which then replaces
    ``folder`` (its old content, stale or not, goes). Returns the names of the files published.

    A reader sees the old folder, no folder (for the instant between two renames; SIGINT and SIGTERM wait for
    the second), or the new one: never a mix. A failure in ``write`` leaves ``folder`` as it was. Only a folder
    that mdpipe published (it holds :data:`MARKER`) is ever replaced.
    """
    folder = Path(folder)
    tmp = temporary_folder(folder)
    trash = None
    try:
        os.chmod(tmp, file_mode(folder=True))  # as a file's: the umask of now
        write(tmp)
        names = sorted(p.name for p in tmp.iterdir())
        with open(tmp / MARKER, "w", encoding="utf-8") as fh:
            fh.write(f"mdpipe {__version__}\n")
        with stops_deferred():
            while True:
                try:
                    os.rename(tmp, folder)
                    break
                except OSError as exc:
                    if exc.errno not in (errno.EEXIST, errno.ENOTEMPTY, errno.ENOTDIR, errno.EISDIR):
                        raise
                trash = _set_aside(folder) or trash
        return names
    finally:
        for leftover in (tmp, trash):
            if leftover is not None and leftover.exists():
                shutil.rmtree(leftover, ignore_errors=True)


def unpublish(folder):
    """Remove mdpipe's output ``folder`` (renamed aside first, so it never shows half-deleted); anything else
    in its place is left alone."""
    trash = _set_aside(Path(folder))
    if trash is not None:
        shutil.rmtree(trash, ignore_errors=True)


def remove_partials(paths):
    """Delete what interrupted or killed runs left beside ``paths`` (output folders and files): the temporary
    names :func:`publish` and :func:`atomic_write` give them. Each folder holding ``paths`` is listed once."""
    wanted = {}
    for path in map(Path, paths):
        wanted.setdefault(path.parent, set()).add(path.name)
    for parent, names in wanted.items():
        try:
            entries = list(os.scandir(parent))
        except (FileNotFoundError, NotADirectoryError):
            continue
        for entry in entries:
            if not entry.name.startswith(PARTIAL_PREFIX):
                continue
            owner = entry.name[len(PARTIAL_PREFIX):].rsplit(".", 1)[0]  # less the random suffix (no dots)
            if owner not in names and owner.endswith(".old"):  # a replaced folder set aside
                owner = owner[:-len(".old")]
            if owner not in names:
                continue
            if entry.is_dir(follow_symlinks=False):
                shutil.rmtree(entry.path, ignore_errors=True)
            else:
                with contextlib.suppress(FileNotFoundError):
                    os.remove(entry.path)


SIGNIFICANT_DIGITS = 15  # every double holds 15: 1 / 40e-6 = 24999.999999999996 is written 25000.0


def _clean(value):
    if isinstance(value, float):
        return float(f"{value:.{SIGNIFICANT_DIGITS}g}") if math.isfinite(value) else None
    if hasattr(value, "item"):
        item = value.item()
        return _clean(item if type(item) is not type(value) else float(item))  # a long double's item is itself
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
    write_table(path, list(records[0]), records)


def write_run_json(path, *, capture, params, layout, radar):
    """Provenance: mdpipe version, processing parameters, input file (as given, and resolved) and what was read from
    it."""
    record = {"mdpipe_version": __version__, "capture": str(capture), "input": str(Path(capture).resolve()),
              "layout": layout,
              "process_params": asdict(params), "radar": {k: _clean(v) for k, v in asdict(radar).items()}}
    atomic_write(path, lambda tmp: Path(tmp).write_text(json.dumps(record, indent=1, default=str)))


LINE_ESCAPES = str.maketrans({"\t": "\\t", "\n": "\\n", "\r": "\\r"})


def write_error(path, capture, message, traceback_text=None):
    """``capture<TAB>message`` on the first line (what :func:`summarize` reads; a tab, newline or return in either
    written as its escape), then the traceback if any."""
    first = "\t".join(str(part).translate(LINE_ESCAPES) for part in (capture, message))
    text = f"{first}\n" + (f"\n{traceback_text}" if traceback_text else "")
    atomic_write(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))


def gather(folder, *, only=None):
    """Every ``*.features.csv`` under ``folder`` (outside temporary folders), and the captures that failed.

    The cells stay the text their per-capture CSVs hold, so types survive the merge by construction (a bool
    stays ``True``, an integer ``0``; a null stays empty). Uses the csv module only: pandas would add 0.8 s.
    ``only``: the capture folders to read (a batch's own; :func:`folders_beyond` counts the others). A table that
    cannot be read (not UTF-8, a field over the csv module's limit) counts as a failed capture, named.

    Returns
    -------
    columns : list of str
        The union of the tables' columns, in order of appearance.
    rows : list of dict
        One per target row, column -> text ("" where null or absent).
    errors : list of (str, str)
        (capture, one-line error) per ``*.error.txt`` and unreadable table.
    """
    columns, rows, errors = {}, [], []
    tables, failures = _published(folder, FEATURES_SUFFIX, ERROR_SUFFIX)
    kept = None if only is None else {Path(f) for f in only}
    for path in tables:
        if kept is not None and Path(path).parent not in kept:
            continue
        try:
            with open(path, newline="", encoding="utf-8") as fh:
                reader = csv.DictReader(fh)
                found = list(reader)
                columns.update(dict.fromkeys(reader.fieldnames or ()))
        except (csv.Error, UnicodeDecodeError, OSError) as exc:
            errors.append((str(path), f"{path}: its table cannot be read ({' '.join(str(exc).split())}); "
                                      "process its capture again"))
            continue
        rows.extend(found)
    for path in failures:
        if kept is not None and Path(path).parent not in kept:
            continue
        with open(path, encoding="utf-8", errors="replace") as fh:
            errors.append(tuple((fh.readline().rstrip("\n").split("\t", 1) + [""])[:2]))
    return list(columns), rows, errors


def published_input(folder):
    """The capture whose outputs ``folder`` holds, as its run record names it (resolved), or None."""
    for record in sorted(Path(folder).glob("*" + RUN_SUFFIX)):
        try:
            found = json.loads(record.read_text(encoding="utf-8")).get("input")
        except (OSError, ValueError, AttributeError):
            continue
        if isinstance(found, str):
            return found
    return None


def folders_beyond(folder, only):
    """How many capture folders under ``folder`` hold tables or errors but are not among ``only``."""
    tables, failures = _published(folder, FEATURES_SUFFIX, ERROR_SUFFIX)
    return len({Path(path).parent for path in list(tables) + list(failures)} - {Path(f) for f in only})


def gathered_rows(folder, replaced, *, only=None):
    """The rows :func:`gather` would read from ``folder`` (``only`` those capture folders) once the feature tables at
    the paths of ``replaced`` (path -> the rows :func:`write_features_csv` writes there) are written: those tables are
    taken from ``replaced``, the others read as they stand."""
    rows = []
    kept = None if only is None else {Path(f) for f in only}
    for path in sorted(set(_published(folder, FEATURES_SUFFIX)[0]) | set(replaced)):
        if kept is not None and Path(path).parent not in kept:
            continue
        if path in replaced:
            rows.extend(text_rows(replaced[path]))
            continue
        with contextlib.suppress(FileNotFoundError), open(path, newline="", encoding="utf-8") as fh:
            rows.extend(csv.DictReader(fh))
    return rows


def text_rows(rows):
    """``rows`` as :func:`gather` reads them back from the table :func:`write_features_csv` writes."""
    records = [json_record(r) for r in rows]
    buffer = io.StringIO(newline="")
    _write_csv(buffer, list(records[0]), records)
    buffer.seek(0)
    return list(csv.DictReader(buffer))


def _write_csv(fh, columns, rows):
    writer = csv.DictWriter(fh, fieldnames=columns, restval="")
    writer.writeheader()
    writer.writerows(rows)


def write_table(path, columns, rows):
    """Write text ``rows`` (dicts) under ``columns`` as one CSV, missing cells empty."""
    def write(tmp):
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            _write_csv(fh, columns, rows)
    atomic_write(path, write)


_INTEGER = re.compile(r"-?\d+")


def _typed(column):
    """A column of text as the type its per-capture CSVs wrote: Python's csv writes a bool as True/False, an
    int as digits and a float with a point or an exponent; empty cells are null."""
    import pandas as pd

    present = column.dropna()
    if len(present) and present.isin(("True", "False")).all():
        return column.map({"True": True, "False": False}).astype("boolean")
    if len(present) and present.str.fullmatch(_INTEGER).all():
        return pd.to_numeric(column).astype("Int64")
    try:
        return pd.to_numeric(column)
    except (ValueError, TypeError):
        return column


def frame(columns, rows):
    """The merged rows of :func:`gather` as a pandas DataFrame with their types: booleans (``aliased``) as
    booleans, integers (``target``, ``range_bin``) as integers, nulls where a capture had none."""
    import pandas as pd

    table = pd.DataFrame(rows, columns=columns, dtype=object)
    return table.where(table.notna() & table.ne(""), None).apply(_typed)


def _published(folder, *suffixes):
    """Per suffix, the files under ``folder`` whose names end in it, outside temporary folders, sorted (one
    walk of the tree for all)."""
    found = [[] for _ in suffixes]
    for root, dirs, files in os.walk(folder):
        dirs[:] = [d for d in dirs if not d.startswith(PARTIAL_PREFIX)]
        for name in files:
            if name.startswith(PARTIAL_PREFIX):
                continue
            for i, suffix in enumerate(suffixes):
                if name.endswith(suffix):
                    found[i].append(Path(root) / name)
                    break
    return [sorted(paths) for paths in found]


MAX_DECIMALS = 6


def to_resolution(value, resolution):
    """``value`` as text with the decimals its ``resolution`` supports (0.0007981 at 0.094 -> ``0.00``); four
    significant digits when the resolution is finer than 1e-6 or unknown."""
    if not (math.isfinite(resolution) and resolution > 0) or resolution < 10 ** -MAX_DECIMALS:
        return f"{value:.4g}"
    text = f"{value:.{max(0, -math.floor(math.log10(resolution)))}f}"
    return text.lstrip("-") if float(text) == 0 else text
