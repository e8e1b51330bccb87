"""What processing one capture or recording returns (:func:`mdpipe.process.pipeline.process_capture`)."""

from dataclasses import dataclass

from mdpipe import __version__
from mdpipe.process.features import FEATURE_KEYS, STATUS_KEYS


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


def base_row(path, process, params, *, n_samples, clipped, interference, transmitters=1):
    """A row before any target is read into it: the ``none`` row of a capture or recording (every status
    ``no_target``), with the options and the radar's parameters it was read with. ``params``: RadarParams or
    IqParams; ``n_samples``: chirps or I/Q samples; ``clipped``: the share of samples at full scale (None for float
    samples); ``interference``: the share of chirps crossed by another radar's (None where not measured);
    ``transmitters``: the chirps' transmit cycle (the first transmitter's chirps read; 1 for one transmitter)."""
    return {
        "file": str(path), "target": None, "class": "none", "range_m": None, "range_bin": None,
        "range_min_m": None, "range_max_m": None, "rx_gain_db": None, **dict.fromkeys(FEATURE_KEYS),
        **dict.fromkeys(STATUS_KEYS, "no_target"),
        "elevation_deg": process.elevation_deg, "n_blades": process.n_blades,
        "n_blades_source": None if process.n_blades is None else "given", "threshold_db": process.threshold_db,
        "wavelength_m": params.wavelength_m, "prf_hz": params.prf_hz, "transmitters": transmitters,
        "dwell_s": params.duration_s(n_samples),
        "clipped_share": clipped, "interference_share": interference, "mdpipe_version": __version__,
    }
