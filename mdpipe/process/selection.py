"""Which range bins hold targets, how to combine the RX channels, and how to follow a target in range.

Detection works on moving power (MTI: the slow-time mean removed), so a static scatterer 30 dB
stronger than a drone does not win. The noise level is the median moving power over the gate.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.process.filters import running_median

MIN_SEPARATION_BINS = 3  # Hann main lobe +-2 bins, plus the range-Doppler spread of fast blade tips
SIDELOBE_DB = 40.0       # peaks this far below the strongest are taken for its range sidelobes
TRACK_HALF_WIDTH_BINS = 2
SWITCH_DB = 3.0


@dataclass(frozen=True)
class Detection:
    """A target found in the range gate: its peak bin (padded grid), range and SNR of the moving power."""

    gate_index: int
    bin: int
    range_m: float
    snr_db: float


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


def manual_detection(stats, range_m):
    """The gate bin nearest ``range_m`` (``--range-m``)."""
    index = int(np.argmin(np.abs(stats.gate_range_m - range_m)))
    power = stats.gate_moving_power
    floor = max(noise_power(stats), np.finfo(float).tiny)
    return Detection(index, int(stats.gate_bins[index]), float(stats.gate_range_m[index]),
                     float(10 * np.log10(max(power[index], np.finfo(float).tiny) / floor)))


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


def stitch(signals, path, chunk_chirps, *, overlap=16):
    """One phase-continuous slow-time signal that follows ``path`` across the columns of ``signals``.

    Parameters
    ----------
    signals : ndarray (n_chirps, K)
        Slow time of the K bins the path visits.
    path : ndarray (n_chunks,)
        Column of ``signals`` to use in each chunk of ``chunk_chirps`` chirps.

    At a change of column the new column is scaled by the complex least-squares factor that matches
    it to the old one over ``overlap`` chirps around the boundary, so no phase step enters the
    spectrum.
    """
    out = np.empty(signals.shape[0], dtype=np.complex64)
    factor = np.ones(signals.shape[1], dtype=np.complex128)
    previous = path[0]
    for chunk, column in enumerate(path):
        start = chunk * chunk_chirps
        stop = min(start + chunk_chirps, signals.shape[0])
        if column != previous:
            lo, hi = max(start - overlap, 0), min(start + overlap, signals.shape[0])
            new, old = signals[lo:hi, column], signals[lo:hi, previous] * factor[previous]
            denominator = np.vdot(new, new)
            factor[column] = np.vdot(new, old) / denominator if abs(denominator) > 0 else 1.0
            previous = column
        out[start:stop] = signals[start:stop, column] * factor[column]
    return out
