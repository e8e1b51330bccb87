"""What processing one capture or recording returns (:func:`mdpipe.process.pipeline.process_capture`)."""

from dataclasses import dataclass


@dataclass
class CaptureResult:
    """Rows (one per target, or one ``none`` row), the analyses behind them and the range statistics.

    ``params``: a capture's :class:`~mdpipe.params.RadarParams`, or an I/Q recording's
    :class:`~mdpipe.params.IqParams`; ``stats``: a capture's :class:`~mdpipe.process.ranging.GateStatistics`
    (None for an I/Q recording, which has no range). ``noise_power`` is the receiver noise per chirp and RX (V^2:
    the median moving power over the gate; an I/Q recording's, read from the echo: :mod:`mdpipe.process.cw`),
    which is also that of each target's combined slow time (unit-norm RX weights);
    ``process`` holds the :class:`mdpipe.params.ProcessParams` used; ``detection_test`` the
    :class:`~mdpipe.process.selection.DetectionTest` applied (None with ``--range-m``).
    """

    path: str
    params: object
    layout: str
    stats: object
    detections: list
    analyses: list
    rows: list
    noise_power: float
    process: object
    detection_test: object = None
