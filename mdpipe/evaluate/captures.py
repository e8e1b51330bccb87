"""Captures an earlier ``mdpipe evaluate --keep-captures`` run kept, processed again instead of simulated anew.

Simulating is most of a sweep's time (the default sweep: about 80 %); a change to the processing is scored on the
same scenes by processing their kept captures again. A kept capture stands for a drawn scene only where both were
made alike: its ``/Truth`` holds the drawn scene's YAML, character for character, and the folder's
``SIMULATOR_FILE`` names the digest (:func:`simulator_digest`) of the code that simulated it, which must be the
current code's. Any other capture (another draw, a file that does not open) is simulated anew; a folder kept by
other code is refused, so a kept capture is never scored stale.
"""

import ast
import hashlib
import os
import sys
from pathlib import Path

import h5py
import numpy as np

import mdpipe
from mdpipe.errors import MdpipeError

SIMULATOR_FILE = "simulator.sha256"
SIMULATOR_ROOTS = ("simulate", "physics")  # the simulator's packages; what they import from mdpipe counts too
TRUTH_KEYS = ("radar", "targets", "simulation")  # what scoring reads from a capture's /Truth


def _imported_modules(path, package):
    """The ``mdpipe`` modules the Python file at ``path``, of the dotted ``package``, imports (dotted names; a name
    imported from a package may be a module of it; relative imports resolved against ``package``)."""
    names = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names if alias.name.split(".")[0] == "mdpipe")
        elif isinstance(node, ast.ImportFrom):
            base = package.split(".")[:len(package.split(".")) - node.level + 1] if node.level else []
            module = ".".join(base + ([node.module] if node.module else []))
            if module.split(".")[0] == "mdpipe":
                names.add(module)
                names.update(f"{module}.{alias.name}" for alias in node.names)
    return names


def _module_file(root, name):
    """The source file of module ``name`` (dotted, under the package at ``root``), or None (a name that is no
    module: a function or class imported from one)."""
    parts = name.split(".")[1:]
    candidates = [root.joinpath(*parts, "__init__.py"), root.joinpath(*parts).with_suffix(".py")] if parts \
        else [root / "__init__.py"]
    return next((path for path in candidates if path.is_file()), None)


def simulator_sources():
    """The source files a capture's samples and ``/Truth`` come from: every file of ``SIMULATOR_ROOTS`` and, in turn,
    every ``mdpipe`` module they import (the parameters, the capture writer, the version) with the ``__init__.py`` of
    each package above it, in path order. The processing is none of them: the simulator imports nothing from it."""
    root = Path(mdpipe.__file__).parent
    pending = [path for package in SIMULATOR_ROOTS for path in (root / package).rglob("*.py")]
    seen = set()
    while pending:
        path = pending.pop()
        if path in seen:
            continue
        seen.add(path)
        parts = path.relative_to(root).with_suffix("").parts
        package = ".".join(("mdpipe",) + parts[:-1])  # the package the file is of (or is: an __init__.py)
        pending.extend(init for parent in path.parents
                       if parent.is_relative_to(root) and (init := parent / "__init__.py").is_file())
        pending.extend(found for name in _imported_modules(path, package) if (found := _module_file(root, name)))
    return sorted(seen)


def simulator_digest():
    """SHA-256 (hex) of :func:`simulator_sources` (the path and content of each) and the Python, numpy and h5py
    versions."""
    root = Path(mdpipe.__file__).parent
    versions = f"python {sys.version}, numpy {np.__version__}, h5py {h5py.__version__}\0"
    digest = hashlib.sha256(versions.encode())
    for path in simulator_sources():
        digest.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def mark_simulator(captures_dir, digest):
    """Write ``digest`` (the :func:`simulator_digest` taken as the run started) into ``captures_dir``, where the code
    still has it: code changed during the run may have simulated some of the captures, and none is marked reusable."""
    if digest != simulator_digest():
        return False
    (Path(captures_dir) / SIMULATOR_FILE).write_text(digest + "\n", encoding="ascii")
    return True


def _same_folder(a, b):
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def check_reusable(captures_dir, out_captures_dir, digest):
    """``captures_dir`` as a folder of captures to reuse: raises :class:`MdpipeError` naming the fix when it is not a
    folder, is the run's own captures folder (emptied as the run starts), or was kept by simulator code other than
    the current code's (``digest``, its :func:`simulator_digest`)."""
    captures_dir = Path(captures_dir)
    if not captures_dir.is_dir():
        raise MdpipeError(f"--reuse-captures {captures_dir}: no such folder; give the captures/ folder of a run made "
                          "with --keep-captures")
    if _same_folder(captures_dir, out_captures_dir):
        raise MdpipeError(f"--reuse-captures {captures_dir} is this run's own captures folder, which it empties "
                          "first; give another --out")
    try:
        kept = (captures_dir / SIMULATOR_FILE).read_text(encoding="ascii").strip()
    except FileNotFoundError:
        kept, why = None, "holds no simulator digest"
    except (OSError, UnicodeDecodeError) as exc:
        kept, why = None, f"has a digest file that cannot be read ({exc.__class__.__name__})"
    else:
        why = "was simulated by other simulator code"
    if kept != digest:
        raise MdpipeError(f"--reuse-captures {captures_dir}: the folder {why} ({SIMULATOR_FILE}); run without it "
                          "(with --keep-captures) to simulate the sweep anew")


def kept_truth(path, scene_yaml):
    """The ``/Truth`` expected features of the capture at ``path`` if it was simulated from ``scene_yaml``, else None
    (no such file, one that does not open, another scene, a truth without what scoring reads)."""
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
    expected = truth["expected"]
    if not all(isinstance(expected.get(key), list if key == "targets" else dict) for key in TRUTH_KEYS):
        return None
    return expected
