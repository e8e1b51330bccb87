"""The folder's summary figure drawn while a pool still draws the captures' own figures.

A batch ends with OUT/summary.png, drawn from its captures' tables in OUT. Drawn after the last capture, it is
time the pool's workers wait out; but it needs only the captures' rows, which are known once every
capture of the run is analysed (or up to date, or failed), before the last figures are drawn. It is drawn
then, in a thread of the batch's process (whose core the pool leaves idle as it ends), from the rows the
tables will hold, and kept only where the tables finally gathered hold exactly those rows (else drawn
again: a capture whose outputs could not be written, a table changed by hand meanwhile).

matplotlib is not thread-safe (its settings are global; :mod:`mdpipe.report.plots` sets some while it draws):
nothing else may draw in the process while the thread does. The batch's own thread only waits on the pool.
"""

from pathlib import Path

from mdpipe.batch import runner
from mdpipe.report import tables


class EarlySummary:
    """Collects the run's analysed rows (``analysed``) and outcomes (``outcome``); once every job has one,
    draws the summary of ``out_dir`` in a thread. :meth:`png` gives it for the rows finally gathered."""

    def __init__(self, out_dir, jobs):
        self.out_dir = out_dir
        self.waiting = {job.key for job in jobs}
        self.folders = [job.folder for job in jobs]  # the batch's own: its summary's (:func:`tables.gather`)
        self.replaced = {}
        self.thread = None
        self.drawn = None  # (rows, png) once drawn

    def analysed(self, step):
        job = step.job  # its table's path as the walk of out_dir names it
        table = Path(self.out_dir) / job.key / (Path(job.capture).stem + tables.FEATURES_SUFFIX)
        self.replaced[table] = step.result.rows
        self._resolved(step.job.key)

    def outcome(self, outcome):
        self._resolved(outcome.key)

    def _resolved(self, key):
        self.waiting.discard(key)
        if not self.waiting and self.thread is None:
            self.thread = runner.start_thread(self._draw)

    def _draw(self):
        from mdpipe.report import plots

        try:
            rows = tables.gathered_rows(self.out_dir, self.replaced, only=self.folders)
            self.drawn = (rows, plots.summary_png(rows) if rows else None)
        except Exception:  # noqa: BLE001 - drawn again at the end, where a failure is reported
            self.drawn = None

    def png(self, rows):
        """The summary drawn early, if it was drawn from ``rows`` (the rows gathered at the end); else None."""
        if self.thread is None:
            return None
        self.thread.join()
        if self.drawn is None or self.drawn[0] != rows:
            return None
        return self.drawn[1]
