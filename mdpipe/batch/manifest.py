"""What a batch folder holds: per capture, the input's size, mtime and content hash, mdpipe's version, the
processing settings and the files published. A capture is redone exactly when one of these changed or its
published files are gone.

The manifest is ``OUT/manifest.json``, rewritten atomically. Hashing streams the file (1 MiB blocks):
its cost is one read of every input per run (about 0.5 s per GB here, see benchmarks/bench_batch.py).
"""

import hashlib
import json
import os
from pathlib import Path

from mdpipe import __version__
from mdpipe.io.files import check_regular_file
from mdpipe.report.tables import atomic_write

MANIFEST_NAME = "manifest.json"
FORMAT = 1
HASH_BLOCK_BYTES = 1 << 20
IDENTITY = ("input", "size_bytes", "mtime_ns", "sha256", "mdpipe_version", "settings")


def fingerprint(path):
    """Size (bytes), modification time (ns) and SHA-256 of the file at ``path``, hashed as a stream; a path that is
    not a regular file (a FIFO, a device) is refused first (:func:`mdpipe.io.files.check_regular_file`)."""
    check_regular_file(path)
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        stat = os.fstat(fh.fileno())
        for block in iter(lambda: fh.read(HASH_BLOCK_BYTES), b""):
            digest.update(block)
    return {"size_bytes": stat.st_size, "mtime_ns": stat.st_mtime_ns, "sha256": digest.hexdigest()}


def identity(capture, print_, settings):
    """Everything whose change makes a capture's outputs stale, as the manifest stores it."""
    return {"input": str(Path(capture).resolve()), **print_, "mdpipe_version": __version__,
            "settings": json.loads(json.dumps(settings))}


def up_to_date(previous, current, folder):
    """Whether the record ``previous`` matches ``current`` (from :func:`identity`) and its files are in ``folder``."""
    if previous is None or any(previous.get(key) != current[key] for key in IDENTITY):
        return False
    return all((Path(folder) / name).is_file() for name in previous.get("outputs", ())) and bool(previous.get("outputs"))


def load(out_dir):
    """The records of ``out_dir``'s manifest by output key; empty when there is none or it is unreadable."""
    try:
        data = json.loads((Path(out_dir) / MANIFEST_NAME).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    if not isinstance(data, dict) or data.get("format") != FORMAT or not isinstance(data.get("captures"), dict):
        return {}
    return data["captures"]


def save(out_dir, records):
    """Write the records as ``out_dir``/manifest.json in one rename."""
    text = json.dumps({"format": FORMAT, "captures": dict(sorted(records.items()))}, indent=1)
    atomic_write(Path(out_dir) / MANIFEST_NAME, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
