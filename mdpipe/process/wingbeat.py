"""Wingbeat frequency: the period with which a bird's micro-Doppler pattern repeats.

The log-spectrogram of the body-demodulated echo (body line at 0 Hz) is detrended along time in
each Doppler row (a running mean over the longest wingbeat searched removes the slow change of a
fly-by) and autocorrelated along time, summed over the rows: a whole Doppler pattern, signed, so
the up- and down-strokes, which mirror each other, do not pass for two wingbeats. The fundamental
is then found as for rotors (:mod:`mdpipe.process.periodicity`).

The rows read are those lit (``SIGNAL_ROW_DB`` over the noise) in half the frames; a bird that glides
between flapping bursts lights its wing rows only while it flaps, so where those rows show no wingbeat,
the rows lit in a quarter of the frames are read. (Read first, those rows add the bursts' on and off to
the pattern of a bird that flaps most of the dwell, and two herons and geese lost their wingbeat.)
"""

import numpy as np
from mdpipe.process.doppler import noise_level_per_bin, spectrogram
from mdpipe.process.filters import moving_average
from mdpipe.process.periodicity import period_from_autocorrelation

FRAME_S = 0.064
HOP_S = 0.016
MIN_FRAME_S = 0.016
BAND_BINS = 48        # a frame resolves the micro-Doppler band into this many bins, no more: shorter frames
                      # follow faster wingbeats (a 15 Hz beat lasts one 64 ms frame)
MIN_WINGBEAT_HZ = 0.3
MAX_WINGBEAT_HZ = 20.0
MAX_MICRO_DOPPLER_HZ = 2000.0  # rows kept: wings move at a few m/s (< 2 kHz even at 76 GHz)
SIGNAL_ROW_DB = 10.0
SIGNAL_ROW_PERCENTILES = (50, 75)  # rows lit in half the frames, then in a quarter (flapping between glides)
REPEAT_SHARE = 0.8  # repeats looked for up to 80 % of the record: three wingbeats show their repeat at 2T


def pattern_autocorrelation(spec, *, detrend_frames, noise_level, row_percentile=50):
    """Time autocorrelation of the detrended log-spectrogram, summed over Doppler, normalised (unbiased).

    Only Doppler rows whose power stands ``SIGNAL_ROW_DB`` above ``noise_level`` (per bin) in
    ``100 - row_percentile`` % of the frames take part: rows of noise would only dilute the pattern.
    """
    power = spec.power[np.abs(spec.f_hz) <= MAX_MICRO_DOPPLER_HZ]
    power = power[np.percentile(power, row_percentile, axis=1) > noise_level * 10 ** (SIGNAL_ROW_DB / 10)]
    if len(power) == 0:
        return np.zeros(spec.power.shape[1])
    rows = np.log(power + np.finfo(float).tiny)
    rows = rows - moving_average(rows, max(1, detrend_frames), axis=1)
    n = rows.shape[1]
    spectra = np.fft.rfft(rows, n=2 * n, axis=1)
    r = np.fft.irfft(np.abs(spectra) ** 2, axis=1)[:, :n].sum(axis=0) / np.arange(n, 0, -1)
    return r / r[0] if r[0] > 0 else r


def wingbeats(demodulated, *, prf_hz, noise_power, band_hz=None):
    """Wingbeat periods of a body-demodulated echo (noise ``noise_power`` per chirp): for each row set of
    ``SIGNAL_ROW_PERCENTILES`` in turn, a :class:`~mdpipe.process.periodicity.Period` or None (a generator:
    the caller stops at the first it accepts).

    The spectrogram frame is ``FRAME_S``, or shorter where the micro-Doppler band (``band_hz`` wide) still
    holds ``BAND_BINS`` Doppler bins at the shorter frame (down to ``MIN_FRAME_S``).

    Needs two wingbeats in the dwell; with fewer than three the period cannot be seen to repeat
    (``repeats`` is 1) and the caller asks more of its strength.
    """
    frame_s = min(FRAME_S, len(demodulated) / prf_hz / 8)
    if band_hz:
        frame_s = min(frame_s, max(MIN_FRAME_S, BAND_BINS / band_hz))
    hop_s = HOP_S * frame_s / FRAME_S
    spec = spectrogram(demodulated, prf_hz=prf_hz, window_s=frame_s, hop_s=hop_s)
    frame_rate = 1.0 / spec.hop_s
    noise_level = noise_level_per_bin(noise_power, int(round(spec.window_s * prf_hz)))
    for row_percentile in SIGNAL_ROW_PERCENTILES:
        r = pattern_autocorrelation(spec, detrend_frames=int(2 * frame_rate / MIN_WINGBEAT_HZ),
                                    noise_level=noise_level, row_percentile=row_percentile)
        yield period_from_autocorrelation(r, sample_rate_hz=frame_rate, min_period_s=1.0 / MAX_WINGBEAT_HZ,
                                          max_period_s=1.0 / MIN_WINGBEAT_HZ, repeat_share=REPEAT_SHARE)
