"""One capture, read -> analyse -> publish: the unit of work of ``mdpipe process``, ``mdpipe batch`` and the
Dask workers.

Every exception raised while one capture is read, analysed or written ends here as that capture's one-line
error (its traceback kept for the error file and ``--debug``), so the run goes on. Interruptions
(``KeyboardInterrupt``, ``SystemExit``) pass through; :func:`mdpipe.report.tables.publish` then leaves the
capture's published folder as it was.
"""

import os
import shutil
import traceback
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Optional

from mdpipe.batch import manifest
from mdpipe import errors
from mdpipe.errors import MdpipeError
from mdpipe.params import FigureParams, ProcessParams
from mdpipe.process.pipeline import CaptureResult, process_capture
from mdpipe.report import tables

DONE, FAILED, UP_TO_DATE = "done", "failed", "up to date"


@dataclass(frozen=True)
class Job:
    """What to do with one capture.

    Parameters
    ----------
    capture : str
        Input file.
    key : str
        Output folder relative to ``out_dir`` (POSIX path), from :mod:`mdpipe.batch.inputs`.
    out_dir : str or None
        Folder to publish into; None publishes nothing (``process --json`` without ``--out``).
    params : ProcessParams
    reader : dict
        ``frame_counter``, ``overrides`` and ``allow_external`` for :func:`mdpipe.io.open_capture`.
    figures : FigureParams or None
        Draw the per-capture figures with these choices; None: no figures.
    track : bool
        Fingerprint the input for the manifest and skip it when ``previous`` still describes it.
    previous : dict or None
        The manifest record of the last run.
    given : str or None
        The capture's path as the user gave it, for the tables, when ``capture`` had to be made absolute
        (Dask workers run in other folders); None: ``capture``.
    """

    capture: str
    key: str
    out_dir: Optional[str]
    params: ProcessParams
    reader: dict
    figures: Optional[FigureParams] = FigureParams()
    track: bool = False
    previous: Optional[dict] = None
    given: Optional[str] = None

    @property
    def folder(self):
        return Path(self.out_dir) / self.key

    def settings(self):
        """What, besides the input and mdpipe's version, the outputs depend on."""
        return {"process": asdict(self.params), "reader": self.reader,
                "figures": None if self.figures is None else asdict(self.figures)}


@dataclass
class Outcome:
    """What became of one capture: ``status`` is ``done``, ``failed`` or ``up to date`` (``failed`` then tells
    whether the outputs kept are an error); ``record`` is the manifest record of what is published (None when
    nothing is)."""

    capture: str
    key: str
    status: str
    failed: bool
    message: str = ""
    traceback: Optional[str] = None
    rows: list = field(default_factory=list)
    record: Optional[dict] = None


def figures(result):
    """The figures of an analysed capture: ``range`` (not for an I/Q recording, which has no range), and
    ``spectrogram`` and ``spectrum`` where it has targets."""
    ranged = ("range",) if result.stats is not None else ()
    return ranged + (("spectrogram", "spectrum") if result.analyses else ())


def _draw_figure(result, job, figure, folder):
    from mdpipe.report import plots

    path = folder / f"{Path(job.capture).stem}_{figure}.png"
    if figure == "range":
        plots.range_figure(result, path)
    else:
        getattr(plots, f"{figure}_figure")(result, path, job.figures)


def _write_outputs(result, job, folder, staged=None):
    """The tables into ``folder``, and the figures: drawn there, or moved from ``staged`` where :func:`draw`
    drew them."""
    stem = folder / Path(job.capture).stem
    tables.write_features_csv(result.rows, stem.with_name(stem.name + tables.FEATURES_SUFFIX))
    tables.write_run_json(stem.with_name(stem.name + tables.RUN_SUFFIX), capture=job.capture, params=job.params,
                          layout=result.layout, radar=result.params)
    if staged is not None:
        for path in sorted(Path(staged).iterdir()):
            os.replace(path, folder / path.name)
    elif job.figures is not None:
        for figure in figures(result):
            _draw_figure(result, job, figure, folder)


@dataclass
class DrawFailure:
    """Why a figure could not be drawn (:func:`draw`): the capture's one-line error, its traceback, and whether
    it was writing that failed (a full disk) rather than the drawing (a bug)."""

    message: str
    trace: str
    writing: bool


def stage(analysed):
    """A new temporary folder beside ``analysed``'s output folder for :func:`draw` to draw its figures into
    (:func:`mdpipe.report.tables.temporary_folder`: the next run removes it if this one is killed)."""
    return str(tables.temporary_folder(analysed.job.folder))


def draw(analysed, figure, staged):
    """Draw ``figure`` (one of :func:`figures`) of an analysed capture into the folder ``staged``, for
    :func:`publish` to publish with the rest: a pool draws one capture's figures in several workers. Returns
    None, or a :class:`DrawFailure`; never raises an Exception."""
    try:
        _draw_figure(analysed.result, analysed.job, figure, Path(staged))
    except Exception as exc:
        writing = isinstance(exc, OSError)
        return DrawFailure(one_line(analysed.job.capture, exc, writing=writing), _trace(exc), writing)
    return None


def one_line(capture, exc, *, writing=False):
    """The message of a failed capture, on one line, naming the capture."""
    if writing:
        return " ".join(f"{capture}: cannot write its outputs: {exc}".split())
    named = isinstance(exc, (MdpipeError, OSError)) and str(capture) in str(exc)
    return errors.one_line(exc) if named else " ".join(f"{capture}: {errors.one_line(exc)}".split())


def failure(job, message, trace=None, *, keep_trace=False, identity=None):
    """The outcome of a failed capture: its stale outputs replaced by its error file (with ``trace`` when
    ``keep_trace``), or removed when even that cannot be written (the message then says so, with the cause)."""
    outcome = Outcome(job.capture, job.key, FAILED, True, message, trace)
    if job.out_dir is None:
        return outcome
    error_file = job.folder / (Path(job.capture).stem + tables.ERROR_SUFFIX)
    try:
        names = tables.publish(job.folder, lambda tmp: tables.write_error(
            Path(tmp) / error_file.name, job.capture, message, trace if keep_trace else None))
    except Exception as exc:  # a full disk or a read-only folder: say so, keep the original cause
        try:
            tables.unpublish(job.folder)
        except OSError:
            pass
        outcome.message = f"{message}; its error file {error_file} could not be written either: {exc}"
        return outcome
    if keep_trace:
        outcome.message = f"{message} (traceback in {error_file})"
    if identity is not None:
        outcome.record = {**identity, "status": FAILED, "error": message, "outputs": names}
    return outcome


@dataclass
class Analysed:
    """A capture read and analysed, its outputs not yet written: what :func:`draw` and :func:`publish` need
    (a pool draws its figures in other workers than the one that analysed it)."""

    job: Job
    result: CaptureResult
    identity: Optional[dict]


def run(job):
    """Read, analyse and publish ``job``'s capture; returns an :class:`Outcome` and never raises an Exception."""
    step = analyse(job)
    return publish(step) if isinstance(step, Analysed) else step


def analyse(job):
    """Read and analyse ``job``'s capture: an :class:`Analysed` to publish, or the :class:`Outcome` of a capture
    that is up to date or failed (its error file published). Never raises an Exception."""
    identity = None
    try:
        if job.track:
            identity = manifest.identity(job.capture, manifest.fingerprint(job.capture), job.settings())
            if manifest.up_to_date(job.previous, identity, job.folder):
                return Outcome(job.capture, job.key, UP_TO_DATE, job.previous["status"] == FAILED,
                               job.previous.get("error", ""), record=job.previous)
        result = process_capture(job.capture, job.params, **job.reader)
        for row in result.rows:
            row["file"] = job.given or job.capture
    except Exception as exc:
        return failure(job, one_line(job.capture, exc), _trace(exc),
                       keep_trace=not isinstance(exc, (MdpipeError, OSError)), identity=identity)
    return Analysed(job, result, identity)


def publish(analysed, staged=None, drawn=()):
    """Write an analysed capture's tables and figures and publish them together; returns its :class:`Outcome`
    (failed, its error file published instead, when they cannot be written). Never raises an Exception.

    ``staged``: the folder (:func:`stage`) its figures were drawn into (:func:`draw`); they are published
    from there, and it is removed. ``drawn``: the :class:`DrawFailure` s of those that could not be drawn,
    in the figures' order (the first is the capture's error).
    """
    job, result, identity = analysed.job, analysed.result, analysed.identity
    try:
        if drawn:
            return failure(job, drawn[0].message, drawn[0].trace, keep_trace=not drawn[0].writing,
                           identity=identity)
        outcome = Outcome(job.capture, job.key, DONE, False, rows=result.rows)
        if job.out_dir is not None:
            try:
                names = tables.publish(job.folder, lambda tmp: _write_outputs(result, job, Path(tmp), staged))
            except Exception as exc:  # a full disk (OSError), or a figure that cannot be drawn (a bug: keep the trace)
                writing = isinstance(exc, OSError)
                return failure(job, one_line(job.capture, exc, writing=writing), _trace(exc), keep_trace=not writing,
                               identity=identity)
            if identity is not None:
                outcome.record = {**identity, "status": "ok", "outputs": names}
        return outcome
    finally:
        if staged is not None:
            shutil.rmtree(staged, ignore_errors=True)


def _trace(exc):
    return "".join(traceback.format_exception(type(exc), exc, exc.__traceback__))
