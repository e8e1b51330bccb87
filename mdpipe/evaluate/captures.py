"""Captures an earlier ``mdpipe evaluate --keep-captures`` run kept, processed again instead of simulated anew.

Simulating is most of a sweep's time (the default sweep: about 80 %); a change to the processing is scored on the
same scenes by processing their kept captures again. A kept capture stands for a drawn scene only where both were
made alike: its ``/Truth`` holds the drawn scene's YAML, character for character, and the folder's
``SIMULATOR_FILE`` names the digest of the simulator's source (:func:`simulator_digest`) that the current code has.
Anything else (another draw, a changed simulator, a file that does not open) is simulated anew, so a kept capture
is never scored stale.
"""

import hashlib
from functools import cache
from pathlib import Path

import mdpipe
from mdpipe.errors import MdpipeError

SIMULATOR_FILE = "simulator.sha256"
SIMULATOR_PACKAGES = ("simulate", "physics")  # the code a capture's samples and truth come from


@cache
def simulator_digest():
    """SHA-256 of the simulator's source files (path and content of each, in path order), hex."""
    root = Path(mdpipe.__file__).parent
    digest = hashlib.sha256()
    for package in SIMULATOR_PACKAGES:
        for path in sorted((root / package).rglob("*.py")):
            digest.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def mark_simulator(captures_dir):
    """Write the current :func:`simulator_digest` into ``captures_dir`` (captures kept for reuse)."""
    (Path(captures_dir) / SIMULATOR_FILE).write_text(simulator_digest() + "\n", encoding="ascii")


def check_reusable(captures_dir, out_captures_dir):
    """``captures_dir`` as a folder of captures to reuse: raises :class:`MdpipeError` naming the fix when it is not a
    folder, is the run's own captures folder (emptied as the run starts), or was kept by another simulator."""
    captures_dir = Path(captures_dir)
    if not captures_dir.is_dir():
        raise MdpipeError(f"--reuse-captures {captures_dir}: no such folder; give the captures/ folder of a run made "
                          "with --keep-captures")
    if out_captures_dir.exists() and captures_dir.resolve() == Path(out_captures_dir).resolve():
        raise MdpipeError(f"--reuse-captures {captures_dir} is this run's own captures folder, which it empties "
                          "first; give another --out")
    marked = captures_dir / SIMULATOR_FILE
    try:
        kept = marked.read_text(encoding="ascii").strip()
    except (OSError, UnicodeDecodeError):
        kept = None
    if kept != simulator_digest():
        why = "holds no simulator digest" if kept is None else "was simulated by other simulator code"
        raise MdpipeError(f"--reuse-captures {captures_dir}: the folder {why} ({SIMULATOR_FILE}); run without it "
                          "(with --keep-captures) to simulate the sweep anew")


def kept_truth(path, scene_yaml):
    """The ``/Truth`` expected features of the capture at ``path`` if it was simulated from ``scene_yaml``, else None
    (no such file, one that does not open, another scene)."""
    from mdpipe.io import open_capture

    if not Path(path).is_file():
        return None
    try:
        with open_capture(path) as capture:
            truth = capture.truth
    except Exception:  # noqa: BLE001 - a kept file that does not open is simulated anew, whatever the failure
        return None
    if truth is None or truth["scene_yaml"] != scene_yaml:
        return None
    return truth["expected"]
