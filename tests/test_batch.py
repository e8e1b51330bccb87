"""mdpipe batch: mirrored outputs, the manifest's redo rule, failures that replace stale outputs, a crash inside
one capture, a full disk, a read-only OUT, and Dask against the process pool."""

import csv
import errno
import json
import multiprocessing
import os
import shutil
import signal
import time
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

import pytest
from click.testing import CliRunner

from mdpipe.batch import manifest, unit
from mdpipe.cli import main
from mdpipe.params import FigureParams
from mdpipe.report import tables

SAMPLES = Path(__file__).resolve().parents[1] / "data_samples"


def batch(*args):
    return CliRunner().invoke(main, ["batch", *map(str, args)])


@pytest.fixture
def captures(tmp_path):
    """A folder with nested subfolders, one stem twice, and a name with a space and a colon."""
    folder = tmp_path / "in"
    for relative, sample in (("day1/x.h5", "phantom4_xband.h5"), ("day2/x.h5", "gull_flyby.h5"),
                             ("drone 2: pass.h5", "phantom4_xband.h5")):
        (folder / relative).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(SAMPLES / sample, folder / relative)
    return folder


def published(out):
    """Every published capture folder under ``out``, relative, with the files it holds."""
    return {p.parent.relative_to(out).as_posix(): sorted(q.name for q in p.parent.iterdir())
            for p in out.rglob(tables.MARKER)}


def test_batch_mirrors_folders_and_keeps_same_stems_apart(tmp_path, captures):
    out = tmp_path / "out"
    result = batch(captures, "--out", out, "-j", 2)
    assert result.exit_code == 0, result.output
    assert "3 captures: 3 processed, 0 up to date, 0 failed" in result.output
    assert result.stderr == ""  # not a terminal: no progress bar
    figures = ["_range.png", "_spectrogram.png", "_spectrum.png"]
    assert published(out) == {
        "day1/x": sorted([tables.MARKER, "x.features.csv", "x.run.json"] + [f"x{f}" for f in figures]),
        "day2/x": sorted([tables.MARKER, "x.features.csv", "x.run.json"] + [f"x{f}" for f in figures]),
        "drone 2: pass": sorted([tables.MARKER, "drone 2: pass.features.csv", "drone 2: pass.run.json"]
                                + [f"drone 2: pass{f}" for f in figures]),
    }
    assert "drone" in (out / "day1/x/x.features.csv").read_text() and "bird" in (out / "day2/x/x.features.csv").read_text()
    assert sorted(manifest.load(out)) == ["day1/x", "day2/x", "drone 2: pass"]
    assert (out / "summary.png").stat().st_size > 0
    assert not list(out.rglob(f"{tables.PARTIAL_PREFIX}*"))
    umask = os.umask(0o022)
    os.umask(umask)
    for path in [out / "features.csv", out / "manifest.json", out / "day2/x/x_spectrum.png"]:
        assert path.stat().st_mode & 0o777 == 0o666 & ~umask, path
    assert (out / "day2/x").stat().st_mode & 0o777 == 0o777 & ~umask


def test_progress_line_on_a_terminal(monkeypatch):
    import io

    from mdpipe import cli

    clock = iter([100.0, 110.0, 130.0])  # started at 100 s; 1 of 4 done at 110 s; 2 at 130 s
    monkeypatch.setattr(cli.time, "monotonic", lambda: next(clock))
    stream = io.StringIO()
    progress = cli.Progress(4, stream)
    progress.update(unit.Outcome("a.h5", "a", unit.DONE, False))
    progress.update(unit.Outcome("b.h5", "b", unit.FAILED, True))
    frames = stream.getvalue().split("\r")[1:]
    # ETA = elapsed / done x remaining: 10 s x 3 = 30 s, then 15 s x 2 = 30 s
    assert frames == ["[........................] 0/4, 0 failed, ETA ? ",
                      "[######..................] 1/4, 0 failed, ETA 00:00:30 ",
                      "[############............] 2/4, 1 failed, ETA 00:00:30 "]


def test_summary_table_keeps_types(tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    for name in ("clutter_only.h5", "phantom4_xband.h5", "gull_flyby.h5"):
        shutil.copy(SAMPLES / name, folder / name)
    out = tmp_path / "out"
    assert batch(folder, "--out", out, "-j", 1, "--no-figures").exit_code == 0
    columns, rows, errors = tables.gather(out)
    header, *merged = csv.reader((out / "features.csv").read_text().splitlines())
    by_file = {line[0]: line for line in merged}
    clutter, drone = by_file[str(folder / "clutter_only.h5")], by_file[str(folder / "phantom4_xband.h5")]
    # the none row has no target (empty, not 0.0 or nan); the drone's target 0 stays 0, its aliased False
    assert clutter[header.index("target")] == "" and drone[header.index("target")] == "0"
    assert drone[header.index("aliased")] == "False" and drone[header.index("n_blades")] == "2"
    typed = tables.frame(columns, rows)
    assert str(typed["target"].dtype) == "Int64" and str(typed["aliased"].dtype) == "boolean"
    assert str(typed["range_bin"].dtype) == "Int64" and typed["snr_db"].dtype.kind == "f"
    assert errors == []



SUMMARY_RUN = """
import sys
from mdpipe.cli import main
main(["summarize", sys.argv[1]], standalone_mode=False)
print("pandas" in sys.modules)
"""


def test_folder_summary_loads_no_pandas(tmp_path):
    """The folder's table and figure are drawn from the gathered text rows: pandas' import (0.1-0.3 s) is not
    paid at the end of every batch."""
    import subprocess
    import sys

    out = tmp_path / "out"
    assert batch(SAMPLES / "phantom4_xband.h5", SAMPLES / "clutter_only.h5", "--out", out, "-j", 1,
                 "--no-figures").exit_code == 0
    (out / "features.csv").unlink()
    done = subprocess.run([sys.executable, "-c", SUMMARY_RUN, str(out)], capture_output=True, text=True, check=True)
    assert done.stdout.splitlines()[-1] == "False"
    assert (out / "summary.png").stat().st_size > 0 and len((out / "features.csv").read_text().splitlines()) == 3

def _mtimes(out):
    return {key: (out / key / f"{Path(key).name}.features.csv").stat().st_mtime_ns for key in manifest.load(out)}


def test_manifest_redoes_exactly_what_changed(tmp_path, captures):
    out = tmp_path / "out"
    assert batch(captures, "--out", out, "-j", 1, "--no-figures").exit_code == 0
    first = _mtimes(out)
    again = batch(captures, "--out", out, "-j", 1, "--no-figures")
    assert "3 captures: 0 processed, 3 up to date, 0 failed" in again.output and _mtimes(out) == first

    stat = (captures / "day2/x.h5").stat()  # touched: the mtime alone changed
    os.utime(captures / "day2/x.h5", ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))
    assert "1 processed, 2 up to date" in batch(captures, "--out", out, "-j", 1, "--no-figures").output
    second = _mtimes(out)
    assert [k for k in first if first[k] != second[k]] == ["day2/x"]

    path = captures / "day1/x.h5"  # same size and mtime, one byte of content changed: the hash tells
    stat = path.stat()
    data = bytearray(path.read_bytes())
    data[-1] ^= 1
    path.write_bytes(bytes(data))
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    assert "1 processed, 2 up to date" in batch(captures, "--out", out, "-j", 1, "--no-figures").output
    third = _mtimes(out)
    assert [k for k in second if second[k] != third[k]] == ["day1/x"]

    records = manifest.load(out)  # a capture made by another mdpipe version
    records["drone 2: pass"]["mdpipe_version"] = "0.0.1"
    manifest.save(out, records)
    assert "1 processed, 2 up to date" in batch(captures, "--out", out, "-j", 1, "--no-figures").output
    fourth = _mtimes(out)
    assert [k for k in third if third[k] != fourth[k]] == ["drone 2: pass"]

    assert "3 processed, 0 up to date" in batch(captures, "--out", out, "-j", 1, "--no-figures", "--blades", 3).output
    assert json.loads((out / "day1/x/x.run.json").read_text())["process_params"]["n_blades"] == 3

    shutil.rmtree(out / "day2/x")  # outputs removed by hand: redone
    assert "1 processed, 2 up to date" in batch(captures, "--out", out, "-j", 1, "--no-figures", "--blades", 3).output

    other = tmp_path / "other"  # another folder with a day2/x.h5, into the same OUT: redone, and said
    (other / "day2").mkdir(parents=True)
    shutil.copy(captures / "day2/x.h5", other / "day2/x.h5")
    result = batch(other, "--out", out, "-j", 1, "--no-figures", "--blades", 3)
    assert "1 captures: 1 processed, 0 up to date" in result.output
    assert result.stderr == (f"Warning: {out / 'day2/x'} held the outputs of {captures / 'day2/x.h5'}; "
                             f"now those of {other / 'day2/x.h5'}\n")


def test_a_capture_that_now_fails_loses_its_stale_outputs(tmp_path, captures):
    out = tmp_path / "out"
    assert batch(captures, "--out", out, "-j", 2).exit_code == 0
    (captures / "day2/x.h5").write_bytes((SAMPLES / "gull_flyby.h5").read_bytes()[:4000])
    result = batch(captures, "--out", out, "-j", 2)
    assert result.exit_code == 2
    (line,) = result.stderr.splitlines()
    assert line.startswith(f"Error: {captures / 'day2/x.h5'}: the HDF5 file is truncated")
    assert published(out)["day2/x"] == sorted([tables.MARKER, "x.error.txt"])
    assert "3 captures: 0 processed, 2 up to date, 1 failed" in result.output
    assert "2 target rows from 2 captures (drone 2); 1 failed" in result.output
    assert manifest.load(out)["day2/x"]["status"] == "failed"
    kept = batch(captures, "--out", out, "-j", 2)  # unchanged since it failed: still a failure, not redone
    assert kept.exit_code == 2 and "0 processed, 2 up to date, 1 failed (1 of them unchanged since they failed)" in kept.output


def test_a_crash_inside_one_capture_is_its_one_line_error(tmp_path, captures, monkeypatch):
    real = unit.process_capture

    def crash_on_day2(path, *args, **kwargs):
        if "day2" in str(path):
            raise ValueError("cannot reshape array of size 0 into shape (0,newaxis)")
        return real(path, *args, **kwargs)

    monkeypatch.setattr(unit, "process_capture", crash_on_day2)
    out = tmp_path / "out"
    result = batch(captures, "--out", out, "-j", 1, "--no-figures")
    assert result.exit_code == 2
    error_file = out / "day2/x/x.error.txt"
    assert result.stderr.splitlines() == [
        f"Error: {captures / 'day2/x.h5'}: internal error, ValueError: cannot reshape array of size 0 into shape "
        f"(0,newaxis) (traceback in {error_file})"]
    assert "Traceback (most recent call last)" in error_file.read_text() and "crash_on_day2" in error_file.read_text()
    assert "2 processed, 0 up to date, 1 failed" in result.output
    assert (out / "day1/x/x.features.csv").exists() and (out / "drone 2: pass/drone 2: pass.features.csv").exists()
    debug = CliRunner().invoke(main, ["process", str(captures / "day2/x.h5"), "--out", str(out), "--debug"])
    assert debug.exit_code == 2 and "Traceback (most recent call last)" in debug.stderr


def test_full_disk_leaves_no_stale_or_partial_outputs(tmp_path, captures, monkeypatch):
    out = tmp_path / "out"
    assert batch(captures / "day1", "--out", out, "-j", 1, "--no-figures").exit_code == 0

    def no_space(path, write):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))

    monkeypatch.setattr(tables, "atomic_write", no_space)  # every output and error file; not the manifest
    result = batch(captures / "day1", "--out", out, "-j", 1, "--no-figures", "--blades", 3)
    assert result.exit_code == 2
    line, summary = result.stderr.splitlines()
    assert summary == f"Error: [Errno 28] No space left on device: '{out / 'features.csv'}'"
    assert line.startswith(f"Error: {captures / 'day1/x.h5'}: cannot write its outputs: [Errno 28] No space left")
    assert f"its error file {out / 'x/x.error.txt'} could not be written either: [Errno 28] No space left" in line
    assert not (out / "x").exists() and not list(out.rglob(f"{tables.PARTIAL_PREFIX}*"))  # stale table gone
    assert manifest.load(out) == {}
    monkeypatch.undo()
    assert "1 processed, 0 up to date" in batch(captures / "day1", "--out", out, "-j", 1, "--no-figures").output


def test_read_only_output_folder_is_one_line_exit_1(tmp_path):
    if os.geteuid() == 0:  # root writes through permission bits; sysfs is mounted read-only for everyone
        out = Path("/sys/fs/mdpipe-out")
    else:
        out = tmp_path / "ro"
        out.mkdir()
        out.chmod(0o555)
    result = batch(SAMPLES / "gull_flyby.h5", "--out", out)
    assert result.exit_code == 1
    assert result.output.strip().splitlines() == [result.output.strip()]
    assert result.output.startswith(f"Error: {out}: cannot write into this output folder (")
    assert result.output.rstrip().endswith("); choose a writable --out")


def test_an_output_folder_mdpipe_did_not_write_is_left_alone(tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    shutil.copy(SAMPLES / "gull_flyby.h5", folder / "gull_flyby.h5")
    (folder / "gull_flyby").mkdir()
    (folder / "gull_flyby" / "notes.txt").write_text("mine")
    result = CliRunner().invoke(main, ["process", str(folder / "gull_flyby.h5"), "--out", str(folder),
                                       "--no-figures"])
    assert result.exit_code == 2 and "was not written by mdpipe (left as it is)" in result.stderr
    assert (folder / "gull_flyby" / "notes.txt").read_text() == "mine" and (folder / "gull_flyby.h5").exists()


class KillsItsWorker(dict):
    """Reader options whose unpickling ends the worker process at once, as a segfault would."""

    def __reduce__(self):
        return os._exit, (1,)


def test_a_worker_that_dies_fails_only_its_capture(tmp_path):
    from dataclasses import replace

    from mdpipe.batch import runner
    from mdpipe.params import ProcessParams

    good = [unit.Job(str(SAMPLES / name), Path(name).stem, str(tmp_path), ProcessParams(),
                     {"frame_counter": "auto", "overrides": {}}, figures=None)
            for name in ("phantom4_xband.h5", "gull_flyby.h5", "clutter_only.h5")]
    dying = replace(good[1], key="dies", reader=KillsItsWorker())
    outcomes = {o.key: o for o in runner.run([good[0], dying, good[1], good[2]], workers=2, track=True)}
    assert {key: o.status for key, o in outcomes.items()} == {
        "phantom4_xband": "done", "gull_flyby": "done", "clutter_only": "done", "dies": "failed"}
    assert outcomes["dies"].message == (f"{SAMPLES / 'gull_flyby.h5'}: its worker process died (killed by the system, "
                                        "out of memory say, or a crash inside a library)")
    assert (tmp_path / "dies" / "gull_flyby.error.txt").exists()
    assert sorted(manifest.load(tmp_path)) == ["clutter_only", "gull_flyby", "phantom4_xband"]  # redone next run


class KillsItsWorkerWhenDrawn(FigureParams):
    """Figure options that end a worker process when its figures read them: a worker dying while it draws."""

    def __getattribute__(self, name):
        if name == "doppler_limits" and multiprocessing.parent_process() is not None:
            os._exit(1)
        return super().__getattribute__(name)


@pytest.mark.parametrize("stage", ["analysis", "figures"])
def test_a_worker_that_dies_with_figures_to_draw_fails_only_its_capture(tmp_path, stage):
    """A capture with figures is two pool tasks, its analysis and then its figures; a worker dying in either
    loses what it held and breaks the pool: the captures not finished are run again alone, and only the one
    that kills its worker is failed."""
    from dataclasses import replace

    from mdpipe.batch import runner
    from mdpipe.params import ProcessParams

    good = [unit.Job(str(SAMPLES / name), Path(name).stem, str(tmp_path), ProcessParams(),
                     {"frame_counter": "auto", "overrides": {}})
            for name in ("phantom4_xband.h5", "gull_flyby.h5", "clutter_only.h5")]
    dying = replace(good[1], key="dies", **({"reader": KillsItsWorker()} if stage == "analysis" else
                                            {"figures": KillsItsWorkerWhenDrawn()}))
    analysed = []
    outcomes = {o.key: o for o in runner.run([good[0], dying, good[1], good[2]], workers=2,
                                             analysed=lambda step: analysed.append(step.job.key))}
    assert {key: o.status for key, o in outcomes.items()} == {
        "phantom4_xband": "done", "gull_flyby": "done", "clutter_only": "done", "dies": "failed"}
    assert ("dies" in analysed) == (stage == "figures")
    assert outcomes["dies"].message.endswith("its worker process died (killed by the system, out of memory say, "
                                             "or a crash inside a library)")
    assert (tmp_path / "dies" / "gull_flyby.error.txt").exists()
    assert (tmp_path / "gull_flyby" / "gull_flyby_spectrum.png").exists()


def test_no_room_to_stage_figures_is_the_captures_one_line_error(tmp_path, monkeypatch):
    """A pool draws a capture's figures into a temporary folder beside its output folder; where that folder
    cannot be made (a full disk), the capture fails with the reason, its error file published, and the
    batch's process draws nothing itself."""
    from mdpipe.batch import runner
    from mdpipe.params import ProcessParams
    from mdpipe.report import plots

    def full(analysed):
        raise OSError(errno.ENOSPC, "No space left on device")

    def drawn_here(*args, **kwargs):
        raise AssertionError("a figure drawn in the batch's process")

    monkeypatch.setattr(unit, "stage", full)
    for name in ("range_figure", "spectrogram_figure", "spectrum_figure"):
        monkeypatch.setattr(plots, name, drawn_here)
    jobs = [unit.Job(str(SAMPLES / name), Path(name).stem, str(tmp_path), ProcessParams(),
                     {"frame_counter": "auto", "overrides": {}}) for name in ("gull_flyby.h5", "clutter_only.h5")]
    outcomes = runner.run(jobs, workers=2)
    assert sorted((o.status, o.message) for o in outcomes) == sorted(
        ("failed", f"{job.capture}: cannot write its outputs: [Errno 28] No space left on device") for job in jobs)
    assert sorted(published(tmp_path)) == ["clutter_only", "gull_flyby"]
    assert (tmp_path / "gull_flyby" / "gull_flyby.error.txt").exists()


def test_a_pool_with_nothing_to_publish_returns_the_rows():
    """Jobs with figures but no output folder (rows only, as ``process --json`` asks) run whole in the pool:
    nothing is staged or drawn."""
    from mdpipe.batch import runner
    from mdpipe.params import ProcessParams

    jobs = [unit.Job(str(SAMPLES / name), Path(name).stem, None, ProcessParams(), {"frame_counter": "auto",
                                                                                   "overrides": {}})
            for name in ("gull_flyby.h5", "phantom4_xband.h5")]
    outcomes = sorted(runner.run(jobs, workers=2), key=lambda o: o.key)
    assert [(o.key, o.status, [row["class"] for row in o.rows]) for o in outcomes] == [
        ("gull_flyby", "done", ["bird"]), ("phantom4_xband", "done", ["drone"])]


def test_a_pool_leaves_the_collector_as_it_found_it(tmp_path):
    """The objects frozen out of the collector for the fork are released when the pool ends; objects the
    caller froze itself stay frozen."""
    import gc

    from mdpipe.batch import runner
    from mdpipe.params import ProcessParams

    jobs = [unit.Job(str(SAMPLES / "clutter_only.h5"), f"c{i}", str(tmp_path), ProcessParams(),
                     {"frame_counter": "auto", "overrides": {}}, figures=None) for i in range(2)]
    assert gc.get_freeze_count() == 0
    runner.run(jobs, workers=2)
    assert gc.get_freeze_count() == 0
    gc.freeze()
    try:
        frozen = gc.get_freeze_count()
        runner.run(jobs, workers=2)
        assert gc.get_freeze_count() == frozen
    finally:
        gc.unfreeze()


def test_helper_threads_leave_the_stop_signals_to_the_main_thread():
    """A thread started by the batch blocks SIGINT and SIGTERM: the kernel then hands them to the main thread,
    which holds them back while it forks a worker (Python runs their handlers there anyway)."""
    from mdpipe.batch import runner

    masks = []
    runner.start_thread(lambda: masks.append(signal.pthread_sigmask(signal.SIG_BLOCK, []))).join(timeout=10)
    assert {signal.SIGINT, signal.SIGTERM} <= masks[0]
    assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, [])  # the main thread's own is untouched


def test_the_first_figure_that_fails_is_the_captures_error(tmp_path, monkeypatch):
    """Where two of a capture's figures fail (drawn by two workers, in any order), its error is that of the
    first in the figures' order, as one task drawing them all would meet it."""
    from mdpipe.batch import runner
    from mdpipe.params import ProcessParams
    from mdpipe.report import plots

    def broken(text, after_s):
        def draw(*args, **kwargs):
            time.sleep(after_s)
            raise ValueError(text)
        return draw

    monkeypatch.setattr(plots, "spectrogram_figure", broken("the spectrogram", 0.3))  # it fails last
    monkeypatch.setattr(plots, "spectrum_figure", broken("the spectrum", 0.0))
    jobs = [unit.Job(str(SAMPLES / "gull_flyby.h5"), f"g{i}", str(tmp_path), ProcessParams(),
                     {"frame_counter": "auto", "overrides": {}}) for i in range(2)]
    outcomes = runner.run(jobs, workers=2)
    assert [o.message.split(" (traceback")[0] for o in outcomes] == [
        f"{SAMPLES / 'gull_flyby.h5'}: internal error, ValueError: the spectrogram"] * 2


def test_each_capture_is_published_before_the_pool_analyses_more(tmp_path):
    """The pool is handed as many tasks as it has workers, a capture's figures before the next analysis: the
    first capture is published before the third is analysed (an interrupted run keeps what it did; queued
    behind every analysis, nothing was published until all were done)."""
    from mdpipe.batch import runner
    from mdpipe.params import ProcessParams

    jobs = [unit.Job(str(SAMPLES / "clutter_only.h5"), f"c{i}", str(tmp_path), ProcessParams(),
                     {"frame_counter": "auto", "overrides": {}}) for i in range(5)]
    events = []
    runner.run(jobs, workers=2, analysed=lambda step: events.append("analysed"),
               on_outcome=lambda outcome: events.append("published"))
    assert events.count("analysed") == events.count("published") == 5
    third = [i for i, event in enumerate(events) if event == "analysed"][2]
    assert events.index("published") < third


def test_the_folder_summary_is_drawn_before_the_last_figures(tmp_path, captures, monkeypatch):
    """With a pool, OUT/summary.png is drawn as soon as every capture is analysed, from the rows their tables
    will hold, while the pool draws the captures' figures: the drawing at the end is not called, and the figure
    is the one the tables gathered at the end give, byte for byte."""
    from mdpipe.report import plots

    def late(rows, path):
        raise AssertionError("the summary was drawn at the end")

    monkeypatch.setattr(plots, "summary_figure", late)
    out = tmp_path / "out"
    result = batch(captures, "--out", out, "-j", 2)
    assert result.exit_code == 0, result.output
    _, rows, _ = tables.gather(out)
    assert len(rows) == 3
    assert (out / "summary.png").read_bytes() == plots.summary_png(rows)


def test_an_early_summary_is_kept_only_for_the_rows_it_was_drawn_from(tmp_path):
    """The summary drawn early is given for exactly the rows it was drawn from: the batch's captures' rows (an
    earlier run's capture in OUT left out, as the batch's summary leaves it), the analysed captures' in place of their
    tables. Rows that differ at the end (a capture whose outputs could not be written, a table changed meanwhile) get
    none."""
    from mdpipe.batch.summary import EarlySummary
    from mdpipe.params import ProcessParams
    from mdpipe.report import plots

    def job(name, key):
        return unit.Job(str(SAMPLES / name), key, str(tmp_path), ProcessParams(), {"frame_counter": "auto",
                                                                                     "overrides": {}})

    unit.run(job("clutter_only.h5", "earlier"))  # published by an earlier run
    jobs = [job("gull_flyby.h5", "a"), job("phantom4_xband.h5", "b")]
    early = EarlySummary(tmp_path, jobs)
    steps = [unit.analyse(j) for j in jobs]
    for step in steps:  # matplotlib is not thread-safe: these figures are drawn before the summary's thread starts
        unit.publish(step)
    early.analysed(steps[0])
    assert early.thread is None  # one capture is still being analysed
    early.analysed(steps[1])
    _, rows, _ = tables.gather(tmp_path, only=[j.folder for j in jobs])
    assert [row["class"] for row in rows] == ["bird", "drone"]  # a, b: the order of their paths; not the earlier run's
    assert early.png(rows) == plots.summary_png(rows)
    assert early.png(tables.gather(tmp_path)[1]) is None  # (with the earlier run's row)
    changed = [dict(row, **{"class": "bird"}) if row["class"] == "drone" else row for row in rows]
    assert early.png(changed) is None


def test_dask_missing_is_one_line(tmp_path, monkeypatch):
    monkeypatch.setitem(__import__("sys").modules, "distributed", None)
    result = batch(SAMPLES / "gull_flyby.h5", "--out", tmp_path / "out", "--scheduler", "local")
    assert result.exit_code == 1
    assert result.output == ("Error: --scheduler needs Dask distributed, which is not installed: "
                             "pip install 'mdpipe[dask]'\n")


def test_dask_local_cluster_gives_the_pool_tables(tmp_path, monkeypatch):
    pytest.importorskip("distributed", reason="Dask is an optional extra: pip install 'mdpipe[dask]'")
    monkeypatch.chdir(tmp_path)  # relative paths: the Dask workers run in another folder
    folder = Path("in")
    folder.mkdir()
    for name in ("phantom4_xband.h5", "gull_flyby.h5", "clutter_only.h5"):
        shutil.copy(SAMPLES / name, folder / name)
    pool, cluster = Path("pool"), Path("dask")
    assert batch(folder, "--out", pool, "-j", 2, "--no-figures").exit_code == 0
    result = batch(folder, "--out", cluster, "-j", 2, "--no-figures", "--scheduler", "local")
    assert result.exit_code == 0, result.output
    assert "3 captures: 3 processed" in result.output
    assert (cluster / "features.csv").read_bytes() == (pool / "features.csv").read_bytes()
    assert "\nin/gull_flyby.h5," in (cluster / "features.csv").read_text()  # the path as given
    for name in ("phantom4_xband", "gull_flyby", "clutter_only"):
        table = f"{name}/{name}.features.csv"
        assert (cluster / table).read_bytes() == (pool / table).read_bytes()


def test_leftovers_of_a_killed_run_are_removed_and_nothing_else(tmp_path):
    out = tmp_path / "out"
    keep = [out / ".mdpipe-partial-other.abc123", out / "x" / "x.features.csv", out / "notes.txt"]
    gone = [out / ".mdpipe-partial-x.k2j3_q", out / ".mdpipe-partial-x.old.1a2b3c4d",
            out / ".mdpipe-partial-features.csv.zz9"]
    for path in keep + gone:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text("")
    tables.remove_partials([out / "x", out / "features.csv"])
    assert [p.exists() for p in keep] == [True, True, True] and [p.exists() for p in gone] == [False, False, False]


def test_the_pool_starts_the_largest_captures_first(tmp_path):
    """Jobs go to the pool by input size, largest first, ties in the order given; a vanished input counts as
    empty (its job fails at once)."""
    from mdpipe.batch import runner
    from mdpipe.params import ProcessParams

    sizes = {"a": 10, "b": 3000, "c": 10, "d": 700}
    for name, size in sizes.items():
        (tmp_path / f"{name}.h5").write_bytes(b"\0" * size)
    names = ["a", "gone", "b", "c", "d"]
    jobs = [unit.Job(str(tmp_path / f"{n}.h5"), n, None, ProcessParams(), {}, None) for n in names]
    assert [job.key for job in runner._largest_first(jobs)] == ["b", "d", "a", "c", "gone"]


def _terminate_self():
    os.kill(os.getpid(), signal.SIGTERM)
    time.sleep(5)


def _threads():
    from threadpoolctl import threadpool_info

    from mdpipe.process import ranging
    return sorted({pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"}), ranging.WORKERS


@pytest.mark.parametrize("workers", [1, 2, 64])
def test_a_pool_worker_takes_its_share_of_the_cores(workers):
    """A pool worker's BLAS runs one thread, and it reads captures in its share of the cores (one thread at
    least, two at most): its siblings take the rest."""
    from mdpipe.batch import runner

    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork"), initializer=runner._start_worker,
                             initargs=(os.getpid(), workers)) as pool:
        blas, readers = pool.submit(_threads).result(timeout=30)
    assert blas == [1]
    assert readers == max(1, min(2, (os.cpu_count() or 1) // workers))


def test_a_forked_worker_ends_on_sigterm_whatever_handler_it_inherited():
    """The command's SIGTERM handler raises to unwind the batch; a worker forked under it must still just end
    when the pool stops it."""
    from mdpipe.batch import runner
    from mdpipe.cli import _stop

    previous = signal.signal(signal.SIGTERM, _stop)
    try:
        with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork"), initializer=runner._start_worker,
                                 initargs=(os.getpid(), 1)) as pool:
            with pytest.raises(BrokenProcessPool):
                pool.submit(_terminate_self).result(timeout=30)
    finally:
        signal.signal(signal.SIGTERM, previous)


FORKED_RUN = """
import sys
from pathlib import Path
from mdpipe.batch import runner, unit
from mdpipe.params import FigureParams, ProcessParams
out, names = sys.argv[1], sys.argv[2:]
print(runner._context([]).get_start_method())
jobs = [unit.Job(name, Path(name).stem, out, ProcessParams(), {"frame_counter": "auto", "overrides": {}},
                 figures=FigureParams()) for name in names]
print(" ".join(o.status for o in runner.run(jobs, workers=2)))
"""


def test_forked_and_fork_server_workers_give_the_same_outputs(tmp_path, monkeypatch):
    """Workers are forked from a process with no other thread (a fresh interpreter here: the test runner may
    hold threads), else started by a fork server; both ways publish the same bytes (tables and figures)."""
    import subprocess
    import sys

    from mdpipe.batch import runner
    from mdpipe.params import FigureParams, ProcessParams

    names = [str(SAMPLES / name) for name in ("phantom4_xband.h5", "gull_flyby.h5")]
    forked = subprocess.run([sys.executable, "-c", FORKED_RUN, str(tmp_path / "fork"), *names], capture_output=True,
                            text=True, timeout=300, check=True)
    assert forked.stdout.split("\n")[:2] == ["fork", "done done"]
    monkeypatch.setattr(runner.threading, "active_count", lambda: 2)
    assert runner._context([]).get_start_method() == "forkserver"
    jobs = [unit.Job(name, Path(name).stem, str(tmp_path / "forkserver"), ProcessParams(),
                     {"frame_counter": "auto", "overrides": {}}, figures=FigureParams()) for name in names]
    assert [o.status for o in runner.run(jobs, workers=2)] == ["done", "done"]
    outputs = {start: {p.relative_to(tmp_path / start).as_posix(): p.read_bytes()
                       for p in (tmp_path / start).rglob("*") if p.is_file() and p.suffix in (".csv", ".png")}
               for start in ("fork", "forkserver")}
    assert len(outputs["fork"]) == 2 * 4  # a table and three figures each
    assert outputs["fork"] == outputs["forkserver"]


def test_gather_reads_published_tables_and_errors_in_one_walk(tmp_path):
    """Tables and error files in nested folders, in path order; nothing inside a temporary folder (a capture
    being published) or named as a temporary file."""
    out = tmp_path / "out"
    for relative, text in (("b/b.features.csv", "file,class\nb.h5,bird\n"),
                           ("a/x/a.features.csv", "file,class,extra\na.h5,drone,1\n"),
                           (".mdpipe-partial-c.abc/c.features.csv", "file,class\nc.h5,none\n"),
                           ("d/.mdpipe-partial-d.features.csv", "file,class\nd.h5,none\n"),
                           ("e/e.error.txt", "e.h5\te.h5: not HDF5\n")):
        (out / relative).parent.mkdir(parents=True, exist_ok=True)
        (out / relative).write_text(text)
    columns, rows, errors = tables.gather(out)
    assert columns == ["file", "class", "extra"]
    assert [row["file"] for row in rows] == ["a.h5", "b.h5"]
    assert errors == [("e.h5", "e.h5: not HDF5")]


def test_a_forked_worker_does_not_keep_out_locked(tmp_path):
    """A worker forked while the run holds OUT's lock closes its copy: the lock goes with the run, not with the
    last worker (after a killed run, a worker can live on for a while)."""
    import fcntl

    from mdpipe.batch import runner

    out = tmp_path / "out"
    pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork"), initializer=runner._start_worker,
                               initargs=(os.getpid(), 1))
    try:
        with runner.locked(out):
            assert pool.submit(os.getpid).result(timeout=30) != os.getpid()  # the worker runs
        fd = os.open(out / runner.LOCK_NAME, os.O_RDWR)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)  # raises BlockingIOError while a worker holds it
        finally:
            os.close(fd)
    finally:
        pool.shutdown(wait=True)
