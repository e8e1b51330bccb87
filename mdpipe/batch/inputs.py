"""Which captures a batch holds and where each one's outputs go.

A file argument is published as ``OUT/<its stem>/``; a folder argument is searched recursively for
``*.h5`` and ``*.hdf5`` files (Radarlog captures, I/Q recordings), and, a carrier given (``--carrier-hz``),
``*.wav`` I/Q recordings too, each published under ``OUT/`` at its path relative to that folder, less the
suffix (``IN/day2/gull.h5`` -> ``OUT/day2/gull/``), so same-named captures of different subfolders stay
apart. Two captures that would still share a folder (``gull.h5`` beside ``gull.hdf5``, or beside a subfolder
``gull/`` of captures) are refused before anything runs.
"""

import os
from dataclasses import dataclass
from pathlib import Path

from mdpipe.batch.manifest import MANIFEST_NAME
from mdpipe.errors import MdpipeError
from mdpipe.report.tables import PARTIAL_PREFIX, SUMMARY_PNG, SUMMARY_TABLE

LOCK_NAME = ".mdpipe.lock"
OUT_FILES = (MANIFEST_NAME, SUMMARY_TABLE, SUMMARY_PNG)  # written into OUT itself

CAPTURE_SUFFIXES = (".h5", ".hdf5")
WAV_SUFFIXES = (".wav",)  # searched for where a carrier is given: a folder of captures may hold other sounds
GLOB_CHARACTERS = "*?["


class InputsError(MdpipeError):
    """A command-line input that names no capture: a usage error."""


@dataclass(frozen=True)
class Capture:
    """A capture file and its output folder ``key``, relative to OUT (a POSIX path)."""

    path: Path
    key: str


def _in_folder(folder, suffixes):
    found = []
    for root, dirs, files in os.walk(folder):
        dirs.sort()
        found.extend(Path(root) / name for name in sorted(files) if name.lower().endswith(suffixes))
    return found


def find_captures(inputs, *, wav=False):
    """The captures named by ``inputs`` (files or folders), in order, each once; ``wav``: folders are searched for
    ``*.wav`` I/Q recordings too.

    Raises
    ------
    InputsError
        An input that does not exist (an unmatched shell pattern among them), a folder without captures, or
        two captures that would be published in the same output folder.
    """
    captures, owner = [], {}
    for given in map(Path, inputs):
        if not given.exists():
            hint = (" (a shell pattern that matched no file?)" if any(c in str(given) for c in GLOB_CHARACTERS)
                    else "")
            raise InputsError(f"{given}: no such file or folder{hint}")
        if given.is_dir():
            suffixes = CAPTURE_SUFFIXES + (WAV_SUFFIXES if wav else ())
            found = [(path, path.relative_to(given).with_suffix("").as_posix()) for path in _in_folder(given, suffixes)]
            if not found:
                names = [f"*{suffix}" for suffix in suffixes]
                raise InputsError(f"{given}: no {', '.join(names[:-1])} or {names[-1]} capture in this folder or "
                                  "below it")
        else:
            found = [(given, given.stem)]
        for path, key in found:
            if key in OUT_FILES + (LOCK_NAME,) or any(part.startswith(PARTIAL_PREFIX) for part in key.split("/")):
                raise InputsError(f"{path} would be published in OUT/{key}/, a name of the batch's own files in OUT "
                                  f"(or of its temporary ones, {PARTIAL_PREFIX}*); rename the capture")
            resolved = path.resolve()
            if key in owner:
                if owner[key] == resolved:
                    continue
                raise InputsError(f"{owner[key]} and {resolved} would both be published in OUT/{key}/; "
                                  "give the folder that holds both instead of the files")
            owner[key] = resolved
            captures.append(Capture(path, key))
    for key in owner:  # a capture's folder may not hold another capture's folder
        parent = key.rpartition("/")[0]
        while parent:
            if parent in owner:
                raise InputsError(f"{owner[parent]} would be published in OUT/{parent}/, which also holds the "
                                  f"outputs of {owner[key]}; rename one of them")
            parent = parent.rpartition("/")[0]
    return captures
