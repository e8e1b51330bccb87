"""Which range bins hold targets, how to combine the RX channels, and how to follow a target in range.

Detection works on moving power (MTI: the slow-time mean removed), so a static scatterer 30 dB
stronger than a drone does not win. The noise level is the median moving power over the gate.

A target is followed at a fractional range position: per chunk, the bin where it is strongest and
the power of its two neighbours give its offset from that bin through the window's range response
(:func:`fractional_track`); smoothed over chunks and interpolated per chirp, that track is where
pass 2 evaluates the range DFT (:func:`mdpipe.process.ranging.slow_time`).
"""

from dataclasses import dataclass
from typing import Optional

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.process.filters import moving_average, running_median
from mdpipe.process.ranging import bin_range_m, range_response

MIN_SEPARATION_BINS = 3  # Hann main lobe +-2 bins, plus the range-Doppler spread of fast blade tips
SIDELOBE_DB = 40.0       # peaks this far below the strongest are taken for its range sidelobes
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


def detect(stats, *, detection_db, max_targets, zero_pad=1):
    """Local maxima of moving power above the noise by ``detection_db``, strongest first."""
    power = stats.gate_moving_power
    floor = noise_power(stats)
    if len(power) < 3 or floor <= 0:
        return []
    separation = MIN_SEPARATION_BINS * zero_pad
    order = np.argsort(power)[::-1]
    found = []
    for index in order:
        if power[index] < floor * 10 ** (detection_db / 10):
            break
        if found and power[index] < power[found[0]] * 10 ** (-SIDELOBE_DB / 10):
            break
        left, right = power[max(index - 1, 0)], power[min(index + 1, len(power) - 1)]
        if power[index] < max(left, right) or any(abs(index - f) < separation for f in found):
            continue
        found.append(index)
        if len(found) == max_targets:
            break
    return [Detection(int(i), int(stats.gate_bins[i]), float(stats.gate_range_m[i]),
                      float(10 * np.log10(power[i] / floor))) for i in found]


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
    power = stats.gate_moving_power
    floor = max(noise_power(stats), np.finfo(float).tiny)
    return Detection(index, int(stats.gate_bins[index]), float(range_m),
                     float(10 * np.log10(max(power[index], np.finfo(float).tiny) / floor)), fixed_bin=float(fixed_bin))


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
    half = (min(SMOOTH_CHUNKS, n_chunks) | 1) // 2  # fewer chunks than SMOOTH_CHUNKS: still fewer than 2 half + 1
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


def track_range_m(track_bins, params, zero_pad=1):
    """Nearest and farthest range of a chirp track (m)."""
    return tuple(float(r) for r in bin_range_m([np.min(track_bins), np.max(track_bins)], params, zero_pad))
