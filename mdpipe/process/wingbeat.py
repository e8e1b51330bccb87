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
them decay the whole record's pattern below the repeat test) is read within its flapping bursts only
(:func:`gated_pattern_autocorrelation`): four geese and a pigeon of the evaluation sweep, `none` before.
Where the whole record gives the period of a bird that glides, the bursts measure it again where their peaks
line up more closely (:func:`_within_bursts`): the switches to gliding shift the whole record's peaks.

A period under four frames is blurred by the frame (its lags lie within the frames' own overlap, and
its peak can be missed for its double): it is read again with frames of a quarter of it (a sparrow
beating 14.6 Hz in 63 ms frames read 7.6 % off, and at 14 Hz at X band as 7 Hz). Where that look finds twice the
period, the wingbeat is one of the two (:class:`Octave`).
"""

import functools
from dataclasses import dataclass, replace

import numpy as np
from mdpipe.process.doppler import Spectrogram, noise_level_per_bin, spectrogram
from mdpipe.process.filters import moving_average
from mdpipe.process.periodicity import Period, bartlett_error, best_near, period_from_autocorrelation, refine_period

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
PAIR_SIGMAS = 3.0             # ... a period standing this many standard errors of its lag's mean (Bartlett's)
MIN_WING_ROWS = 3             # ... in this many Doppler rows at least (one or two lit rows are lines, not wings)
BLURRED_FRAMES = 4            # a period under this many frames is read again in frames of a quarter of it ...
BLUR_AGREEMENT = 0.15         # ... where it, or half of it, is found within this share (else withheld)
BURST_AGREEMENT = 0.05        # a whole-record period is measured again within the bursts where found within this
SHORT_BURST_BEATS = 3.0       # a gliding bird's longest burst under this many periods: its repeat at 2T holds under a
                              # beat of flapping pairs (:func:`_short_bursts`)
CYCLE_SHARE = 0.9             # a whole-record period this share of the flap-glide cycle or longer is no wingbeat
GLIDE_DROP_DB = 10.0          # a glide: the wing rows this far under their level while flapping ...
BODY_STEADY_DB = 3.0          # ... while the body line holds within this of its own
BODY_BINS = 2                 # the body line: the Doppler bins this close to 0 Hz (the body demodulated there),
                              # the Hann window's main lobe to its nulls: wing rows dark in a glide lie beyond
BODY_LOBE_BINS = 1.5          # ... the rows it lights by itself: 6 dB down 1 bin off, 15 dB down 1.5 bins off
WEAK_MERGE_BINS = 4           # where fewer than MIN_WING_ROWS rows are lit: the bins averaged four at a time ...
WEAK_ROW_DB = 3.0             # ... and a cell lit this far over the noise (noise's 4-bin mean passes it in 6 % of
                              # the frames, its 75th percentile over a dwell's frames 1.3x the noise: never)
LEAKAGE_DB = -10.0            # ... from where the body line's window leakage falls this far under the noise
SCALLOP_LOSS_DB = 1.42        # a line half a bin off its bin reads this much under its peak there (Hann)
SIDE_REPEAT = 0.5             # a stroke side's rows repeating at T under this, ...
SIDE_DOUBLE_SHARE = 0.15      # ... and at 2T this much more: T is half the wingbeat's period
REACH_SPAN_SHARE = 0.8        # weak rows' reach is read only where it ends within this share of the span's half
STROKE_FRAME_S = 0.05         # a stroke's reach read in frames a rotor at 20 rev/s turns once in at least ...
MIN_STROKE_FRAMES = 8         # ... and this many frames with a wing row lit


def _lit_level(noise_level, lit_db=SIGNAL_ROW_DB):
    """The power of a lit cell: ``lit_db`` above ``noise_level`` (per bin)."""
    return noise_level * 10 ** (lit_db / 10)


def _frames_per_window(spec):
    """How many hops a spectrogram frame spans: frames this many apart or fewer share chirps."""
    return int(round(spec.window_s / spec.hop_s))


def _lit_mask(spec, noise_level, row_percentile, *, off_hz=-1.0, lit_db=SIGNAL_ROW_DB, max_hz=MAX_MICRO_DOPPLER_HZ,
              floor=None):
    """Which Doppler rows of ``spec``, within ``max_hz`` and beyond ``off_hz``, are lit (:func:`_lit_level`) in
    ``100 - row_percentile`` % of the frames, and above ``floor`` (a power per row) there where given."""
    distance_hz = np.abs(spec.f_hz)
    mask = (distance_hz <= max_hz) & (distance_hz > off_hz)
    level = _lit_level(noise_level, lit_db)
    if floor is not None:
        level = np.maximum(level, floor[mask])
    mask[mask] = np.percentile(spec.power[mask], row_percentile, axis=1) > level
    return mask


def _lit_rows(spec, noise_level, row_percentile, *, off_hz=-1.0, lit_db=SIGNAL_ROW_DB, floor=None):
    """The Doppler rows within ``MAX_MICRO_DOPPLER_HZ`` (and beyond ``off_hz``) lit (:func:`_lit_level`) in
    ``100 - row_percentile`` % of the frames (and above ``floor``, a power per row, where given)."""
    return spec.power[_lit_mask(spec, noise_level, row_percentile, off_hz=off_hz, lit_db=lit_db, floor=floor)]


def _body_hz(spec, bins=BODY_BINS):
    """How far from 0 Hz the body line (demodulated there) reaches in ``spec``: ``bins`` Doppler bins."""
    return bins * (spec.f_hz[1] - spec.f_hz[0])


def _dwell_frame_s(demodulated, *, prf_hz):
    """The spectrogram frame read first: ``FRAME_S``, or an eighth of the dwell where that is shorter."""
    return min(FRAME_S, len(demodulated) / prf_hz / 8)


def dwell_frames(demodulated, *, prf_hz, noise_power):
    """The dwell's spectrogram read for wings as a whole, of ``FRAME_S`` frames (an eighth of the dwell at most), and
    its noise level per bin: what :func:`flap_glide_share`, :func:`stroke_swing` and :func:`weak_reach_hz` read."""
    return _frames(demodulated, prf_hz=prf_hz, noise_power=noise_power,
                   frame_s=_dwell_frame_s(demodulated, prf_hz=prf_hz))


def _frames(demodulated, *, prf_hz, noise_power, frame_s):
    """The spectrogram of ``frame_s`` frames (hop a quarter of it) and its noise level per bin."""
    spec = spectrogram(demodulated, prf_hz=prf_hz, window_s=frame_s, hop_s=HOP_S * frame_s / FRAME_S)
    return spec, noise_level_per_bin(noise_power, int(round(spec.window_s * prf_hz)))


def _lag_products(rows):
    """Sum over lags 0 .. n - 1 of ``x(t) x(t + lag)`` of each row of ``rows`` (FFT based, not normalised)."""
    n = rows.shape[-1]
    return np.fft.irfft(np.abs(np.fft.rfft(rows, n=2 * n, axis=-1)) ** 2, axis=-1)[..., :n]


def pattern_autocorrelation(spec, *, detrend_frames, noise_level, row_percentile=50, lit_db=SIGNAL_ROW_DB):
    """Time autocorrelation of the detrended log-spectrogram, summed over Doppler, normalised (unbiased).

    Only Doppler rows whose power stands ``lit_db`` above ``noise_level`` (per bin) in
    ``100 - row_percentile`` % of the frames take part: rows of noise would only dilute the pattern.
    """
    power = _lit_rows(spec, noise_level, row_percentile, lit_db=lit_db)
    if len(power) == 0:
        return np.zeros(spec.power.shape[1])
    return _rows_autocorrelation(power, detrend_frames=detrend_frames)


def _rows_autocorrelation(power, *, detrend_frames):
    """Time autocorrelation of the log of Doppler rows ``power`` (rows, frames), each less its moving average over
    ``detrend_frames``, summed over the rows, unbiased, normalised at lag 0 (left as it is where that is 0)."""
    rows = np.log(power + np.finfo(float).tiny)
    rows = rows - moving_average(rows, max(1, detrend_frames), axis=1)
    n = rows.shape[1]
    r = _lag_products(rows).sum(axis=0) / np.arange(n, 0, -1)
    return r / r[0] if r[0] > 0 else r


def flapping_frames(rows, *, noise_level, frame_rate, lit_db=SIGNAL_ROW_DB):
    """Frames in which a bird flaps: where the share of ``rows`` (its wing rows) lit ``lit_db`` above
    ``noise_level``, averaged over ``FLAP_SMOOTH_S`` (an odd number of frames, centred), reaches ``FLAP_SHARE``
    of its 95th percentile (the strokes light the rows unevenly within a beat; a glide leaves them dark)."""
    lit = (rows > _lit_level(noise_level, lit_db)).mean(axis=0)
    smooth = moving_average(lit, 2 * int(round(FLAP_SMOOTH_S * frame_rate / 2)) + 1)
    return smooth >= FLAP_SHARE * np.percentile(smooth, 95)


def bursts(flapping):
    """``(start, stop)`` frame index pairs of the runs of True in ``flapping``."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], np.asarray(flapping, dtype=int), [0]])))
    return edges.reshape(-1, 2)


def _gliding(spec, *, noise_level, frame_rate, lit_db=SIGNAL_ROW_DB):
    """The rows of ``spec`` lit in a quarter of the frames and the frames in which they flap
    (:func:`flapping_frames`), where a bird glides between bursts; None where fewer than ``MIN_WING_ROWS`` rows are
    lit, or the rows flap throughout but ``MIN_GLIDE_SHARE`` of the dwell, or never."""
    rows = _lit_rows(spec, noise_level, SIGNAL_ROW_PERCENTILES[-1], lit_db=lit_db)
    if len(rows) < MIN_WING_ROWS:
        return None
    flapping = flapping_frames(rows, noise_level=noise_level, frame_rate=frame_rate, lit_db=lit_db)
    if not flapping.any() or flapping.mean() > 1 - MIN_GLIDE_SHARE:
        return None
    return rows, flapping


def gated_pattern_autocorrelation(spec, *, noise_level, frame_rate, lit_db=SIGNAL_ROW_DB):
    """The pattern autocorrelation of a bird that glides between flapping bursts, within its bursts only.

    The rows lit in a quarter of the frames (``MIN_WING_ROWS`` of them at least) are read in the bursts
    :func:`flapping_frames` marks, less the frames whose window holds a switch (half a window each side),
    each burst's rows less their own straight-line trend (the bursts' on and off, and their ramps, are no
    pattern); each lag's products are averaged over the pairs of frames that lag apart within one burst
    (the wingbeat's phase does not carry from one burst to the next). Returns ``(r, pairs)``: ``r``
    normalised to 1 at lag 0 (0 where the bursts hold no variation), over the lags resting on
    ``FLAP_SMOOTH_S`` of pairs at least, and ``pairs`` their number. A period is searched up to half those
    lags (for one burst: two periods and a quarter second must fit in it). None where the rows show no
    glide (frames not flapping in under ``MIN_GLIDE_SHARE`` of the dwell), flap for under ``FLAP_SMOOTH_S``,
    or fewer than ``MIN_WING_ROWS`` rows are lit.
    """
    gliding = _gliding(spec, noise_level=noise_level, frame_rate=frame_rate, lit_db=lit_db)
    return None if gliding is None else _bursts_autocorrelation(spec, gliding, frame_rate=frame_rate)


def _bursts_autocorrelation(spec, gliding, *, frame_rate):
    """:func:`gated_pattern_autocorrelation` of ``spec`` from its :func:`_gliding` rows and flapping frames
    (``gliding``, not None)."""
    rows, flapping = gliding
    rows = np.log(rows + np.finfo(float).tiny)
    n = rows.shape[1]
    straddling = _frames_per_window(spec) // 2  # frames a switch falls in, each side of it
    products, pairs = np.zeros(n), np.zeros(n)
    for start, stop in bursts(flapping):
        start, stop = start + straddling, stop - straddling
        length = stop - start
        if length < 2:  # no pair a lag apart, and no trend
            continue
        frames = np.arange(length)
        trend = np.polynomial.polynomial.polyfit(frames, rows[:, start:stop].T, 1)  # (2, rows)
        burst = rows[:, start:stop] - (trend[0][:, None] + trend[1][:, None] * frames[None, :])
        products[:length] += _lag_products(burst).sum(axis=0)
        pairs[:length] += np.arange(length, 0, -1)
    usable = int(np.argmax(pairs < max(1.0, FLAP_SMOOTH_S * frame_rate)))
    if usable == 0:
        return None
    r = products[:usable] / pairs[:usable]
    return (r / r[0] if r[0] > 0 else np.zeros(usable)), pairs[:usable]


def _period(r, *, frame_rate, frames_per_window):
    """The wingbeat period in a pattern autocorrelation ``r`` (a Period or None) of frames ``frames_per_window``
    hops long: a single-repeat period gives way to a shorter one, up to ``SHORTER_SHARE`` of it, seen to repeat
    with ``MIN_PERIODICITY``.

    Periods up to half the record are searched (two wingbeats in it). Where none is found there, or none as strong
    as ``MIN_PERIODICITY``, the lags run on to half the dwell and a lag past it: the frames' centres span a frame
    less than the dwell, and a peak shows only with a lag beyond it (a gull beating 3.01 Hz for 0.706 s at K band,
    in 35 ms frames, peaked at the record's half, a lag past the last lag searched, and read no wingbeat). Only
    there: the peaks of the lags added may outshine a shorter period's and change the look's choice (searched so
    wherever, a quadrotor seen face-on, its rows repeating at 13.1 Hz in the first look, read 13.0 Hz in the look
    that confirms so short a period, where it had read 16.2 Hz and none was taken: `bird` for `none`). A period
    found so whose parabola refines it past half the dwell is none: the dwell holds under two beats of it (a gull
    beating 3.22 Hz seen 0.616 s, 1.98 beats, was read at 3.24 Hz).
    """
    dwell_lags = len(r) - 1 + frames_per_window  # the record spans n - 1 hops and a window

    def up_to(max_period_s, max_lag=None):
        return period_from_autocorrelation(r, sample_rate_hz=frame_rate, min_period_s=1.0 / MAX_WINGBEAT_HZ,
                                           max_period_s=max_period_s, repeat_share=REPEAT_SHARE, max_lag=max_lag)

    found = up_to(1.0 / MIN_WINGBEAT_HZ)
    if found is None or found.strength < MIN_PERIODICITY:
        # the lags run to the dwell's half and one past: a peak at the half shows only against the lag past it
        wide = up_to(1.0 / MIN_WINGBEAT_HZ, max_lag=min(dwell_lags // 2 + 2, len(r)))
        if wide is not None and wide.period_s * frame_rate <= dwell_lags / 2:  # refined, it may pass the half
            found = wide
    if found is not None and found.repeats == 1:
        shorter = up_to(SHORTER_SHARE * found.period_s)
        if shorter is not None and shorter.repeats >= 2 and shorter.strength >= MIN_PERIODICITY:
            return shorter
    return found


def wingbeat(demodulated, *, prf_hz, noise_power, band_hz=None, still=False):
    """Wingbeat period of a body-demodulated echo (noise ``noise_power`` per chirp): a
    :class:`~mdpipe.process.periodicity.Period`, an :class:`Octave` (two looks an octave apart, or a stroke side's
    rows repeating at twice the period read: :func:`_signed_double`), a :class:`ShortBursts` (read over flapping
    bursts too short to hold its repeat: :func:`_short_bursts`), or None.

    The spectrogram frame is ``FRAME_S``, or shorter where the micro-Doppler band (``band_hz`` wide) still
    holds ``BAND_BINS`` Doppler bins at the shorter frame (down to ``MIN_FRAME_S``); see :func:`_looks`. A
    period T under ``BLURRED_FRAMES`` frames is read again with frames of T / ``BLURRED_FRAMES`` (not under
    ``MIN_FRAME_S``): a frame blurs the lags up to its length, and the peak of a wingbeat there can be
    missed for its double (a sparrow's 14 Hz read at 7 Hz in 64 ms frames). That look's period is taken
    where it is T / 2 within ``BLUR_AGREEMENT``, or T and T is under two frames (the first frames blurred
    it: a 14.6 Hz beat read 7.6 % off in 63 ms frames); T where it confirms T over two frames, finds none,
    or cannot be shorter; an :class:`Octave` where it finds 2 T (an X-band bird of the offmodel benchmark beating
    3.89 Hz read 7.78 Hz in 64 ms frames, 3.91 Hz in 32 ms ones); none where it finds another period. The second look
    reads its rows as the first did (each bin, or averaged for weak wings: :func:`wing_frames`). ``still``: the body
    neither flies nor travels; its wing rows stand over its line's leakage (:func:`wing_frames`).
    """
    frame_s = _dwell_frame_s(demodulated, prf_hz=prf_hz)
    if band_hz:
        frame_s = min(frame_s, max(MIN_FRAME_S, BAND_BINS / band_hz))
    frames = wing_frames(demodulated, prf_hz=prf_hz, noise_power=noise_power, frame_s=frame_s, still=still)
    if frames.wing_rows() < MIN_WING_ROWS:
        return None
    found = _two_looks(demodulated, frames, prf_hz=prf_hz, noise_power=noise_power, still=still)
    if isinstance(found, Period):
        found = _signed_double(found, frames)
    return _short_bursts(found, frames) if isinstance(found, Period) else found


def _short_bursts(found, frames):
    """``found``, or a :class:`ShortBursts` where it rests on two repeats or fewer (no scatter of its repeats to read:
    its standard error is unknown) and the bird glides between bursts (:attr:`WingFrames.flap_bursts`) the longest of
    which holds under ``SHORT_BURST_BEATS`` of it.

    The whole record's repeat at 2T then pairs under a beat of flapping frames within one burst, the rest of its pairs
    straddling a switch to gliding, which shifts the peaks by a few per cent (:func:`_within_bursts`), and the bursts
    are too short for the period to be measured again within them (a gull and a crow of the held-out bird sweep at seed
    999, one burst of 2.0-2.2 beats each, marked 2.5 and 2.6 periods long, read 5.2 and 6.3 % fast; the next longest
    burst read on two repeats or fewer on the evaluation's sweeps held 5.6 beats). A period read within the bursts
    (:func:`_gated_period`) on two repeats or fewer is held so too. Limit: the marks run over a burst's ends by up to
    half the lit share's smoothing (``FLAP_SMOOTH_S``) each, where the stroke ramps up and down: a burst of 2 beats
    within the record was marked 3.1-3.4 periods long in synthetic crows (read 4.6-6.3 % fast, within its bursts) and
    stays `ok`."""
    if np.isfinite(found.error_s):
        return found
    if frames.flap_bursts is None:
        return found
    runs = frames.flap_bursts[1]
    longest_s = float((runs[:, 1] - runs[:, 0]).max()) / frames.frame_rate
    return ShortBursts(found.period_s, longest_s) if longest_s < SHORT_BURST_BEATS * found.period_s else found


def _two_looks(demodulated, frames, *, prf_hz, noise_power, still):
    """The period :func:`_looks` reads in ``frames``, read again in shorter frames where it spans under
    ``BLURRED_FRAMES`` of them (see :func:`wingbeat`): a Period, an :class:`Octave`, or None."""
    found = _looks(frames)
    window_s = frames.spec.window_s
    if found is None or found.period_s >= BLURRED_FRAMES * window_s:
        return found
    shorter = wing_frames(demodulated, prf_hz=prf_hz, noise_power=noise_power,
                          frame_s=max(MIN_FRAME_S, found.period_s / BLURRED_FRAMES), weak=frames.weak, still=still)
    if shorter.spec.window_s >= window_s:  # no shorter frame (8 chirps at least)
        return found
    again = _looks(shorter)
    if again is None:  # nothing more seen
        return found
    ratio = again.period_s / found.period_s
    if abs(2 * ratio - 1) <= BLUR_AGREEMENT:  # the first look took the wingbeat's double
        return again
    if abs(ratio - 1) <= BLUR_AGREEMENT:  # confirmed: under two frames the shorter frames read it sharper
        return again if found.period_s < 2 * window_s else found
    if abs(ratio / 2 - 1) <= BLUR_AGREEMENT:  # the shorter frames read twice the period: one of the two
        return Octave(period_s=again.period_s, short_s=found.period_s)
    return None


@dataclass(frozen=True)
class ShortBursts:
    """A wingbeat read at ``period_s`` (over the whole record or within the bursts) of a bird that glides between
    flapping bursts, the longest ``burst_s`` long (under ``SHORT_BURST_BEATS`` periods), on two repeats or fewer
    (:func:`_short_bursts`): a wing pattern, but its period is not sharp."""

    period_s: float
    burst_s: float


@dataclass(frozen=True)
class Octave:
    """A wingbeat read at ``short_s`` whose double, ``period_s``, the echo also supports: a wing-like pattern either
    way, so a wingbeat is there, but which of the two is its period is not told. Either the two looks
    (:func:`wingbeat`) disagree by an octave (the longer look's frames read ``short_s``, the shorter frames twice it:
    the first may read the sign-blind T / 2 of wings crossing the body's Doppler at both turns of their stroke, or the
    second may miss T for its double), or ``by_sides``: the wing rows of one stroke side repeat at twice the period the
    rows together repeat at (:func:`_signed_double`)."""

    period_s: float
    short_s: float
    by_sides: bool = False


def _side_autocorrelations(frames, row_percentile=SIGNAL_ROW_PERCENTILES[0]):
    """The pattern autocorrelations (:func:`pattern_autocorrelation`, detrended over the slowest wingbeat's two periods
    as :func:`_row_set_period` reads it) of the wing rows of ``frames`` lit in ``100 - row_percentile`` % of the
    frames, one for each side of the body line (above it, then below); None for a side where fewer than
    ``MIN_WING_ROWS`` are."""
    spec = frames.spec
    lit = _lit_mask(spec, frames.noise_level, row_percentile, off_hz=frames.off_hz, lit_db=frames.lit_db)
    sides = []
    for sign in (1, -1):
        mask = lit & (np.sign(spec.f_hz) == sign)
        if np.count_nonzero(mask) < MIN_WING_ROWS:
            sides.append(None)
            continue
        r = _rows_autocorrelation(spec.power[mask], detrend_frames=int(2 * frames.frame_rate / MIN_WINGBEAT_HZ))
        sides.append(r if r[0] > 0 else None)
    return sides


def _signed_double(found, frames):
    """``found`` (a Period), or an :class:`Octave` at twice its period where a stroke side's wing rows (lit in
    half the frames, or in a quarter: ``SIGNAL_ROW_PERCENTILES``) repeat at T under ``SIDE_REPEAT`` and at 2T by
    ``SIDE_DOUBLE_SHARE`` more (the lag 2T within the record's ``REPEAT_SHARE``).

    Rows off the body line keep the stroke's sign: those at +v light as the wing advances, once a beat. All rows
    together repeat at half the beat where its two strokes look alike (and near the body line, sign-blind, they do);
    a side's rows then repeat at 2T and hardly at T. Five geese and gulls seen over 1.5-2.3 beats read 1.9-2.1 times
    their wingbeat so (`make evaluate-heldout-birds`): a side of theirs at T -0.15-0.46, at 2T 0.16-0.87 more. Of the
    right readings of three benchmarks whose sides were read (206 on the rows lit in half the frames, 256 in a
    quarter), a side repeats at 2T up to 0.25 more than at T, but then at T with 0.5 or more; the 25 sides under 0.5
    at T repeat less at 2T.
    """
    lag = found.period_s * frames.frame_rate
    for row_percentile in SIGNAL_ROW_PERCENTILES:
        for r in _side_autocorrelations(frames, row_percentile):
            if r is None or 2 * lag + 2 >= REPEAT_SHARE * len(r):
                continue
            once, twice = best_near(r, lag, half_width=1, lowest=1), best_near(r, 2 * lag, half_width=1, lowest=1)
            if once < SIDE_REPEAT and twice - once >= SIDE_DOUBLE_SHARE:
                return Octave(period_s=2 * found.period_s, short_s=found.period_s, by_sides=True)
    return found


@dataclass(frozen=True)
class WingFrames:
    """A spectrogram read for wings: ``spec`` (its rows each a Doppler bin, or bins averaged), the noise level per bin
    ``noise_level``, ``lit_db`` how far above it a cell is lit, ``off_hz`` how far from 0 Hz the wing rows lie
    (beyond the body line), whether the rows are the weak look's (:func:`weak_rows`), and ``floor``, a power per row
    that a wing row stands over besides (:func:`leakage_floor`), or None."""

    spec: object
    noise_level: float
    lit_db: float
    off_hz: float
    weak: bool
    floor: object = None

    @property
    def frame_rate(self):
        return 1.0 / self.spec.hop_s

    def lit_rows(self, row_percentile, *, wings_only=False):
        """The rows lit in ``100 - row_percentile`` % of the frames (off the body line and over ``floor`` only,
        ``wings_only``)."""
        return _lit_rows(self.spec, self.noise_level, row_percentile, off_hz=self.off_hz if wings_only else -1.0,
                         lit_db=self.lit_db, floor=self.floor if wings_only else None)

    def wing_rows(self):
        """How many rows off the body line are lit in a quarter of the frames."""
        return len(self.lit_rows(SIGNAL_ROW_PERCENTILES[-1], wings_only=True))

    @functools.cached_property
    def gliding(self):
        """The rows lit in a quarter of the frames and the frames in which they flap, where the bird glides between
        bursts (:func:`_gliding`), else None; read once, for the bursts' pattern, cycle and length."""
        return _gliding(self.spec, noise_level=self.noise_level, frame_rate=self.frame_rate, lit_db=self.lit_db)

    @functools.cached_property
    def flap_bursts(self):
        """The flapping frames of a bird that glides between bursts and their :func:`bursts`, or None where it does
        not glide (:func:`flapping_frames` on the rows :func:`gated_pattern_autocorrelation` reads, not flapping in
        ``MIN_GLIDE_SHARE`` of the dwell at least: :attr:`gliding`)."""
        return None if self.gliding is None else (self.gliding[1], bursts(self.gliding[1]))

    @functools.cached_property
    def gated(self):
        """The pattern autocorrelation within the flapping bursts (:func:`gated_pattern_autocorrelation`) and its
        pairs, or None; read once, for the period within the bursts and for a whole-record period measured again."""
        return None if self.gliding is None else _bursts_autocorrelation(self.spec, self.gliding,
                                                                          frame_rate=self.frame_rate)


def wing_frames(demodulated, *, prf_hz, noise_power, frame_s, weak=None, body_bins=BODY_LOBE_BINS, still=False):
    """The spectrogram of ``frame_s`` frames (hop a quarter of it) read for wings (:class:`WingFrames`), the wing
    rows lying ``body_bins`` Doppler bins off 0 Hz or more.

    Its rows as they are, a cell lit ``SIGNAL_ROW_DB`` over the noise; or, ``weak`` (by default: where fewer than
    ``MIN_WING_ROWS`` wing rows are lit so), :func:`weak_rows`, a cell lit ``WEAK_ROW_DB`` over the noise (those start
    beyond the body line's leakage).

    ``still``: a body that neither flies nor travels in the dwell (a bird hovering or crossing the beam, a point
    crossing it, a swaying branch; or one whose velocity is not read). Its wing rows (each bin) stand, besides, over
    what its own line's window leakage can light there (:func:`leakage_floor`). A strong line's Hann sidelobes light
    rows a few bins off it, and their level swings as the body track's residual moves the line within its bin: an
    X-band point crossing the beam at 55-65 dB per frame lit six rows 2-4 bins off it so, 12-26 dB under that floor,
    which beat like wings at 11.6 Hz. A flying body's wing rows are read as they are (a body that flies is no branch
    and no crossing point). Limits: the floor is a steady tone's; a line sweeping 2.5 bins or more within one frame
    lights rows past it (a line wobbling +-1 bin at 11 Hz read so as wings); and only the rows counted as wings stand
    over it: once three do, the pattern read is that of every lit row, leakage rows with them (a still target with a
    band of its own beside a strong wobbling line could read the wobble).
    """
    spec, noise_level = _frames(demodulated, prf_hz=prf_hz, noise_power=noise_power, frame_s=frame_s)
    return _read_for_wings(spec, noise_level, weak=weak, body_bins=body_bins, still=still)


def _read_for_wings(spec, noise_level, *, weak, body_bins, still=False):
    """:func:`wing_frames` of a spectrogram ``spec`` (noise ``noise_level`` per bin)."""
    fine = WingFrames(spec, noise_level, SIGNAL_ROW_DB, _body_hz(spec, body_bins), weak=False,
                      floor=leakage_floor(spec) if still else None)
    if weak is None:
        weak = fine.wing_rows() < MIN_WING_ROWS
    if not weak:
        return fine
    return WingFrames(weak_rows(spec, noise_level), noise_level, WEAK_ROW_DB, fine.off_hz, weak=True)


def hann_leakage(bins):
    """The envelope of a Hann window's response ``bins`` (1.5 or more) bins from a tone, in power against its peak:
    ``(pi k (k^2 - 1))^-2`` (its transform is ``sin(pi k) / (pi k (1 - k^2))``; reached at half-bin offsets: -15.4 dB
    at 1.5 bins, -32.3 dB at 2.5)."""
    k = np.asarray(bins, dtype=np.float64)
    return 1.0 / (np.pi * k * (k ** 2 - 1)) ** 2


def _body_peak_power(spec):
    """The body line's power at 0 Hz: its bins there (the centre one and its neighbours) at their highest in each
    frame, at the 95th percentile over the frames."""
    centre = int(np.argmin(np.abs(spec.f_hz)))
    return float(np.percentile(spec.power[max(centre - 1, 0):centre + 2].max(axis=0), 95))


def leakage_floor(spec):
    """The power the body line's window leakage can put in each Doppler row of ``spec``, 2 bins or more off 0 Hz (0
    nearer: the line's own main lobe): Hann's sidelobe envelope (:func:`hann_leakage`) half a bin nearer than the
    row (the line anywhere within its bin) under the line's peak, its power (:func:`_body_peak_power`) read up by
    ``SCALLOP_LOSS_DB`` (the bins' highest lies that much under the line's peak where the line falls between two)."""
    bins = np.abs(spec.f_hz) / (spec.f_hz[1] - spec.f_hz[0])
    envelope = hann_leakage(np.maximum(bins - 0.5, 1.5))
    peak = _body_peak_power(spec) * 10 ** (SCALLOP_LOSS_DB / 10)
    return np.where(bins >= 2 - 1e-9, peak * envelope, 0.0)


def weak_rows(spec, noise_level, *, max_hz=MAX_MICRO_DOPPLER_HZ):
    """``spec`` with the rows of weak wings averaged ``WEAK_MERGE_BINS`` bins at a time: a wing lit a few dB over the
    noise in each bin (a crow at -7.8 dB per IF sample, K band: its wing rows 2-6 dB up in a quarter of the 64 ms
    frames) stands out of the average's smaller scatter.

    The body line's three bins at 0 Hz make one row; the averaged rows start, each side, where the body's window
    leakage (:func:`hann_leakage`, at the 95th percentile of its power over the frames) falls ``LEAKAGE_DB`` under
    the noise, so that the body's own sidelobes do not pass for wings. Each row's power is its bins' mean (the noise
    level per bin stays that of ``spec``) and its Doppler their mean.
    """
    f_hz = spec.f_hz
    centre = int(np.argmin(np.abs(f_hz)))
    body_db = 10 * np.log10(_body_peak_power(spec) / noise_level + np.finfo(float).tiny)
    first = 2
    while first < len(f_hz) and body_db + 10 * np.log10(hann_leakage(first - 0.5)) > LEAKAGE_DB:  # body half a bin off
        first += 1
    groups = [np.arange(max(centre - 1, 0), min(centre + 2, len(f_hz)))]
    for side in (1, -1):
        start = first
        while True:
            group = centre + side * np.arange(start, start + WEAK_MERGE_BINS)
            if group.min() < 0 or group.max() >= len(f_hz) or np.abs(f_hz[group]).max() > max_hz:
                break
            groups.append(group)
            start += WEAK_MERGE_BINS
    groups.sort(key=lambda g: f_hz[g].mean())
    return Spectrogram(power=np.array([spec.power[g].mean(axis=0) for g in groups]), t_s=spec.t_s,
                       f_hz=np.array([f_hz[g].mean() for g in groups]), window_s=spec.window_s, hop_s=spec.hop_s)


def weak_reach_hz(spec, noise_level):
    """How far from the body line (Hz) the rows of :func:`weak_rows`, over the whole span, reach, lit ``WEAK_ROW_DB``
    over the noise in a quarter of the frames of the dwell's spectrogram ``spec`` (:func:`dwell_frames`): the
    outer edge of the outermost such row. None where fewer than ``MIN_WING_ROWS`` are. Read once, it gives the wings'
    reach (:func:`wing_reach_hz`) and whether they overrun the span (:func:`overruns_span`).

    The dwell's band (:func:`mdpipe.process.spectral.occupied_band`, 10 dB over the smoothed dwell spectrum) misses
    wings that stand a few dB over the noise in each frame, or beat only in bursts (a crow of the evaluation sweep,
    K band: a band of +-31 Hz, its body line's, where its wing rows reach +-250 Hz). Read over the whole span, weak
    blades reach on past wings (a quadrotor at K band, its lines 12 dB over the noise, its rows beat at 11.7 Hz
    and, read to 2 kHz only, passed for wings).
    """
    rows = weak_rows(spec, noise_level, max_hz=np.inf)
    lit = _lit_mask(rows, noise_level, SIGNAL_ROW_PERCENTILES[-1], off_hz=_body_hz(spec, BODY_LOBE_BINS),
                    lit_db=WEAK_ROW_DB, max_hz=np.inf)
    if lit.sum() < MIN_WING_ROWS:
        return None
    return float(np.abs(rows.f_hz[lit]).max() + WEAK_MERGE_BINS * (spec.f_hz[1] - spec.f_hz[0]) / 2)


def wing_reach_hz(weak_hz, *, prf_hz):
    """The wings' reach (Hz from the body line) of the weak rows' reach ``weak_hz`` (:func:`weak_reach_hz`): itself,
    or None where there is none or it passes ``REACH_SPAN_SHARE`` of the span's half (the reach is then unknown,
    :func:`overruns_span`: faint blade flashes that fill the span light it so, a quadrotor at 77 GHz to 97 % of it,
    and so do a gull's wings at 94 GHz)."""
    return weak_hz if weak_hz is not None and weak_hz <= readable_reach_hz(prf_hz) else None


def overruns_span(weak_hz, *, prf_hz):
    """Whether the weak rows' reach ``weak_hz`` (:func:`weak_reach_hz`) passes ``REACH_SPAN_SHARE`` of the span's
    half: what lights them moves faster than the span holds, or as fast, and they tell only that."""
    return weak_hz is not None and weak_hz > readable_reach_hz(prf_hz)


def readable_reach_hz(prf_hz):
    """The farthest reach (Hz from the body line) read as one: ``REACH_SPAN_SHARE`` of the span's half."""
    return REACH_SPAN_SHARE * prf_hz / 2


def _looks(frames):
    """The wingbeat period in ``frames`` (:class:`WingFrames`).

    Each row set of ``SIGNAL_ROW_PERCENTILES`` gives a period; the first seen to repeat with
    ``MIN_PERIODICITY`` is taken, else the first whose repeat the record cannot hold (two wingbeats in the
    dwell) with ``MIN_SINGLE_PERIODICITY``, else the period within flapping bursts (:func:`_gated_period`).
    In the weak look a row set is read only with ``MIN_WING_ROWS`` wing rows in it: the body's row alone, a
    line 0.4 bin off 0 Hz with weak wings 3 Hz in it, repeated at 1.23 Hz (its beat with the wings' lines);
    rows of single bins keep theirs (a goose of the evaluation sweep reads its wingbeat in the rows lit in half
    its frames, which hold under three wing rows). (:func:`wingbeat` reads none unless ``MIN_WING_ROWS`` rows off the body line are lit in a quarter of the
    frames: a modulation of the body line alone (its main lobe's three rows) is no wing, and the line's beat with
    another (a residual line at 0 Hz, a second body) repeats it as evenly.)
    """
    single = None
    for index, row_percentile in enumerate(SIGNAL_ROW_PERCENTILES):
        if frames.weak and len(frames.lit_rows(row_percentile, wings_only=True)) < MIN_WING_ROWS:
            continue  # the body's row with weak wings' beat in it (see above)
        found = _row_set_period(frames, row_percentile)
        if found is None:
            continue
        if found.repeats >= 2 and found.strength >= MIN_PERIODICITY:
            if len(frames.lit_rows(row_percentile, wings_only=True)) < MIN_WING_ROWS:
                found = _stroke_signed(found, frames, SIGNAL_ROW_PERCENTILES[index + 1:])
            return _within_cycle(found, frames)
        if found.repeats == 1 and found.strength >= MIN_SINGLE_PERIODICITY and single is None:
            single = found
    if single is not None:
        return _within_cycle(single, frames)
    return _gated_period(frames)


def _row_set_period(frames, row_percentile):
    """The wingbeat period (:func:`_period`) in the rows of ``frames`` lit in ``100 - row_percentile`` % of them."""
    r = pattern_autocorrelation(frames.spec, detrend_frames=int(2 * frames.frame_rate / MIN_WINGBEAT_HZ),
                                noise_level=frames.noise_level, row_percentile=row_percentile, lit_db=frames.lit_db)
    return _period(r, frame_rate=frames.frame_rate, frames_per_window=_frames_per_window(frames.spec))


def _stroke_signed(found, frames, wider_percentiles):
    """``found``, a period read on rows that hold fewer than ``MIN_WING_ROWS`` wing rows (the body line's main lobe,
    and a row or two of its skirt), or the wider row set's period where that is its double or half.

    The body line's rows are sign-blind: the wings cross the body's Doppler at both turns of their stroke, and
    the body line's modulation repeats at T / 2 whether or not the strokes differ (a bird beating 4.22 Hz read on
    the body line's three rows at 8.64 Hz, its wing rows, 26 of them, repeating at 4.22 Hz), or at 2 T where a beat
    of two lines in it is slow. Rows off the body line keep the stroke's sign (a row at +v lights on one stroke
    only), so a wider row set (``wider_percentiles``) holding ``MIN_WING_ROWS`` wing rows, and seeing its period
    repeat with ``MIN_PERIODICITY``, decides between T and its octave (within ``BLUR_AGREEMENT``); any other
    disagreement keeps ``found`` (the wider rows hold the on and off of flapping bursts: a goose of the evaluation
    sweep reads its wingbeat only on the rows lit in half its frames).
    """
    for row_percentile in wider_percentiles:
        if len(frames.lit_rows(row_percentile, wings_only=True)) < MIN_WING_ROWS:
            continue
        wide = _row_set_period(frames, row_percentile)
        if wide is None or wide.repeats < 2 or wide.strength < MIN_PERIODICITY:
            continue
        ratio = wide.period_s / found.period_s
        if abs(ratio / 2 - 1) <= BLUR_AGREEMENT or abs(2 * ratio - 1) <= BLUR_AGREEMENT:
            return wide
    return found


def burst_cycle_s(frames):
    """The cycle (s) of a bird's flap-glide bursts in ``frames``: the median time between its switches from gliding
    to flapping, and between those from flapping to gliding (the record's own start and end are none); None where it
    does not glide (:attr:`WingFrames.flap_bursts`) or shows no two switches of one kind."""
    found = frames.flap_bursts
    if found is None:
        return None
    flapping, runs = found
    starts, stops = runs[:, 0][runs[:, 0] > 0], runs[:, 1][runs[:, 1] < len(flapping)]
    gaps = np.concatenate([np.diff(starts), np.diff(stops)])
    return float(np.median(gaps)) / frames.frame_rate if len(gaps) else None


def _within_cycle(found, frames):
    """``found``, a period seen in the whole record (measured again within the bursts: :func:`_within_bursts`), or,
    where it spans ``CYCLE_SHARE`` of the cycle of a bird's flap-glide bursts or more (:func:`burst_cycle_s`), the
    period read within the bursts (:func:`_gated_period`), or None.

    A burst shorter than the period holds less than one beat: such a period is the cycle of flapping and gliding,
    which repeats whole, not the wingbeat (a crow flapping 1.04 s and gliding 0.89 s read 0.522 Hz for 4.19 Hz; a
    goose flapping 0.77 s and gliding 0.36 s, 0.885 Hz for 2.66 Hz: the default sweep at seed 4321).
    """
    cycle_s = burst_cycle_s(frames)
    if cycle_s is not None and found.period_s >= CYCLE_SHARE * cycle_s:
        return _gated_period(frames)
    return _within_bursts(found, frames)


def _within_bursts(found, frames):
    """``found``, a period seen in the whole record, measured again within the flapping bursts where the bird
    glides between them (:func:`gated_pattern_autocorrelation`): its peaks near k T refined there. That period
    is taken where it is within ``BURST_AGREEMENT`` of ``found`` and its peaks line up on k T more closely
    (a smaller standard error, three peaks at least); else ``found``.

    A burst's switch to gliding cuts the wing pattern at some phase of its beat, and the pairs of frames across
    it add a term of the wingbeat's own period to the whole record's autocorrelation, shifted by that phase:
    its peaks move by a few per cent, each by its own amount (a goose flapping 2.0 s of a 2.8 s dwell read
    3.1 % fast, its peaks off k T by up to 2.5 frames; within its burst, 0.5 % and 0.05 frames). The gated
    autocorrelation pairs only frames of one burst, but rests on fewer pairs and peaks: where the bursts are
    short and many, the whole record reads closer (a crow flapping 1.0 s at a time: 0.1 % against 1.2 %).
    """
    gated = frames.gated
    if gated is None:
        return found
    r, _ = gated
    frame_rate = frames.frame_rate
    coarse = found.period_s * frame_rate
    if (1 + BURST_AGREEMENT) * coarse >= REPEAT_SHARE * len(r):
        return found
    period, _, error = refine_period(r, coarse, limit=REPEAT_SHARE * len(r))
    if abs(period / coarse - 1) > BURST_AGREEMENT or error >= found.error_s * frame_rate:
        return found
    return replace(found, period_s=period / frame_rate, error_s=error / frame_rate)


def _gated_period(frames):
    """The wingbeat within the flapping bursts of a bird that glides between them (a Period or None).

    Read on :func:`gated_pattern_autocorrelation` (two beats in a row in a burst at least) with the strengths
    the other looks need (``MIN_PERIODICITY`` seen to repeat at 2T, where the bursts hold 2T; else
    ``MIN_SINGLE_PERIODICITY``), and ``PAIR_SIGMAS`` standard errors of the lag's mean at least (Bartlett's,
    ``sqrt((1 + 2 sum r(k)^2) / pairs)`` over the lags k of frames that share chirps: a few dozen pairs of
    overlapping frames of speckle correlate by chance); repeats at 3T are not asked for (a burst holds few
    beats, and a drifting wingbeat falls short there).
    """
    gated = frames.gated
    if gated is None:
        return None
    r, pairs = gated
    found = period_from_autocorrelation(r, sample_rate_hz=frames.frame_rate, min_period_s=1.0 / MAX_WINGBEAT_HZ,
                                        max_period_s=1.0 / MIN_WINGBEAT_HZ, repeat_share=REPEAT_SHARE, max_order=2)
    if found is None:
        return None
    repeat_seen = 2 * found.peak_lag < int(REPEAT_SHARE * len(r))  # the 2T test was made (and passed)
    overlap = r[1:min(len(r), _frames_per_window(frames.spec))]  # frames sharing chirps correlate
    error = bartlett_error(overlap, pairs[found.peak_lag])
    needed = max(MIN_PERIODICITY if repeat_seen else MIN_SINGLE_PERIODICITY, PAIR_SIGMAS * error)
    return found if found.strength >= needed else None


def flap_glide_share(spec, noise_level, *, still=False):
    """The share of the dwell a bird flaps, where it glides between flapping bursts; None where it does not.

    On the dwell's spectrogram ``spec`` (:func:`dwell_frames`; ``noise_level`` per bin), the wing rows are those within
    ``MAX_MICRO_DOPPLER_HZ`` lit in a quarter of the frames and off the body line (``BODY_BINS`` of 0 Hz; for a
    ``still`` body, over its line's leakage too: :func:`wing_frames`), ``MIN_WING_ROWS`` of them at least;
    :func:`flapping_frames` marks where they flap. A glide is frames not
    flapping in ``MIN_GLIDE_SHARE`` of the dwell at least (and flapping in as much), in which the wing rows' median
    power falls ``GLIDE_DROP_DB`` under its median while flapping and the body line's holds within
    ``BODY_STEADY_DB`` of its own: a bird stops beating and glides on. Rotors never stop; a target fading as a whole
    (a point crossing range bins) takes its body line down with it. This tells a bird whose bursts hold too few beats
    for a wingbeat (geese of the evaluation sweep flapping 1.6-2.3 beats at a time: 8-21 wing rows falling 26-34 dB,
    the body within 1.5 dB). The wings of a slow stroke also go dark at its turns, where they move no faster than
    the body (the paper's Table II birds beating 0.5 Hz: lit 83 % of the dwell): a bird too.
    """
    frames = _read_for_wings(spec, noise_level, weak=None, body_bins=BODY_BINS, still=still)
    wings = frames.lit_rows(SIGNAL_ROW_PERCENTILES[-1], wings_only=True)
    body = spec.power[np.abs(spec.f_hz) <= frames.off_hz]
    if len(wings) < MIN_WING_ROWS or len(body) == 0:
        return None
    flapping = flapping_frames(wings, noise_level=noise_level, frame_rate=frames.frame_rate, lit_db=frames.lit_db)
    share = float(flapping.mean())
    if not MIN_GLIDE_SHARE <= share <= 1 - MIN_GLIDE_SHARE:
        return None
    # weak wings' rows are mostly noise while flapping: their drop is that of their power over it
    wing_power = wings.sum(axis=0) - (len(wings) * noise_level if frames.weak else 0.0)
    body_power = body.sum(axis=0)
    tiny = np.finfo(float).tiny

    def change_db(p):
        return 10 * np.log10(max(np.median(p[flapping]), tiny) / max(np.median(p[~flapping]), tiny))

    if change_db(wing_power) < GLIDE_DROP_DB or abs(change_db(body_power)) > BODY_STEADY_DB:
        return None
    return share


def stroke_swing(spec, noise_level):
    """How far the wings' reach moves over the dwell: the spread (95th less 5th percentile) of each frame's outermost
    lit wing row's distance from the body line, over the frames with a wing row lit, as a share of the greatest; None
    where fewer than ``MIN_WING_ROWS`` rows off the body line are lit in a quarter of the frames of the dwell's
    spectrogram ``spec`` (:func:`dwell_frames`, weak wings' rows averaged) or fewer than ``MIN_STROKE_FRAMES`` have a
    wing row lit. Frames shorter than ``STROKE_FRAME_S`` are the caller's to refuse.

    A wing's tip moves fastest mid-stroke and stops at the turns: its reach swings within one beat. A rotor's tips
    turn at one speed, and a frame that holds a turn or more shows the same reach from frame to frame. Seven birds of
    the held-out bird sweep seen over 1.1-1.8 beats swung 0.27-0.59 of their reach; two quadrotors whose blades stood a
    few dB over the noise (their combs not found), 0.03-0.06.
    """
    frames = _read_for_wings(spec, noise_level, weak=None, body_bins=BODY_BINS)
    spec = frames.spec
    rows = _lit_mask(spec, frames.noise_level, SIGNAL_ROW_PERCENTILES[-1], off_hz=frames.off_hz, lit_db=frames.lit_db)
    if np.count_nonzero(rows) < MIN_WING_ROWS:
        return None
    lit = spec.power[rows] > _lit_level(frames.noise_level, frames.lit_db)
    seen = lit.any(axis=0)
    if np.count_nonzero(seen) < MIN_STROKE_FRAMES:
        return None
    distance_hz = np.abs(spec.f_hz[rows])
    reach_hz = np.max(np.where(lit[:, seen], distance_hz[:, None], 0.0), axis=0)
    return float((np.percentile(reach_hz, 95) - np.percentile(reach_hz, 5)) / reach_hz.max())
