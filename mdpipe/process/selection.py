"""Which range bins hold targets, how to combine the RX channels, and how to follow a target in range.

Detection is a range-Doppler CFAR on pass 1's Doppler spectra (each probed block's slow time,
its mean removed: a static scatterer 40 dB stronger than a drone leaves nothing there; the 0 Hz
cell, where clutter that barely moves lands, is left out as well). The noise level is the median over the
gate's bins and Doppler cells; the thresholds come from the Gamma statistics of an average of
``blocks x channels`` looks, set so that noise alone gives a detection in a capture with
probability ``FALSE_ALARM_PROBABILITY``: half of it to a line test (the strongest Doppler cell of
a bin: a body line, a rotor or wingbeat line), half to a band test (the mean over the Doppler
cells: blade flashes spread over the span). The more chirps, the lower both thresholds stand.

A target is followed at a fractional range position: per chunk, the bin where it is strongest and
the power of its two neighbours give its offset from that bin through the window's range response
(:func:`fractional_track`); smoothed over chunks and interpolated per chirp, that track is where
pass 2 evaluates the range DFT (:func:`mdpipe.process.ranging.slow_time`).
"""

from dataclasses import dataclass
from typing import Optional

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.process.cfar import gamma_isf, normal_isf
from mdpipe.process.doppler import periodic_hann
from mdpipe.process.filters import moving_average, running_median
from mdpipe.process.ranging import range_response

MIN_SEPARATION_BINS = 3  # Hann main lobe +-2 bins, plus the range-Doppler spread of fast blade tips
SIDELOBE_DB = 40.0       # peaks this far below the strongest are taken for its range sidelobes
FALSE_ALARM_PROBABILITY = 1e-3  # per capture of noise only
CLUTTER_CELLS = 0        # Doppler cells either side of the 0 Hz cell also left out of detection
TRACK_HALF_WIDTH_BINS = 2
SWITCH_DB = 3.0
SMOOTH_CHUNKS = 5        # fractional track averaged over this many chunks (after a 5-chunk median)
OFFSET_TABLE_POINTS = 201


@dataclass(frozen=True)
class Detection:
    """A target found in the range gate: its peak bin (padded grid), range and SNR of the moving power.

    ``fixed_bin`` (fractional, padded grid): analyse this position for the whole dwell instead of
    following the target (a range given by the user).
    """

    gate_index: int
    bin: int
    range_m: float
    snr_db: float
    fixed_bin: Optional[float] = None


def noise_power(stats):
    """Moving power of an empty bin (median over the gate), per chirp, summed over channels."""
    return float(np.median(stats.gate_moving_power))


@dataclass(frozen=True)
class DetectionTest:
    """The range-Doppler test of every gate bin, in units of the noise's mean power per Doppler cell.

    Attributes
    ----------
    noise_cell : float
        Mean noise power per Doppler cell of ``stats.doppler_power`` (V^2).
    line, band : ndarray (B,)
        Strongest Doppler cell, and mean over the Doppler cells, of each gate bin, over ``noise_cell``
        (cells within ``CLUTTER_CELLS`` of 0 Hz left out).
    line_threshold, band_threshold : float
        What noise alone exceeds anywhere in the gate with probability ``false_alarm_probability / 2`` each.
    false_alarm_probability : float
        Per capture (noise only, over all bins and cells).
    looks, band_looks : int
        Shapes n and m of the Gamma laws of a cell and of a bin's band mean (see :func:`detection_test`).
    """

    noise_cell: float
    line: np.ndarray
    band: np.ndarray
    line_threshold: float
    band_threshold: float
    false_alarm_probability: float
    looks: int
    band_looks: int

    def shortfall(self):
        """The strongest line and band against their thresholds, dB over the noise per cell (why nothing was
        detected)."""
        def db(x):
            return 10 * np.log10(max(x, np.finfo(float).tiny))
        return (f"strongest Doppler line {db(self.line.max()):.1f} dB < {db(self.line_threshold):.1f} dB, strongest "
                f"band {db(self.band.max()):.1f} dB < {db(self.band_threshold):.1f} dB, over the noise per cell")

    @property
    def score(self):
        """Per gate bin, the larger of line and band over their thresholds: a target where >= 1."""
        return np.maximum(self.line / self.line_threshold, self.band / self.band_threshold)


def block_noise_response(n_chirps):
    """Noise in the Doppler cells of a block of ``n_chirps`` with its mean removed and a periodic Hann window.

    The cells are ``Y = F W P x`` (P removes the mean, W the window, F the DFT); for white noise of
    variance s^2 their covariance is ``s^2 A A^H`` with ``A = F W P``.

    Returns
    -------
    gain : ndarray (L,)
        Each cell's noise power relative to a cell without the mean removal (1 except near 0 Hz:
        1/3 at 0, 5/6 at +-1).
    rho : ndarray (L, L)
        Magnitude of the correlation between cells (for the periodic Hann, 2/3 between
        neighbours, 1/6 two apart, 0 beyond, away from 0 Hz).
    """
    window = periodic_hann(n_chirps)
    projector = np.eye(n_chirps) - 1.0 / n_chirps
    a = np.fft.fft(window[:, None] * projector, axis=0)
    covariance = a @ a.conj().T
    variance = np.real(np.diagonal(covariance))
    return variance / np.sum(window ** 2), np.abs(covariance) / np.sqrt(np.outer(variance, variance))


def detection_test(stats, *, false_alarm_probability=FALSE_ALARM_PROBABILITY):
    """Range-Doppler CFAR over the gate (see the module notes); returns a :class:`DetectionTest`.

    Each Doppler cell of ``stats.doppler_power``, divided by its noise gain (the mean removal takes
    noise out of the cells next to 0 Hz: :func:`block_noise_response`), is for noise the mean of
    ``n = blocks x channels`` exponential powers: ``mu Gamma(n) / n``. The noise level ``mu`` is the
    median over every gate bin and cell divided by the median of ``Gamma(n) / n`` (targets occupy
    few of them). Line test: the strongest cell against the Gamma(n) quantile at ``p / 2`` shared
    by all cells (union bound). Band test (energy spread over the span: blade flashes): the mean
    over a bin's L cells, correlated through the window, is ``Gamma(m) / m`` with
    ``m = n L^2 / sum_ij rho_ij^2`` (variance-matched, rounded down), against the quantile at
    ``p / 2`` shared by the bins.
    """
    return cell_test(stats.doppler_power, looks=stats.doppler_blocks * stats.covariance.shape[1],
                     false_alarm_probability=false_alarm_probability)


def cell_test(power, *, looks, noise_cell=None, noise_error=0.0, false_alarm_probability=FALSE_ALARM_PROBABILITY):
    """The line and band tests of :func:`detection_test` on Doppler spectra ``power`` (B, L), each the mean of
    ``looks`` periodograms (periodic Hann, the block's mean removed, over the window's sum squared), of B bins;
    ``noise_cell``: the noise's mean power per cell where known, else the median rule above. Returns a
    :class:`DetectionTest`.

    A ``noise_cell`` estimated apart, with relative standard error ``noise_error``, takes half the false-alarm
    probability: the thresholds stand ``z`` standard errors higher, ``z`` exceeded with that half (an estimate 1 %
    low would pass noise over 40 000 looks of a band 2 % over its mean); the tests share the other half."""
    n_gate, n_cells = power.shape
    used = np.flatnonzero(np.minimum(np.arange(n_cells), n_cells - np.arange(n_cells)) > CLUTTER_CELLS)
    gain, rho = block_noise_response(n_cells)
    cells = power[:, used] / gain[used]
    noise = float(np.median(cells)) / (gamma_isf(looks, 0.5) / looks) if noise_cell is None else float(noise_cell)
    band_looks = max(1, int(looks * len(used) ** 2 / np.sum(rho[np.ix_(used, used)] ** 2)))
    p = false_alarm_probability / (4 if noise_error > 0 else 2)
    margin = 1.0 + normal_isf(false_alarm_probability / 2) * noise_error if noise_error > 0 else 1.0
    tiny = np.finfo(float).tiny
    return DetectionTest(noise_cell=noise, line=cells.max(axis=1) / max(noise, tiny),
                         band=cells.mean(axis=1) / max(noise, tiny),
                         line_threshold=margin * gamma_isf(looks, p / cells.size) / looks,
                         band_threshold=margin * gamma_isf(band_looks, p / n_gate) / band_looks,
                         false_alarm_probability=false_alarm_probability, looks=looks, band_looks=band_looks)


def detect(stats, test, *, max_targets, zero_pad=1):
    """Gate bins that pass ``test`` (a :class:`DetectionTest`) and are local maxima of its score, strongest first.

    Bins closer than ``MIN_SEPARATION_BINS`` to a stronger detection, or with moving power
    ``SIDELOBE_DB`` below the strongest detection's (its range sidelobes), are left out.
    """
    score, power = test.score, stats.gate_moving_power
    if len(score) < 3 or test.noise_cell <= 0:
        return []
    separation = MIN_SEPARATION_BINS * zero_pad
    found = []
    for index in np.argsort(score)[::-1]:
        if score[index] < 1:
            break
        if score[index] < max(score[max(index - 1, 0)], score[min(index + 1, len(score) - 1)]):
            continue
        if found and power[index] < power[found[0]] * 10 ** (-SIDELOBE_DB / 10):
            continue
        if any(abs(index - f) < separation for f in found):
            continue
        found.append(index)
        if len(found) == max_targets:
            break
    return [Detection(int(i), int(stats.gate_bins[i]), float(stats.gate_range_m[i]), _snr_db(stats, i)) for i in found]


def manual_detection(stats, range_m, *, gate_m, params, zero_pad=1):
    """A fixed gate at ``range_m`` (``--range-m``): analysed there for the whole dwell, not followed.

    Raises :class:`ParameterError` when ``range_m`` lies outside ``gate_m`` (min, max), itself
    inside the capture's range [0, ``params.max_range_m``].
    """
    low, high = gate_m
    if not low <= range_m <= high:
        raise ParameterError(f"range_m={range_m:g} m lies outside the range gate [{low:g}, {high:.6g}] m "
                             f"(min_range_m, max_range_m; the capture reaches {params.max_range_m:.6g} m): "
                             "choose a range inside it or move the gate")
    fixed_bin = range_m / (params.range_bin_m / zero_pad)
    index = int(np.clip(np.rint(fixed_bin) - stats.gate_bins[0], 0, len(stats.gate_bins) - 1))
    return Detection(index, int(stats.gate_bins[index]), float(range_m), _snr_db(stats, index), fixed_bin=float(fixed_bin))


def detection_at(stats, fixed_bin, *, range_m):
    """A detection held at ``fixed_bin`` (padded grid, fractional; ``range_m``): its gate bin the nearest, its SNR
    that bin's (the hub between a drone's two range-Doppler images)."""
    index = int(np.argmin(np.abs(np.asarray(stats.gate_bins, dtype=float) - fixed_bin)))
    return Detection(index, int(stats.gate_bins[index]), float(range_m), _snr_db(stats, index), fixed_bin=fixed_bin)


def _snr_db(stats, index):
    """The moving power of gate bin ``index`` over the noise's (:func:`noise_power`), dB."""
    floor = max(noise_power(stats), np.finfo(float).tiny)
    return float(10 * np.log10(max(float(stats.gate_moving_power[index]), np.finfo(float).tiny) / floor))



def channel_weights(covariance):
    """Coherent combining toward the target: the dominant eigenvector of each bin's moving covariance.

    Parameters
    ----------
    covariance : ndarray (K, C, C)

    Returns
    -------
    weights : ndarray (K, C)
        Conjugated unit eigenvectors: ``sum_c w_c x_c`` adds the channels in phase.
    gain_db : ndarray (K,)
        SNR gain over one channel for a target with this spatial signature in white noise,
        ``10 log10(lambda_max / mean(diag))``: 10 log10(C) for a point target.
    """
    values, vectors = np.linalg.eigh(covariance)
    dominant = vectors[:, :, -1]
    diagonal = np.real(np.diagonal(covariance, axis1=1, axis2=2)).mean(axis=1)
    gain = values[:, -1] / np.maximum(diagonal, np.finfo(float).tiny)
    return np.conj(dominant), 10 * np.log10(np.maximum(gain, np.finfo(float).tiny))


def track(stats, detection):
    """Gate index of the target in each chunk, followed outwards from the chunk where it is strongest.

    In each chunk the strongest bin within +-2 of the current one takes over only if it beats the
    current bin by ``SWITCH_DB`` (hysteresis: a target between two bins does not flicker), then the
    path is median-filtered over 5 chunks.

    Returns
    -------
    ndarray (n_chunks,) of gate indices
    """
    power = stats.chunk_power
    n_chunks, n_gate = power.shape
    path = np.empty(n_chunks, dtype=int)
    start = int(np.argmax(power[:, detection.gate_index]))

    def follow(chunks, current):
        for chunk in chunks:
            lo, hi = max(current - TRACK_HALF_WIDTH_BINS, 0), min(current + TRACK_HALF_WIDTH_BINS + 1, n_gate)
            best = lo + int(np.argmax(power[chunk, lo:hi]))
            if power[chunk, best] > power[chunk, current] * 10 ** (SWITCH_DB / 10):
                current = best
            path[chunk] = current

    follow(range(start, n_chunks), detection.gate_index)
    follow(range(start - 1, -1, -1), path[start])
    return np.rint(running_median(path, min(5, n_chunks) | 1)).astype(int)


def _offset_table(window, n_samples, zero_pad):
    """Offsets d in [-1/2, 1/2] bin and the log power ratio ln(P(k+1) / P(k-1)) of a tone at k + d (increasing)."""
    d = np.linspace(-0.5, 0.5, OFFSET_TABLE_POINTS)
    right = np.abs(range_response(1 - d, window=window, n_samples=n_samples, zero_pad=zero_pad))
    left = np.abs(range_response(1 + d, window=window, n_samples=n_samples, zero_pad=zero_pad))
    return d, 2 * np.log(right / left)


def fractional_track(stats, path, *, window, n_samples, zero_pad=1):
    """Fractional gate index of the target in each chunk.

    In each chunk the strongest of the path's bin and its two neighbours is taken as k; a tone at
    k + d gives its neighbours the powers ``P R(1 - d)^2`` (k + 1) and ``P R(1 + d)^2`` (k - 1),
    R the range response of the window, so d follows from their ratio (noise level, the median
    chunk power over the gate, subtracted first), inverted on a table of R over [-1/2, 1/2] bin.
    The per-chunk positions are median-filtered over 5 chunks and averaged over ``SMOOTH_CHUNKS``
    (ends padded by odd reflection, so a constant-velocity track is kept exactly).

    Parameters
    ----------
    path : ndarray (n_chunks,) of int
        Gate index per chunk (:func:`track`).

    Returns
    -------
    ndarray (n_chunks,), fractional gate index
    """
    power = stats.chunk_power
    n_chunks, n_gate = power.shape
    rows = np.arange(n_chunks)
    noise = np.median(power, axis=1)
    around = np.clip(path[:, None] + np.arange(-1, 2), 0, n_gate - 1)
    k = around[rows, np.argmax(power[rows[:, None], around], axis=1)]
    tiny = np.finfo(float).tiny
    signal = np.maximum(power - noise[:, None], tiny)
    ratio = np.log(signal[rows, np.minimum(k + 1, n_gate - 1)]) - np.log(signal[rows, np.maximum(k - 1, 0)])
    d_table, ratio_table = _offset_table(window, n_samples, zero_pad)
    offset = np.interp(ratio, ratio_table, d_table)
    offset[(k == 0) | (k == n_gate - 1)] = 0.0  # a neighbour outside the gate: no estimate
    position = running_median(k + offset, min(5, n_chunks) | 1)
    half = (min(SMOOTH_CHUNKS, n_chunks) | 1) // 2  # odd window, at most one chunk longer than the track
    position = moving_average(np.pad(position, half, mode="reflect", reflect_type="odd"), 2 * half + 1)
    return np.clip(position[half:half + n_chunks], 0, n_gate - 1)


def chirp_track(stats, detection, *, window, n_samples, zero_pad=1):
    """Each chirp's position of ``detection`` (padded-grid bins, fractional) and the gate bins it visits.

    A fixed bin (manual range) stays put; otherwise the fractional track of the chunks
    (:func:`fractional_track`) is interpolated linearly between the chunks' centres.

    Returns
    -------
    track_bins : ndarray (n_chirps,)
    visits : ndarray (B,)
        Chunks spent in each gate bin (weights for the channel covariance).
    """
    n_gate = len(stats.gate_bins)
    if detection.fixed_bin is not None:
        return np.full(stats.n_chirps, detection.fixed_bin), np.bincount([detection.gate_index], minlength=n_gate)
    coarse = track(stats, detection)
    chunk_index = fractional_track(stats, coarse, window=window, n_samples=n_samples, zero_pad=zero_pad)
    per_chirp = np.interp(np.arange(stats.n_chirps), stats.chunk_centres, chunk_index)
    track_bins = np.interp(per_chirp, np.arange(n_gate), stats.gate_bins)
    return track_bins, np.bincount(np.rint(chunk_index).astype(int), minlength=n_gate)
