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
sample rate) both read its floor: the noise is overestimated and the echo's SNR under-read. Noise coloured by a
receiver filter narrower than the sampling is read at its highest level (:func:`noise_power`).
"""

import math
from dataclasses import dataclass

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.io.iq import read_iq
from mdpipe.process import memory, selection
from mdpipe.process.classify import classify
from mdpipe.process.doppler import periodic_hann
from mdpipe.process.features import analyse_target
from mdpipe.process.result import CaptureResult, base_row

MIN_SAMPLES = 64            # as a capture's chirps (pipeline.MIN_CHIRPS)
NOISE_FRAME_S = 1e-3        # frames short against a rotor's flash period, so that some hold no flash
NOISE_FRAME_SAMPLES = (16, 1024)
NOISE_QUANTILE = 0.1
NOISE_BANDS = 32
NOISE_OUTLIER_SIGMAS = 3.0
COLOUR_SIGMAS = 3.0         # how closely a column's statistics must be noise's (standard errors)
COLOUR_COLUMNS = 2          # noise-like columns within COLOUR_TOP_DB of the highest: a passband spans several
COLOUR_TOP_DB = 3.0
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
    """The receiver noise per sample (V^2) read from a recording (the lower of its two readings, or, the noise
    coloured, its highest level: module notes), the relative standard error of that reading, both readings, and the
    ratio of the coloured noise's highest level to the lower reading (1 where the noise is white)."""

    power: float
    relative_error: float
    dwell: float
    framed: float
    colour: float = 1.0


def _noise_like(frame_cells, dwell_cells):
    """Which Doppler columns of short frames' powers ``frame_cells`` (frames, columns) are receiver noise's: their
    powers vary over time as noise's do (exponential: variance the square of the mean, to ``COLOUR_SIGMAS`` standard
    errors, sqrt(8 / frames); a flash or a wing stroke passing makes it larger, a steady line smaller), and the fine
    cells of the dwell's periodogram ``dwell_cells`` (Blackman-Harris, FFT order) within each column are exponential
    too (mean over median ln 2 times, to ``COLOUR_SIGMAS`` of about 1.5 sqrt(2 / cells), neighbours correlated: a
    rotor's or a wing's lines stand out there, 5 to 50 000 times). Returns (mask, the mean of the fine cells per
    column: the frames' own level holds their short window's leakage from strong columns beside, 26 dB in a column
    two from a band 53 dB up)."""
    frames, n_columns = frame_cells.shape
    mean = frame_cells.mean(axis=0)
    in_time = np.abs(frame_cells.var(axis=0) / np.maximum(mean, np.finfo(float).tiny) ** 2 - 1.0)
    column = np.rint(np.arange(len(dwell_cells)) * n_columns / len(dwell_cells)).astype(np.int64) % n_columns
    sums = np.bincount(column, weights=dwell_cells, minlength=n_columns)
    counts = np.bincount(column, minlength=n_columns)
    medians = np.array([np.median(dwell_cells[column == c]) for c in range(n_columns)])
    in_frequency = sums / counts / np.maximum(medians, np.finfo(float).tiny) * math.log(2.0) - 1.0
    like = ((in_time < COLOUR_SIGMAS * math.sqrt(8.0 / frames))
            & (in_frequency < COLOUR_SIGMAS * 1.5 * np.sqrt(2.0 / counts)))
    return like, sums / counts


def noise_power(signal, *, frame):
    """The receiver noise of complex ``signal`` (its mean removed), read from the signal: a :class:`NoiseEstimate`.

    Coloured noise (a receiver's filter narrower than its sampling leaves noise over part of the span, much weaker
    beyond): the columns of short frames that are noise's (:func:`_noise_like`) stand at levels apart. Where
    the highest of them stands over the lower reading by more than twice ``COLOUR_SIGMAS`` of its standard errors,
    with ``COLOUR_COLUMNS`` or more of them within ``COLOUR_TOP_DB`` of it (a passband is flat over columns) and
    none of them ``COLOUR_TOP_DB`` under a column beside it (a bird's skirt beside its body line is smooth and
    steady too: two birds' read as the noise, 26 and 43 dB up), it is the noise (the noise of a receiver filtered
    to a third of the span read as a drone's band, before)."""
    window = blackman_harris(len(signal))
    cells = np.abs(np.fft.fft(signal * window)) ** 2 / np.sum(window ** 2)
    dwell, dwell_error = _median_and_error([_exponential_mean(part, axis=0)
                                            for part in np.array_split(cells, NOISE_BANDS)])
    n_frames = len(signal) // frame
    window = periodic_hann(frame)
    frames = np.asarray(signal[:n_frames * frame]).reshape(n_frames, frame)
    frame_cells = np.abs(np.fft.fft(frames * window, axis=1)) ** 2 / np.sum(window ** 2)
    framed, framed_error = _median_and_error(_exponential_mean(frame_cells, axis=0))
    power, error = (dwell, dwell_error) if dwell <= framed else (framed, framed_error)
    like, level = _noise_like(frame_cells, cells)
    near = 10 ** (COLOUR_TOP_DB / 10)
    like &= level * near >= np.maximum(np.roll(level, 1), np.roll(level, -1))  # no echo's skirt beside a stronger line
    highest = float(level[like].max()) if like.any() else 0.0
    top = np.count_nonzero(like & (level * near >= highest))
    if top >= COLOUR_COLUMNS and highest > power * (1.0 + 2 * COLOUR_SIGMAS / math.sqrt(n_frames)):
        return NoiseEstimate(highest, 1.0 / math.sqrt(n_frames), dwell, framed, highest / power)
    return NoiseEstimate(power, error, dwell, framed)


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


def detection(signal, *, sample_rate_hz, false_alarm_probability):
    """Whether anything moves in ``signal`` (its mean removed): the receiver noise read from it
    (:class:`NoiseEstimate`) and the :class:`~mdpipe.process.selection.DetectionTest` of its Doppler spectrum
    against that noise, the thresholds allowing for the reading's error (``noise_error``)."""
    estimate = noise_power(signal, frame=noise_frame(sample_rate_hz))
    power, blocks = detection_spectrum(signal)
    window = periodic_hann(DETECTION_BLOCK)
    test = selection.cell_test(power, looks=blocks, noise_cell=estimate.power * np.sum(window ** 2)
                               / np.sum(window) ** 2, noise_error=estimate.relative_error,
                               false_alarm_probability=false_alarm_probability)
    return estimate, test


def min_samples(sample_rate_hz):
    """The fewest I/Q samples analysed: a capture's fewest chirps, one detection block, and 16 noise frames."""
    return max(MIN_SAMPLES, DETECTION_BLOCK, 16 * noise_frame(sample_rate_hz))


def _no_detection_note(test):
    def db(x):
        return 10 * np.log10(max(x, np.finfo(float).tiny))
    return (f"nothing moving above the noise at a false-alarm probability of {test.false_alarm_probability:g} per "
            f"recording (strongest Doppler line {db(test.line.max()):.1f} dB < {db(test.line_threshold):.1f} dB, "
            f"band {db(test.band.max()):.1f} dB < {db(test.band_threshold):.1f} dB, over the noise per cell)")


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
                        max_file_bytes=int(process.max_memory_gb * memory.GIB / 4))
    params = recording.params
    if recording.n_samples < min_samples(params.sample_rate_hz):
        raise ParameterError(f"{path}: {recording.n_samples} I/Q sample(s); the analysis needs at least "
                             f"{min_samples(params.sample_rate_hz)} at {params.sample_rate_hz:g} Hz")
    signal, gain_db = combined(recording.samples)
    signal = signal - signal.mean()  # static clutter and the radar's own leakage
    if not np.any(np.abs(signal) > 0):
        raise ParameterError(f"{path}: every I/Q sample is the same; the recording holds no signal")
    estimate, test = detection(signal, sample_rate_hz=params.sample_rate_hz,
                               false_alarm_probability=process.false_alarm_probability)
    noise = estimate.power
    row = base_row(path, process, params, n_samples=recording.n_samples, clipped=recording.clipped_fraction,
                   interference=None)
    notes = list(recording.warnings)
    if estimate.colour > 1.0:
        notes.append(f"the receiver noise is coloured (a filter narrower than the sampling?): read at its highest "
                     f"level, {10 * math.log10(estimate.colour):.1f} dB over its lower reading")
    layout = recording.layout.describe()
    if test.score.max() < 1:
        row["notes"] = "; ".join([_no_detection_note(test)] + notes)
        return CaptureResult(str(path), params, layout, None, [], [], [row], noise_power=noise, process=process,
                             detection_test=test)
    analysis = analyse_target(signal, prf_hz=params.prf_hz, wavelength_m=params.wavelength_m, noise_power=noise,
                              params=process, ranged=False)
    row.update(target=0, rx_gain_db=gain_db)
    row.update(analysis.row)
    label, reason = classify(row, detected=True)
    row["class"] = label
    row["notes"] = "; ".join([f"class: {reason}"] + analysis.notes + notes)
    return CaptureResult(str(path), params, layout, None, [], [analysis], [row], noise_power=noise, process=process,
                         detection_test=test)
