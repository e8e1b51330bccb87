"""Wingbeat frequency: the period with which a bird's micro-Doppler pattern repeats.

The log-spectrogram of the body-demodulated echo (body line at 0 Hz) is detrended along time in
each Doppler row (a running mean over the longest wingbeat searched removes the slow change of a
fly-by) and autocorrelated along time, summed over the rows: a whole Doppler pattern, signed, so
the up- and down-strokes, which mirror each other, do not pass for two wingbeats. The fundamental
is then found as for rotors (:mod:`mdpipe.process.periodicity`).

The rows read are those lit (``SIGNAL_ROW_DB`` over the noise) in half the frames; a bird that glides
between flapping bursts lights its wing rows only while it flaps, so where those rows show no wingbeat
seen to repeat, the rows lit in a quarter of the frames are read. (Read first, those rows add the
bursts' on and off to the pattern of a bird that flaps most of the dwell, and a heron and a goose lost
their wingbeat.)

A period whose repeat the record cannot hold (two periods in the dwell) is taken only at twice the
strength of one seen to repeat, and it gives way to a shorter period of the same pattern that is seen
to repeat: the cycle of a bird flapping 1 s and gliding 0.5 s repeats whole (a crow read at 0.66 Hz,
its flap-glide cycle, for 3.97 Hz), the wingbeats within it repeat too.

Where neither row set gives a period, a bird whose bursts hold only a few beats (the glides between
them decay the whole record's pattern below the repeat test) is read over its flapping frames only
(:func:`gated_pattern_autocorrelation`): four geese and a pigeon of the evaluation sweep, `none` before.
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
MIN_PERIODICITY = 0.2         # autocorrelation prominence a wingbeat needs
MIN_SINGLE_PERIODICITY = 0.4  # ... when the record holds only two wingbeats and the repeat cannot be seen
SHORTER_SHARE = 1 / 3         # a single-repeat period gives way to a repeating one up to a third of it
FLAP_SMOOTH_S = 0.25          # flapping frames: the wing rows' lit share averaged over this ...
FLAP_SHARE = 0.5              # ... reaches this share of its 95th percentile
MIN_GLIDE_SHARE = 0.1         # the gated look reads a bird that glides in this share of the dwell at least
MIN_PAIRED_SHARE = 0.5        # ... and a period that half its flapping frames see repeat (two beats in a row)


def _lit_rows(spec, noise_level, row_percentile):
    """The Doppler rows within ``MAX_MICRO_DOPPLER_HZ`` whose power stands ``SIGNAL_ROW_DB`` above
    ``noise_level`` (per bin) in ``100 - row_percentile`` % of the frames."""
    power = spec.power[np.abs(spec.f_hz) <= MAX_MICRO_DOPPLER_HZ]
    return power[np.percentile(power, row_percentile, axis=1) > noise_level * 10 ** (SIGNAL_ROW_DB / 10)]


def _lag_products(rows):
    """Sum over lags 0 .. n - 1 of ``x(t) x(t + lag)`` of each row of ``rows`` (FFT based, not normalised)."""
    n = rows.shape[-1]
    return np.fft.irfft(np.abs(np.fft.rfft(rows, n=2 * n, axis=-1)) ** 2, axis=-1)[..., :n]


def pattern_autocorrelation(spec, *, detrend_frames, noise_level, row_percentile=50):
    """Time autocorrelation of the detrended log-spectrogram, summed over Doppler, normalised (unbiased).

    Only Doppler rows whose power stands ``SIGNAL_ROW_DB`` above ``noise_level`` (per bin) in
    ``100 - row_percentile`` % of the frames take part: rows of noise would only dilute the pattern.
    """
    power = _lit_rows(spec, noise_level, row_percentile)
    if len(power) == 0:
        return np.zeros(spec.power.shape[1])
    rows = np.log(power + np.finfo(float).tiny)
    rows = rows - moving_average(rows, max(1, detrend_frames), axis=1)
    n = rows.shape[1]
    r = _lag_products(rows).sum(axis=0) / np.arange(n, 0, -1)
    return r / r[0] if r[0] > 0 else r


def flapping_frames(rows, *, noise_level, frame_rate):
    """Frames in which a bird flaps: where the share of ``rows`` (its wing rows) lit ``SIGNAL_ROW_DB`` above
    ``noise_level``, averaged over ``FLAP_SMOOTH_S``, reaches ``FLAP_SHARE`` of its 95th percentile (the
    strokes light the rows unevenly within a beat; a glide leaves them dark)."""
    lit = (rows > noise_level * 10 ** (SIGNAL_ROW_DB / 10)).mean(axis=0)
    smooth = moving_average(lit, max(1, int(round(FLAP_SMOOTH_S * frame_rate))))
    return smooth >= FLAP_SHARE * np.percentile(smooth, 95)


def gated_pattern_autocorrelation(spec, *, noise_level, frame_rate):
    """The pattern autocorrelation of a bird that glides between flapping bursts, over its bursts only.

    The rows lit in a quarter of the frames are read in the frames :func:`flapping_frames` marks, each
    burst less its own mean per row (the bursts' on and off are no pattern); the products of each lag are
    averaged over the pairs of flapping frames that lag apart. Returns ``(r, paired)``: ``r`` normalised
    to 1 at lag 0, up to the last lag resting on ``FLAP_SMOOTH_S`` of pairs, and ``paired`` the share of
    the flapping frames with a flapping partner that lag on; None where the rows show no glide (frames
    not flapping in under ``MIN_GLIDE_SHARE`` of the dwell), flapping for under ``FLAP_SMOOTH_S``, or no lit
    row.
    """
    rows = _lit_rows(spec, noise_level, SIGNAL_ROW_PERCENTILES[-1])
    if len(rows) == 0:
        return None
    flapping = flapping_frames(rows, noise_level=noise_level, frame_rate=frame_rate)
    if not flapping.any() or flapping.mean() > 1 - MIN_GLIDE_SHARE:
        return None
    rows = np.log(rows + np.finfo(float).tiny)
    bursts = np.flatnonzero(np.diff(np.concatenate([[0], flapping.astype(int), [0]]))).reshape(-1, 2)
    centred = np.zeros_like(rows)
    for start, stop in bursts:
        centred[:, start:stop] = rows[:, start:stop] - rows[:, start:stop].mean(axis=1, keepdims=True)
    pairs = np.rint(_lag_products(flapping.astype(float)))
    too_few = pairs < max(1.0, FLAP_SMOOTH_S * frame_rate)
    if too_few[0]:
        return None
    usable = int(np.argmax(too_few)) or len(pairs)
    r = _lag_products(centred).sum(axis=0)[:usable] / pairs[:usable]
    return (r / r[0] if r[0] > 0 else r), pairs[:usable] / pairs[0]


def _period(r, *, frame_rate):
    """The wingbeat period in a pattern autocorrelation ``r`` (a Period or None): a single-repeat period gives way
    to a shorter one, up to ``SHORTER_SHARE`` of it, seen to repeat with ``MIN_PERIODICITY``."""
    def up_to(max_period_s):
        return period_from_autocorrelation(r, sample_rate_hz=frame_rate, min_period_s=1.0 / MAX_WINGBEAT_HZ,
                                           max_period_s=max_period_s, repeat_share=REPEAT_SHARE)

    found = up_to(1.0 / MIN_WINGBEAT_HZ)
    if found is not None and found.repeats == 1:
        shorter = up_to(SHORTER_SHARE * found.period_s)
        if shorter is not None and shorter.repeats >= 2 and shorter.strength >= MIN_PERIODICITY:
            return shorter
    return found


def wingbeat(demodulated, *, prf_hz, noise_power, band_hz=None):
    """Wingbeat period of a body-demodulated echo (noise ``noise_power`` per chirp): a
    :class:`~mdpipe.process.periodicity.Period`, or None.

    The spectrogram frame is ``FRAME_S``, or shorter where the micro-Doppler band (``band_hz`` wide) still
    holds ``BAND_BINS`` Doppler bins at the shorter frame (down to ``MIN_FRAME_S``). Each row set of
    ``SIGNAL_ROW_PERCENTILES`` gives a period; the first seen to repeat with ``MIN_PERIODICITY`` is taken,
    else the first whose repeat the record cannot hold (two wingbeats in the dwell) with
    ``MIN_SINGLE_PERIODICITY``, else the period within flapping bursts (:func:`_gated_period`).
    """
    frame_s = min(FRAME_S, len(demodulated) / prf_hz / 8)
    if band_hz:
        frame_s = min(frame_s, max(MIN_FRAME_S, BAND_BINS / band_hz))
    hop_s = HOP_S * frame_s / FRAME_S
    spec = spectrogram(demodulated, prf_hz=prf_hz, window_s=frame_s, hop_s=hop_s)
    frame_rate = 1.0 / spec.hop_s
    noise_level = noise_level_per_bin(noise_power, int(round(spec.window_s * prf_hz)))
    single = None
    for row_percentile in SIGNAL_ROW_PERCENTILES:
        r = pattern_autocorrelation(spec, detrend_frames=int(2 * frame_rate / MIN_WINGBEAT_HZ),
                                    noise_level=noise_level, row_percentile=row_percentile)
        found = _period(r, frame_rate=frame_rate)
        if found is None:
            continue
        if found.repeats >= 2 and found.strength >= MIN_PERIODICITY:
            return found
        if found.repeats == 1 and found.strength >= MIN_SINGLE_PERIODICITY and single is None:
            single = found
    return single or _gated_period(spec, noise_level=noise_level, frame_rate=frame_rate)


def _gated_period(spec, *, noise_level, frame_rate):
    """The wingbeat within the flapping bursts of a bird that glides between them (a Period or None).

    Read on :func:`gated_pattern_autocorrelation`, with the gates of the other looks; the repeat is looked
    for at 2T only (a burst holds few beats and the wingbeat drifts between bursts), and the period must
    repeat within the bursts in ``MIN_PAIRED_SHARE`` of the flapping frames.
    """
    gated = gated_pattern_autocorrelation(spec, noise_level=noise_level, frame_rate=frame_rate)
    if gated is None:
        return None
    r, paired = gated
    found = period_from_autocorrelation(r, sample_rate_hz=frame_rate, min_period_s=1.0 / MAX_WINGBEAT_HZ,
                                        max_period_s=1.0 / MIN_WINGBEAT_HZ, repeat_share=REPEAT_SHARE, max_order=2)
    if found is None or paired[found.peak_lag] < MIN_PAIRED_SHARE:
        return None
    needed = MIN_PERIODICITY if found.repeats >= 2 else MIN_SINGLE_PERIODICITY
    return found if found.strength >= needed else None
