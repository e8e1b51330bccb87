"""Signals sent to a running ``mdpipe batch`` (SIGINT, SIGTERM, SIGKILL) and two runs on one OUT at once:
every capture folder is published whole or not at all, and the next run finishes the work."""

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import as_from_a_terminal
from mdpipe.batch import runner
from mdpipe.report import tables

SAMPLES = Path(__file__).resolve().parents[1] / "data_samples"
MDPIPE = [sys.executable, "-c", "import sys; from mdpipe.cli import run; sys.argv[0] = 'mdpipe'; run()"]
N_CAPTURES = 24  # ~0.15 s each: a run lasts a few seconds, long enough to be stopped within
N_WAITING = 6    # for runs that are not stopped (two started at once overlap by their start-up alone)


def captures_folder(tmp_path, n_captures):
    folder = tmp_path / "in"
    for i in range(n_captures):
        (folder / f"part{i % 2}").mkdir(parents=True, exist_ok=True)
        shutil.copy(SAMPLES / ("phantom4_xband.h5" if i % 2 else "gull_flyby.h5"), folder / f"part{i % 2}" / f"c{i}.h5")
    return folder


@pytest.fixture
def folder(tmp_path):
    return captures_folder(tmp_path, N_CAPTURES)


@pytest.fixture
def few(tmp_path):
    return captures_folder(tmp_path, N_WAITING)


def start(folder, out, command="batch"):
    extra = ["-j", "2"] if command == "batch" else []
    return subprocess.Popen([*MDPIPE, command, str(folder), "--out", str(out), "--no-figures", *extra],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=as_from_a_terminal)


def complete_folders(out):
    """Published capture folders; each must hold its whole output set."""
    found = {}
    for marker in out.rglob(tables.MARKER):
        folder = marker.parent
        stem = folder.name
        names = sorted(p.name for p in folder.iterdir())
        assert names == sorted([tables.MARKER, f"{stem}.features.csv", f"{stem}.run.json"]), names
        found[folder.relative_to(out).as_posix()] = names
    return found


def markers(out):
    """The markers of the capture folders published in ``out`` by a run still going on: a temporary folder
    renamed while the scan reaches it makes the scan start again."""
    while True:
        try:
            return list(out.rglob(tables.MARKER))
        except FileNotFoundError:
            continue


def wait_for_first(out, process, timeout_s=120):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if markers(out):
            return
        assert process.poll() is None, process.communicate()
        time.sleep(0.05)
    raise AssertionError("no capture published in time")


def assert_nothing_half_published(out):
    done = complete_folders(out)
    assert not list(out.rglob(f"{tables.PARTIAL_PREFIX}*"))
    visible = {p.relative_to(out).as_posix() for p in out.glob("part*/*")}
    assert visible == set(done)  # no capture folder without its marker and full set
    return done


@pytest.mark.parametrize("signum, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_interrupted_process_exits_and_publishes_nothing_half(folder, tmp_path, signum, code):
    out = tmp_path / "out"
    process = start(folder, out, "process")
    wait_for_first(out, process)
    process.send_signal(signum)
    stdout, stderr = process.communicate(timeout=60)
    assert process.returncode == code, stderr
    assert stderr == ("Interrupted.\n" if signum == signal.SIGINT else "Terminated.\n")
    assert 1 <= len(assert_nothing_half_published(out)) < N_CAPTURES


@pytest.mark.parametrize("signum, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_interrupted_batch_exits_and_publishes_nothing_half(folder, tmp_path, signum, code):
    out = tmp_path / "out"
    process = start(folder, out)
    wait_for_first(out, process)
    process.send_signal(signum)
    stdout, stderr = process.communicate(timeout=60)
    assert process.returncode == code, stderr
    assert "Traceback" not in stderr
    assert "captures; each capture is published whole or not at all: run the same command again" in stderr
    done = assert_nothing_half_published(out)
    assert 1 <= len(done) < N_CAPTURES
    recorded = json.loads((out / "manifest.json").read_text())["captures"]
    assert set(recorded) <= set(done)  # a capture published as the signal came may not be recorded: it is redone
    process = start(folder, out)
    stdout, stderr = process.communicate(timeout=120)
    assert process.returncode == 0, stderr
    assert (f"{N_CAPTURES} captures: {N_CAPTURES - len(recorded)} processed, {len(recorded)} up to date, 0 failed"
            in stdout)
    assert len(assert_nothing_half_published(out)) == N_CAPTURES


def test_killed_batch_is_finished_by_the_next_run(folder, tmp_path):
    out = tmp_path / "out"
    process = start(folder, out)
    wait_for_first(out, process)
    process.kill()
    process.communicate(timeout=30)  # returns once no worker holds the pipes: none runs on
    process = start(folder, out)
    stdout, stderr = process.communicate(timeout=120)
    assert process.returncode == 0, stderr
    assert f"{N_CAPTURES} captures: " in stdout and "0 failed" in stdout
    assert len(assert_nothing_half_published(out)) == N_CAPTURES
    assert len(json.loads((out / "manifest.json").read_text())["captures"]) == N_CAPTURES


def test_a_second_run_waits_for_the_first(few, tmp_path):
    out = tmp_path / "out"
    with runner.locked(out):  # a first run holds OUT
        second = start(few, out)
        line = second.stderr.readline()
        assert line == f"{out} is in use by another mdpipe run (pid {os.getpid()}); waiting for it to finish\n"
        time.sleep(0.5)
        assert second.poll() is None and not list(out.rglob(tables.MARKER))  # it waits, writing nothing
    stdout, stderr = second.communicate(timeout=120)
    assert second.returncode == 0, stderr
    assert f"{N_WAITING} captures: {N_WAITING} processed, 0 up to date, 0 failed" in stdout


def test_two_runs_on_one_out_at_once(few, tmp_path):
    out = tmp_path / "out"
    runs = [start(few, out), start(few, out)]
    results = [run.communicate(timeout=120) for run in runs]
    assert [run.returncode for run in runs] == [0, 0], results
    assert sum("waiting for it to finish" in stderr for _, stderr in results) == 1  # they overlapped: one waited
    processed = [int(re.search(r"captures: (\d+) processed", stdout).group(1)) for stdout, _ in results]
    assert sum(processed) == N_WAITING  # one after the other: each capture processed once
    assert len(assert_nothing_half_published(out)) == N_WAITING
    assert len(json.loads((out / "manifest.json").read_text())["captures"]) == N_WAITING


# `mdpipe process INPUT --out OUT` whose reader options, read as its captures are set up, send SIGINT from inside a
# weakref callback, where Python swallows the KeyboardInterrupt the handler raises
SWALLOWED_STOP = ("import os, signal, sys, weakref\n"
                  "import mdpipe.cli as cli\n"
                  "class Thing: pass\n"
                  "options = cli.reader_options\n"
                  "def interrupt_inside_a_callback(*args):\n"
                  "    thing = Thing()\n"
                  "    keep = weakref.ref(thing, lambda ref: os.kill(os.getpid(), signal.SIGINT))\n"
                  "    del thing\n"
                  "    return options(*args)\n"
                  "cli.reader_options = interrupt_inside_a_callback\n"
                  "sys.argv = ['mdpipe', 'process', sys.argv[1], '--out', sys.argv[2], '--no-figures']\n"
                  "cli.run()\n")


def process_with_a_swallowed_stop(inputs, out):
    return subprocess.run([sys.executable, "-c", SWALLOWED_STOP, str(inputs), str(out)], capture_output=True,
                          text=True, timeout=120)


def test_a_stop_swallowed_by_a_callback_still_ends_the_command_with_its_code(tmp_path):
    """SIGINT landing inside a weakref callback raises KeyboardInterrupt there, where Python swallows it (and
    printed "Exception ignored in ..."): the command went on and exited 0. The stop is recorded; the command
    ends with 130 and one line, and the swallowed exception prints nothing."""
    done = process_with_a_swallowed_stop(SAMPLES / "gull_flyby.h5", tmp_path / "out")
    assert done.returncode == 130
    assert done.stderr == "Interrupted.\n"


def test_a_stop_swallowed_by_a_callback_ends_the_run_at_the_next_capture(tmp_path):
    """The same swallowed SIGINT, landing as three captures are set up: the stop is recorded, and the run ends when
    the first capture is published (it went on through every capture, and ended with 130 only then): one capture
    folder, whole, and 130."""
    folder = tmp_path / "in"
    (folder / "part0").mkdir(parents=True)
    for i in range(3):
        shutil.copy(SAMPLES / "gull_flyby.h5", folder / "part0" / f"c{i}.h5")
    out = tmp_path / "out"
    done = process_with_a_swallowed_stop(folder, out)
    assert done.returncode == 130
    assert done.stderr == "Interrupted.\n"
    assert len(assert_nothing_half_published(out)) == 1
