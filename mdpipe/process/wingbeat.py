"""Wingbeat frequency: the period with which a bird's micro-Doppler signature repeats.

The spectrogram of the body-demodulated echo (body line at 0 Hz, masked) is reduced to the
micro-Doppler spread of each frame, ``sqrt(sum f^2 P / sum P)``: it swells twice per stroke
direction but its pattern repeats once per wingbeat (up- and down-stroke mirror each other in
Doppler, so the signed centroid would report twice the wingbeat). Its period is found as for
rotors (:mod:`mdpipe.process.periodicity`).
"""

import numpy as np

from mdpipe.process.doppler import spectrogram
from mdpipe.process.periodicity import find_period

FRAME_S = 0.064
HOP_S = 0.016
MIN_WINGBEAT_HZ = 0.3
MAX_WINGBEAT_HZ = 20.0


def micro_doppler_spread_hz(spec, *, body_halfwidth_hz):
    """RMS Doppler of each frame outside ``+-body_halfwidth_hz`` (the masked body line), shape (frames,)."""
    power = np.where(np.abs(spec.f_hz)[:, None] < body_halfwidth_hz, 0.0, spec.power)
    total = power.sum(axis=0)
    return np.sqrt((power * spec.f_hz[:, None] ** 2).sum(axis=0) / np.maximum(total, np.finfo(float).tiny))


def wingbeat(demodulated, *, prf_hz):
    """Wingbeat period of a body-demodulated echo, or None. Needs two wingbeats in the dwell."""
    frame_s = min(FRAME_S, len(demodulated) / prf_hz / 8)
    spec = spectrogram(demodulated, prf_hz=prf_hz, window_s=frame_s, hop_s=HOP_S * frame_s / FRAME_S)
    spread = micro_doppler_spread_hz(spec, body_halfwidth_hz=3.0 / spec.window_s)
    frame_rate = 1.0 / spec.hop_s
    return find_period(spread - spread.mean(), sample_rate_hz=frame_rate, min_period_s=1.0 / MAX_WINGBEAT_HZ,
                       max_period_s=1.0 / MIN_WINGBEAT_HZ)
