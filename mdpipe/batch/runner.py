"""Run many :class:`mdpipe.batch.unit.Job` s: in this process, in a process pool, or on Dask; keep OUT's
manifest and lock.

One process pool (``concurrent.futures.ProcessPoolExecutor``): its workers are forked from this process once
it has imported mdpipe's processing modules, so the imports are paid once, not once per capture or worker
(from a process that runs other threads, or off Linux, a ``forkserver`` that preloads those modules). A
capture with figures is two of its tasks, the analysis and then the figures (see :func:`_pool_round`). A
worker that dies (a segfault, the out-of-memory killer) breaks the pool: the captures it lost are run again
one at a time, each in a fresh worker, so that the one that kills its worker is named (and failed) and the
rest finish.
"""

import collections
import contextlib
import fcntl
import gc
import importlib
import multiprocessing
import os
import select
import shutil
import signal
import sys
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field, replace
from pathlib import Path

from threadpoolctl import threadpool_limits

from mdpipe.batch import manifest, unit
from mdpipe.batch.inputs import LOCK_NAME, OUT_FILES
from mdpipe.process import ranging
from mdpipe.errors import MdpipeError
from mdpipe.report import tables

MANIFEST_INTERVAL_S = 1.0  # the manifest is rewritten at most this often during a run (and at its end)
PRELOAD = ["mdpipe.batch.unit"]
_LOCK_FDS = set()  # OUT's lock, held by this process: a forked worker closes its copy (it must not keep OUT locked)
PRELOAD_FIGURES = ["mdpipe.report.plots"]


class OutputFolderError(MdpipeError):
    """OUT cannot be used (not writable, not a folder)."""


@contextlib.contextmanager
def locked(out_dir, on_wait=None):
    """Hold ``out_dir``'s lock file (flock) for a run; a second run waits, after ``on_wait(message)``."""
    out_dir = Path(out_dir)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        fd = os.open(out_dir / LOCK_NAME, os.O_RDWR | os.O_CREAT, 0o666)  # less the umask
    except OSError as exc:
        raise OutputFolderError(f"{out_dir}: cannot write into this output folder ({exc.strerror}); "
                                "choose a writable --out") from None
    _LOCK_FDS.add(fd)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(fd, 64, 0).decode(errors="replace").strip() or "?"
            if on_wait is not None:
                on_wait(f"{out_dir} is in use by another mdpipe run (pid {holder}); waiting for it to finish")
            fcntl.flock(fd, fcntl.LOCK_EX)
        os.ftruncate(fd, 0)
        os.pwrite(fd, str(os.getpid()).encode(), 0)
        yield
    finally:
        _LOCK_FDS.discard(fd)
        os.close(fd)  # releases the lock


def _watch(parent_pid):
    """Exit as soon as the process ``parent_pid`` has gone (killed by SIGKILL, say): a pool worker holds its
    own queue's write end and would otherwise wait for work forever."""
    try:
        fd = os.pidfd_open(parent_pid)
        select.select([fd], [], [])
    except (AttributeError, OSError):  # no pidfd (not Linux >= 5.3): poll
        while True:
            time.sleep(0.5)
            try:
                os.kill(parent_pid, 0)
            except ProcessLookupError:
                break
            except PermissionError:
                continue
    os._exit(1)


def _start_worker(parent_pid, workers):
    """Ctrl-C reaches the whole process group: the parent decides. SIGTERM (the pool stopping it) ends the
    worker, whatever handler a forked worker inherited; both were blocked from the fork until here. A
    forked worker closes its copy of OUT's lock. A worker ends with the batch's process. Its BLAS runs one
    thread: the pool's workers share the cores, and BLAS threads that wait for work spin on them (the bundled
    samples' analyses took 0.67 s of CPU with two, 0.43 s with one, in the same time alone); it reads and
    transforms with its share of the cores (:func:`mdpipe.process.ranging.share_cores`)."""
    threadpool_limits(limits=1, user_api="blas")
    ranging.share_cores(workers)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, tables.STOP_SIGNALS)
    for fd in list(_LOCK_FDS):
        with contextlib.suppress(OSError):
            os.close(fd)
    _LOCK_FDS.clear()
    threading.Thread(target=_watch, args=(parent_pid,), daemon=True).start()


def _stop_workers(executor):
    for process in list((getattr(executor, "_processes", None) or {}).values()):
        with contextlib.suppress(OSError):
            process.terminate()


def _context(preload):
    """How the pool starts its workers: forked from this process with ``preload`` imported, where that is safe
    (Linux, and no other Python thread, whose locks a fork would copy held; numpy's OpenBLAS threads
    prepare for a fork themselves, and no capture is open in this process); else from a fork server that
    imports ``preload`` once (a fresh interpreter: 0.05 s more, and the imports paid a second time)."""
    if sys.platform == "linux" and threading.active_count() == 1:
        for name in preload:
            importlib.import_module(name)
        return multiprocessing.get_context("fork")
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(preload)
    return context


def start_thread(target):
    """Run ``target`` in a daemon thread that leaves SIGINT and SIGTERM to the main thread (Python runs their
    handlers there; a thread the kernel picked to take them would let a stop through
    :func:`mdpipe.report.tables.stops_deferred`)."""
    with tables.stops_deferred():
        thread = threading.Thread(target=target, daemon=True)
        thread.start()
    return thread


@dataclass
class _Staged:
    """An analysed capture whose figures the pool is drawing into ``folder``: ``left`` of them to come."""

    step: unit.Analysed
    folder: str
    left: int
    failures: dict = field(default_factory=dict)


def _pool_round(jobs, workers, started, analysed):
    """Yield the outcomes of ``jobs`` from one pool; return the jobs lost when a worker died (those it held,
    and those not yet run: the pool is broken).

    A capture with figures is several tasks: its analysis, then one per figure (:func:`mdpipe.batch.unit.draw`,
    into a temporary folder), after which this process publishes it. Only ``workers`` tasks are handed to the
    pool at a time, figures before the next analysis: each capture is published soon after its analysis (an
    interrupted run keeps what it did, and this process holds no more than a few analyses), and the workers
    share the last captures' figures instead of one drawing them while the others idle. ``analysed(step)``
    hears of each :class:`mdpipe.batch.unit.Analysed` as it returns.

    Before a fork, this process's objects are moved out of the collector's reach until the pool ends
    (``gc.freeze``, unless something froze them already): a worker's first full collection walked all 74 000
    of them (45 ms), touching and so copying their pages (a batch of the samples 2 % sooner).
    """
    context = _context(PRELOAD + (PRELOAD_FIGURES if any(job.figures is not None for job in jobs) else []))
    frozen = context.get_start_method() == "fork" and gc.get_freeze_count() == 0
    if frozen:
        gc.freeze()
    try:
        executor = ProcessPoolExecutor(max_workers=workers, mp_context=context, initializer=_start_worker,
                                       initargs=(os.getpid(), workers))
    except BaseException:
        if frozen:
            gc.unfreeze()
        raise
    waiting, ready, running, staged, lost, finished = collections.deque(jobs), collections.deque(), {}, {}, [], False

    def fill():
        """Hand the pool tasks up to ``workers``: figures first, then analyses; none once it is broken."""
        try:
            while len(running) < workers and not lost and (ready or waiting):
                if ready:
                    job, figure = ready.popleft()
                    task, arguments = unit.draw, (staged[job.key].step, figure, staged[job.key].folder)
                else:  # a capture without figures to publish is one task
                    job, figure = waiting.popleft(), None
                    task, arguments = (unit.run if job.figures is None or job.out_dir is None else unit.analyse), (job,)
                with tables.stops_deferred():  # the workers are forked (or started) in submit
                    running[executor.submit(task, *arguments)] = (job, figure)
        except BrokenProcessPool:
            lost.append(job)

    def finished_task(job, figure, result):
        """The outcome ``result`` completes, if any."""
        if figure is None and not isinstance(result, unit.Analysed):
            return result
        if figure is None:
            analysed(result)
            names = unit.figures(result.result)
            try:
                staged[job.key] = _Staged(result, unit.stage(result), len(names))
            except OSError as exc:  # no temporary folder (a full disk, a read-only OUT); nothing drawn here
                return unit.failure(job, unit.one_line(job.capture, exc, writing=True), identity=result.identity)
            ready.extend((job, name) for name in names)
            return None
        entry = staged[job.key]
        entry.left -= 1
        if result is not None:
            entry.failures[figure] = result
        if entry.left:
            return None
        del staged[job.key]  # the failures in the figures' order, as one task drawing them all would meet them
        failures = [entry.failures[name] for name in unit.figures(entry.step.result) if name in entry.failures]
        return unit.publish(entry.step, entry.folder, failures)

    try:
        fill()
        started()
        while running:
            done, _ = wait(running, return_when=FIRST_COMPLETED)
            outcomes = []
            for future in done:
                job, figure = running.pop(future)
                try:
                    outcome = finished_task(job, figure, future.result())
                except BrokenProcessPool:
                    if job not in lost:
                        lost.append(job)
                    continue
                if outcome is not None:
                    outcomes.append(outcome)
            fill()
            yield from outcomes
        finished = True
    finally:
        if not finished:
            _stop_workers(executor)
        executor.shutdown(wait=True, cancel_futures=True)
        if frozen:
            gc.unfreeze()
        for entry in staged.values():  # the pool broke, or the run was stopped, while they were drawn
            shutil.rmtree(entry.folder, ignore_errors=True)
    lost += [entry.step.job for entry in staged.values() if entry.step.job not in lost]
    return lost + list(waiting)


def _largest_first(jobs):
    """``jobs`` by input size, largest first (stable): the longest captures start first, so that no worker is
    left with a long one at the end while the others idle."""
    def size(job):
        try:
            return os.stat(job.capture).st_size
        except OSError:  # gone or unreadable: its job fails quickly
            return 0
    return sorted(jobs, key=size, reverse=True)


def _pool(jobs, workers, started, analysed):
    queue, alone = _largest_first(jobs), False
    while queue:
        round_jobs, queue = (queue[:1], queue[1:]) if alone else (queue, [])
        lost = yield from _pool_round(round_jobs, 1 if alone else min(workers, len(round_jobs)), started, analysed)
        started = _nothing
        if lost and alone:
            yield unit.failure(lost[0], f"{lost[0].capture}: its worker process died (killed by the system, out "
                                        "of memory say, or a crash inside a library)")
        elif lost:
            alone, queue = True, lost + queue


def _nothing(*_):
    pass


def execute(jobs, *, workers=1, scheduler=None, started=_nothing, analysed=_nothing):
    """Yield the :class:`mdpipe.batch.unit.Outcome` of every job as it finishes (in any order).

    ``scheduler`` None: in this process for one worker, else a process pool of ``workers``; ``local`` or a
    ``tcp://host:port`` address: Dask (:mod:`mdpipe.batch.dask_runner`). ``started()`` is called once the
    work is under way (after the pool's workers are forked: it may start threads); ``analysed(step)`` with
    each :class:`mdpipe.batch.unit.Analysed` capture before its figures are drawn (pool only).
    """
    if scheduler is not None:
        from mdpipe.batch import dask_runner

        started()
        yield from dask_runner.execute(jobs, scheduler=scheduler, workers=workers)
    elif workers == 1 or len(jobs) == 1:
        started()
        for job in jobs:
            yield unit.run(job)
    else:
        yield from _pool(jobs, workers, started, analysed)


def _save(out_dir, records, notify):
    try:
        manifest.save(out_dir, records)
    except OSError as exc:  # the outputs stand; the next run redoes what the manifest could not record
        if notify is not None:
            notify(f"Warning: cannot write {Path(out_dir) / manifest.MANIFEST_NAME} ({exc}); the next run will "
                   "redo the captures it does not list")


def run(jobs, *, workers=1, scheduler=None, track=False, on_outcome=None, notify=None, finish=None,
        started=_nothing, analysed=_nothing):
    """Run ``jobs`` (all with one ``out_dir``, or None) under OUT's lock; returns their outcomes.

    With ``track`` the manifest decides what is redone and is updated as captures finish; without, the
    manifest forgets the captures published (they were made with other settings). Temporary folders left by an
    earlier interrupted or killed run are removed first. ``notify(text)`` hears of waits and warnings;
    ``finish(outcomes)`` runs at the end, still under the lock (the folder's summary); ``started()`` once the
    work is under way, ``analysed(step)`` as a capture's analysis returns (see :func:`execute`).
    """
    out_dir = jobs[0].out_dir if jobs else None
    if out_dir is None:
        stream = execute(jobs, workers=workers, scheduler=scheduler, started=started, analysed=analysed)
        return [_report(outcome, on_outcome) for outcome in stream]
    leftovers = [job.folder for job in jobs] + [Path(out_dir) / name for name in OUT_FILES]
    with locked(out_dir, notify):
        tables.remove_partials(leftovers)
        records = manifest.load(out_dir)
        for job in jobs:
            before = records.get(job.key, {}).get("input") or tables.published_input(job.folder)
            if notify is not None and before not in (None, str(Path(job.capture).resolve())):
                notify(f"Warning: {job.folder} held the outputs of {before}; now those of {job.capture}")
        if track:
            jobs = [replace(job, track=True, previous=records.get(job.key)) for job in jobs]
        outcomes, saved_at, interval_s = [], time.monotonic(), MANIFEST_INTERVAL_S
        try:
            with contextlib.closing(execute(jobs, workers=workers, scheduler=scheduler, started=started,
                                                  analysed=analysed)) as stream:
                for outcome in stream:
                    if outcome.record is not None:
                        records[outcome.key] = outcome.record
                    else:
                        records.pop(outcome.key, None)
                    if track and time.monotonic() - saved_at > interval_s:
                        began = time.monotonic()
                        _save(out_dir, records, notify)
                        saved_at = time.monotonic()
                        interval_s = max(MANIFEST_INTERVAL_S, 10 * (saved_at - began))  # <= 10 % of the run
                    outcomes.append(_report(outcome, on_outcome))
            if finish is not None:
                finish(outcomes)
        finally:
            if track or (Path(out_dir) / manifest.MANIFEST_NAME).exists():
                _save(out_dir, records, notify)
            if scheduler is None:
                tables.remove_partials(leftovers)
    return outcomes


def _report(outcome, on_outcome):
    if on_outcome is not None:
        on_outcome(outcome)
    return outcome
