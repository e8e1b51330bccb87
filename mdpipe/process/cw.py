"""One I/Q (CW) recording from file to its feature row: noise, detection, the channels combined, analysis, class.

A continuous-wave radar's I/Q samples are the slow time an FMCW capture yields per range bin, over every range
at once: there is nothing to range-transform, follow or separate in range, so one row is written (everything
moving in the beam is one target). The analysis is the capture's (:func:`mdpipe.process.features.analyse_target`)
at the I/Q sample rate, without a range track (an aliased body Doppler is not unfolded) and without the views an
FMCW ramp adds (its parts and range sides).

The receiver noise is read from the recording itself, as a CW recording has no empty range bins, in two ways,
the lower kept (each reads the echo's own floor for noise where the echo leaves no cell to it, so each errs
high): the dwell's periodogram through a 4-term Blackman-Harris window (sidelobes 92 dB down: a line lights a few
cells only), the lower ``NOISE_QUANTILE`` of each of ``NOISE_BANDS`` parts of the span, the median over the parts;
and, over frames of about ``NOISE_FRAME_S``, each Doppler column's lower ``NOISE_QUANTILE`` over time (the frames
between blade flashes or wing strokes), the median over the columns. Either median leaves out the parts or columns
more than three robust standard deviations over it (a band of micro-Doppler lights them: 150 lines 17 dB up over
a fifth of the span biased it 8 %, now under 5 %). For white noise the cells are exponential, so a quantile q is
``-ln(1 - q)`` times their mean. Where the echo fills every cell (blade lines folded over the whole span by a low
sample rate) both read its floor: the noise is overestimated and the echo's SNR under-read. Noise coloured across the
span (a receiver filter narrower than the sampling, a 1/f rise, clutter spread about 0 m/s) is first made white:
each Doppler cell is scaled by the noise's level there, read from the bands that hold no lines
(:func:`noise_profile`, :func:`whitened`).
"""

import math
from dataclasses import dataclass

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.io.iq import read_iq
from mdpipe.params import GIB
from mdpipe.process import impulses, mains, memory, selection
from mdpipe.process.cfar import gamma_isf
from mdpipe.process.classify import classify
from mdpipe.process.doppler import periodic_hann
from mdpipe.process.filters import running_median
from mdpipe.process.features import analyse_target
from mdpipe.process.result import CaptureResult, base_row

MIN_SAMPLES = 64            # as a capture's chirps (pipeline.MIN_CHIRPS)
NOISE_FRAME_S = 1e-3        # frames short against a rotor's flash period, so that some hold no flash
NOISE_FRAME_SAMPLES = (16, 1024)
NOISE_QUANTILE = 0.1
NOISE_BANDS = 32
NOISE_OUTLIER_SIGMAS = 3.0
COLOUR_SIGMAS = 3.0         # how closely a band's statistics must be noise's (standard errors)
COLOUR_TOP_DB = 3.0         # a band this far under one beside it is an echo's skirt, not noise
PROFILE_CELLS = 512         # fine cells per band of the noise profile, at the least ...
PROFILE_BANDS = 128         # ... and bands at most
PROFILE_SMOOTH = 7          # bands over which the profile's median is taken
LOCAL_CELLS = 17            # detection cells about each whose median is its noise, the noise coloured
BLACKMAN_HARRIS = (0.35875, 0.48829, 0.14128, 0.01168)
DETECTION_BLOCK = 256       # samples per block of the detection test's averaged spectrum


def noise_frame(sample_rate_hz):
    """Samples per frame of the noise estimate: the power of two nearest ``NOISE_FRAME_S``, within bounds."""
    samples = 2 ** round(math.log2(max(sample_rate_hz * NOISE_FRAME_S, 1.0)))
    return int(np.clip(samples, *NOISE_FRAME_SAMPLES))


def blackman_harris(n):
    """The periodic 4-term Blackman-Harris window of ``n`` samples (sidelobes 92 dB down)."""
    phase = 2 * np.pi * np.arange(n) / n
    return sum((-1) ** k * a * np.cos(k * phase) for k, a in enumerate(BLACKMAN_HARRIS))


def blackman_harris_cells(signal):
    """The dwell's Blackman-Harris periodogram (FFT order, V^2 per sample: over the window's summed squares)."""
    window = blackman_harris(len(signal))
    return np.abs(np.fft.fft(signal * window)) ** 2 / np.sum(window ** 2)


def _exponential_mean(cells, axis):
    """The mean of exponential ``cells`` read from their lower ``NOISE_QUANTILE`` along ``axis``."""
    return np.quantile(cells, NOISE_QUANTILE, axis=axis) / -math.log1p(-NOISE_QUANTILE)


def _median_and_error(values):
    """The median of ``values`` less those over it by more than ``NOISE_OUTLIER_SIGMAS`` robust standard deviations
    (1.48 median absolute deviations: parts or columns that the echo lights), and its relative standard error
    (1.25 sigma / sqrt(n) of a normal sample)."""
    values = np.asarray(values, dtype=np.float64)
    median = float(np.median(values))
    spread = 1.4826 * float(np.median(np.abs(values - median)))
    kept = values[values <= median + NOISE_OUTLIER_SIGMAS * spread]
    median = float(np.median(kept))
    return median, 1.2533 * float(np.std(kept)) / math.sqrt(len(kept)) / max(median, np.finfo(float).tiny)


@dataclass(frozen=True)
class NoiseEstimate:
    """The receiver noise per sample (V^2) read from a recording (the lower of its two readings: module notes), the
    relative standard error of that reading, and both readings."""

    power: float
    relative_error: float
    dwell: float
    framed: float


def _line_free(cells):
    """Whether fine cells ``cells`` hold no lines: exponential, their mean ln 2 over their median to ``COLOUR_SIGMAS``
    of about 1.5 sqrt(2 / cells) (Blackman-Harris neighbours correlated; a rotor's or a wing's lines stand out there
    5 to 50 000 times)."""
    return np.mean(cells) / max(np.median(cells), np.finfo(float).tiny) * math.log(2.0) - 1.0 < \
        COLOUR_SIGMAS * 1.5 * math.sqrt(2.0 / len(cells))


def _steady(signal, n_bands):
    """Per band of ``n_bands`` over the span (FFT order), whether its power varies over frames of ``n_bands`` samples
    (one cell a band, periodic Hann) as noise's does: exponential, the variance the square of the mean to
    ``COLOUR_SIGMAS`` standard errors (sqrt(8 / frames)). Wings sweeping through a band light it by turns (a bird's
    skirt beside its body line is smooth, but not steady)."""
    frames = len(signal) // n_bands
    window = periodic_hann(n_bands)
    power = np.abs(np.fft.fft(np.asarray(signal[:frames * n_bands]).reshape(frames, n_bands) * window, axis=1)) ** 2
    mean = power.mean(axis=0)
    ratio = power.var(axis=0) / np.maximum(mean, np.finfo(float).tiny) ** 2
    return np.abs(ratio - 1.0) < COLOUR_SIGMAS * math.sqrt(8.0 / frames)


@dataclass(frozen=True)
class NoiseProfile:
    """The receiver noise's level across the span (:func:`noise_profile`): per FFT cell of the signal (FFT order,
    V^2 per sample), its spread (highest over lowest, on the bands that show it) and whether it is coloured."""

    per_cell: np.ndarray
    spread: float
    coloured: bool


def noise_profile(signal):
    """The receiver noise's level across the span, from the dwell's Blackman-Harris periodogram in bands of
    ``PROFILE_CELLS`` cells or more (``PROFILE_BANDS`` at most, a power of two): each band's lower ``NOISE_QUANTILE``,
    on the bands that hold no lines (:func:`_line_free`), whose power varies over time as noise's does
    (:func:`_steady`) and that lie no more than ``COLOUR_TOP_DB`` under a band beside them (a bird's smooth skirt
    beside its body line, whitened as noise without the last two: 13 of the 114 birds of ``make offmodel-cw`` lost, 2
    with them), interpolated (in dB) over the others and smoothed over ``PROFILE_SMOOTH`` bands, each band then the
    highest of itself and its two neighbours (a sharp filter's edge whitened as its passband, not under it).
    Coloured where its highest stands over its lowest by more than twice ``COLOUR_SIGMAS`` times the smoothed levels'
    spread for white noise (a receiver filter narrower than the sampling, a 1/f rise near 0 Hz, clutter spread about
    0 m/s)."""
    n = len(signal)
    cells = blackman_harris_cells(signal)
    n_bands = int(np.clip(n // PROFILE_CELLS, PROFILE_SMOOTH, PROFILE_BANDS))
    n_bands = 2 ** int(math.log2(n_bands))  # frames of n_bands samples: one cell a band, the bands' own
    bands = np.array_split(cells, n_bands)
    level = np.array([_exponential_mean(band, axis=0) for band in bands])
    free = np.array([_line_free(band) for band in bands])
    free &= _steady(signal, n_bands)
    free &= level * 10 ** (COLOUR_TOP_DB / 10) >= np.maximum(np.roll(level, 1), np.roll(level, -1))
    flat = np.full(n, float(np.median(level)))
    if np.count_nonzero(free) < PROFILE_SMOOTH:
        return NoiseProfile(flat, 1.0, False)
    shown = np.flatnonzero(free)
    log_level = np.interp(np.arange(n_bands), shown, np.log(level[shown]), period=n_bands)
    smoothed = running_median(log_level, PROFILE_SMOOTH, mode="wrap")
    spread = float(np.exp(smoothed[shown].max() - smoothed[shown].min()))
    # a band's level for white noise: the lower tenth of n exponential cells, 3 / sqrt(n) relative, Blackman-Harris
    # neighbours making it 1.5 times that; the median over PROFILE_SMOOTH bands, 1.25 / sqrt of them
    white_spread = 3.0 * 1.5 / math.sqrt(n / n_bands) * 1.25 / math.sqrt(PROFILE_SMOOTH)
    coloured = math.log(spread) > 2 * COLOUR_SIGMAS * white_spread
    if not coloured:
        return NoiseProfile(flat, spread, False)
    upper = np.maximum(smoothed, np.maximum(np.roll(smoothed, 1), np.roll(smoothed, -1)))  # a step's cells not under
    band_of_cell = np.repeat(np.arange(n_bands), [len(band) for band in bands])
    return NoiseProfile(np.exp(upper[band_of_cell]), spread, True)


def whitened(signal, profile):
    """``signal`` with its noise made white at the median level of ``profile`` (a :class:`NoiseProfile`): each
    Doppler cell scaled by the square root of that level over the profile's there."""
    reference = float(np.median(profile.per_cell))
    return np.fft.ifft(np.fft.fft(signal) * np.sqrt(reference / profile.per_cell))


def noise_power(signal, *, frame):
    """The receiver noise of complex ``signal`` (its mean removed, its noise white: :func:`whitened`), read from the
    signal: a :class:`NoiseEstimate`."""
    cells = blackman_harris_cells(signal)
    dwell, dwell_error = _median_and_error([_exponential_mean(part, axis=0)
                                            for part in np.array_split(cells, NOISE_BANDS)])
    n_frames = len(signal) // frame
    window = periodic_hann(frame)
    frames = np.asarray(signal[:n_frames * frame]).reshape(n_frames, frame)
    frame_cells = np.abs(np.fft.fft(frames * window, axis=1)) ** 2 / np.sum(window ** 2)
    framed, framed_error = _median_and_error(_exponential_mean(frame_cells, axis=0))
    if dwell <= framed:
        return NoiseEstimate(dwell, dwell_error, dwell, framed)
    return NoiseEstimate(framed, framed_error, dwell, framed)


def detection_spectrum(signal, *, block=DETECTION_BLOCK):
    """The mean over blocks of ``block`` samples (each less its mean, periodic Hann, over the window's sum squared)
    of their periodograms, shape (1, block), and the number of blocks: what :func:`selection.cell_test` reads."""
    n_blocks = len(signal) // block
    window = periodic_hann(block)
    blocks = np.asarray(signal[:n_blocks * block]).reshape(n_blocks, block)
    blocks = blocks - blocks.mean(axis=1, keepdims=True)
    power = np.mean(np.abs(np.fft.fft(blocks * window, axis=1)) ** 2, axis=0) / np.sum(window) ** 2
    return power[None, :], n_blocks


def combined(samples):
    """The channels (columns of ``samples``) added in phase toward what moves (the dominant eigenvector of the
    moving covariance, :func:`selection.channel_weights`): the signal (n,) complex128 and the gain in dB over one
    channel; one channel as it is (0 dB). No copy of all channels is made (the memory plan counts one signal)."""
    if samples.shape[1] == 1:
        return samples[:, 0].astype(np.complex128), 0.0
    mean = samples.mean(axis=0, dtype=np.complex128)
    covariance = (samples.T @ samples.conj()).astype(np.complex128) / len(samples) - np.outer(mean, mean.conj())
    weight, gain = selection.channel_weights(covariance[None])
    return (samples @ weight[0].astype(np.complex64)).astype(np.complex128), float(gain[0])


def detection(signal, *, sample_rate_hz, false_alarm_probability, coloured=False):
    """Whether anything moves in ``signal`` (its mean removed): the receiver noise read from it
    (:class:`NoiseEstimate`) and the :class:`~mdpipe.process.selection.DetectionTest` of its Doppler spectrum
    against that noise, the thresholds allowing for the reading's error (``noise_error``). Where the noise was
    ``coloured`` (whitened by a profile whose bands cannot follow a steep rise), each cell is held against the
    median of the ``LOCAL_CELLS`` about it instead, as a line stands over its neighbours (the band test then reads
    nothing: a whitened floor is level)."""
    estimate = noise_power(signal, frame=noise_frame(sample_rate_hz))
    power, blocks = detection_spectrum(signal)
    window = periodic_hann(DETECTION_BLOCK)
    if coloured:
        local = running_median(power[0], LOCAL_CELLS, mode="wrap")
        local_noise = local / (gamma_isf(blocks, 0.5) / blocks)  # a Gamma(looks) mean's median to its mean
        test = selection.cell_test(power / local_noise[None, :], looks=blocks, noise_cell=1.0,
                                   noise_error=1.2533 / math.sqrt(LOCAL_CELLS * blocks),
                                   false_alarm_probability=false_alarm_probability)
        return estimate, test
    test = selection.cell_test(power, looks=blocks, noise_cell=estimate.power * np.sum(window ** 2)
                               / np.sum(window) ** 2, noise_error=estimate.relative_error,
                               false_alarm_probability=false_alarm_probability)
    return estimate, test


def min_samples(sample_rate_hz):
    """The fewest I/Q samples analysed: a capture's fewest chirps, one detection block, and 16 noise frames."""
    return max(MIN_SAMPLES, DETECTION_BLOCK, 16 * noise_frame(sample_rate_hz))


def process_recording(path, process, *, overrides=None, allow_external=False):
    """Analyse one I/Q recording; returns a :class:`CaptureResult` of one row.

    ``--range-m`` and the range gate have no meaning here (a CW radar does not range); ``--range-m`` is refused.
    Raises :class:`mdpipe.errors.CaptureFormatError` for unreadable files and
    :class:`mdpipe.errors.ParameterError` for a recording too short, over the memory budget or without signal.
    """
    if process.range_m is not None:
        raise ParameterError(f"{path}: an I/Q (CW) recording has no range; --range-m applies to FMCW captures only")
    recording = read_iq(path, overrides=overrides, allow_external=allow_external,
                        check=lambda n, params, stored: memory.check_iq_memory(path, n, params, process,
                                                                               stored_bytes_per_sample=stored),
                        max_file_bytes=int(process.max_memory_gb * GIB / 4))
    params = recording.params
    if recording.n_samples < min_samples(params.sample_rate_hz):
        raise ParameterError(f"{path}: {recording.n_samples} I/Q sample(s); the analysis needs at least "
                             f"{min_samples(params.sample_rate_hz)} at {params.sample_rate_hz:g} Hz")
    signal, gain_db = combined(recording.samples)
    signal = signal - signal.mean()  # static clutter and the radar's own leakage
    if not np.any(np.abs(signal) > 0):
        raise ParameterError(f"{path}: every I/Q sample is the same; the recording holds no signal")
    # before the noise is read and anything detected: hum alone is no target
    signal, hum = mains.taken_out(signal, prf_hz=params.prf_hz, mains_hz=process.mains_frequencies_hz)
    profile = noise_profile(signal)
    if profile.coloured:
        signal = whitened(signal, profile)
    estimate, test = detection(signal, sample_rate_hz=params.sample_rate_hz,
                               false_alarm_probability=process.false_alarm_probability, coloured=profile.coloured)
    noise = estimate.power
    row = base_row(path, process, params, n_samples=recording.n_samples, clipped=recording.clipped_fraction,
                   interference=None)
    notes = list(recording.warnings)
    row["mains_hum_hz"] = None if hum is None else hum.f0_hz
    if profile.coloured:
        notes.append(f"the receiver noise is coloured, {10 * math.log10(profile.spread):.1f} dB from its lowest to its "
                     "highest level across the span (a filter narrower than the sampling, a rise near 0 Hz, or "
                     "clutter): the echo is read whitened by it")
    layout = recording.layout.describe()
    if test.score.max() < 1:
        row["notes"] = "; ".join([f"nothing moving above the noise at a false-alarm probability of "
                                  f"{test.false_alarm_probability:g} per recording ({test.shortfall()})"]
                                 + ([hum.note()] if hum is not None else []) + notes)
        return CaptureResult(str(path), params, layout, None, [], [], [row], noise_power=noise, process=process,
                             detection_test=test)
    analysis = analyse_target(signal, prf_hz=params.prf_hz, wavelength_m=params.wavelength_m, noise_power=noise,
                              params=process, ranged=False, hum=hum)
    row.update(target=0, rx_gain_db=gain_db)
    row.update(analysis.row)
    label, reason = classify(row, detected=True)
    row["class"] = label
    row["notes"] = "; ".join([f"class: {reason}"] + analysis.notes + notes)
    row = impulses.impulsive_rows([row], [signal], noise, notes)[0]
    return CaptureResult(str(path), params, layout, None, [], [analysis], [row], noise_power=noise, process=process,
                         detection_test=test)
