"""Range processing, streamed over chunks of chirps.

Pass 1 (:func:`gate_statistics`): the windowed range FFT of every chirp of every channel, reduced on
the fly to what selection needs: the static (slow-time mean) and moving (MTI) power of every bin,
and, for the bins of the gate, each channel's mean, the channel covariance of the moving part and
the moving power per chunk. Memory does not grow with the capture's length.

Pass 2 (:func:`slow_time`): the same windowed DFT evaluated only at the bins in use, as one matrix
product per chunk, combined across channels with given weights.

Slow-time signals follow the paper's Doppler sign (approaching positive): the range FFT of a real
IF carries ``exp(+j 4 pi R / lambda)`` in its positive-frequency bins, so they are conjugated.
Arrays are (chirp, channel, sample) in, (chirp, bin) out.
"""

from dataclasses import dataclass

import numpy as np
from scipy.signal import get_window


def range_window(name, n_samples):
    """Symmetric window of ``n_samples`` for the range FFT."""
    return get_window(name, n_samples, fftbins=False).astype(np.float32)


def bin_range_m(bins, params, zero_pad):
    """Range of (fractional) FFT bins of a ``zero_pad`` times padded range FFT."""
    return np.asarray(bins, dtype=np.float64) * params.range_bin_m / zero_pad


@dataclass(frozen=True)
class GateStatistics:
    """Pass-1 summary of a capture.

    Attributes
    ----------
    range_m : ndarray (n_bins,)
        Range of every positive-frequency bin (padded grid).
    static_power, moving_power : ndarray (n_bins,)
        Per chirp and channel: power of the slow-time mean, and mean power about it (MTI).
    gate_bins : ndarray (B,) of int
        Bins inside the range gate.
    mean : ndarray (B, C) complex
        Slow-time mean of each gate bin and channel.
    covariance : ndarray (B, C, C) complex
        Channel covariance of the moving part of each gate bin.
    chunk_power : ndarray (n_chunks, B)
        Moving power (about the chunk's own mean) of each gate bin in each chunk, summed over channels.
    chunk_t_s : ndarray (n_chunks,)
        Centre time of each chunk.
    n_chirps : int
    clipped_fraction : float
        Share of the samples at the int16 full scale (0 for float samples).
    """

    range_m: np.ndarray
    static_power: np.ndarray
    moving_power: np.ndarray
    gate_bins: np.ndarray
    mean: np.ndarray
    covariance: np.ndarray
    chunk_power: np.ndarray
    chunk_t_s: np.ndarray
    n_chirps: int
    clipped_fraction: float = 0.0

    @property
    def gate_range_m(self):
        return self.range_m[self.gate_bins]

    @property
    def gate_moving_power(self):
        """Moving power per chirp summed over channels, per gate bin."""
        return np.real(np.trace(self.covariance, axis1=1, axis2=2))


def gate_statistics(reader, *, window="hann", zero_pad=1, min_range_m=0.0, max_range_m=np.inf, chunk_chirps=256):
    """Pass 1 over ``reader`` (a :class:`mdpipe.io.RadarlogReader`); see :class:`GateStatistics`."""
    params = reader.params
    n_fft = zero_pad * params.n_samples
    win = range_window(window, params.n_samples)
    ranges = bin_range_m(np.arange(n_fft // 2 + 1), params, zero_pad)
    gate = np.flatnonzero((ranges >= min_range_m) & (ranges <= max_range_m) & (np.arange(len(ranges)) > 0))
    n_ch = params.n_channels
    total = np.zeros((len(ranges), n_ch), dtype=np.complex128)
    power = np.zeros(len(ranges))
    cross = np.zeros((len(gate), n_ch, n_ch), dtype=np.complex128)
    chunk_power, chunk_t = [], []
    clip_level = reader.clip_level_v
    clipped = 0
    for first, block in reader.iter_chunks(chunk_chirps=chunk_chirps):
        if clip_level is not None:
            clipped += int(np.count_nonzero(np.abs(block) >= np.float32(clip_level)))
        spectrum = np.conj(np.fft.rfft(block * win, n=n_fft, axis=-1))  # (M, C, bins)
        total += spectrum.sum(axis=0).T
        power += np.einsum("mcb,mcb->b", spectrum, spectrum.conj()).real
        g = spectrum[:, :, gate].transpose(2, 1, 0)  # (B, C, M)
        cross += g @ g.conj().transpose(0, 2, 1)
        local = g - g.mean(axis=-1, keepdims=True)
        chunk_power.append(np.sum(np.abs(local) ** 2, axis=(1, 2)) / block.shape[0])
        chunk_t.append((first + 0.5 * block.shape[0]) * params.chirp_period_s)
    n = reader.n_chirps
    mean = total / n
    static = np.sum(np.abs(mean) ** 2, axis=1) / n_ch
    moving = power / (n * n_ch) - static
    gmean = mean[gate]
    covariance = cross / n - gmean[:, :, None] * gmean[:, None, :].conj()
    return GateStatistics(range_m=ranges, static_power=static, moving_power=np.maximum(moving, 0.0),
                          gate_bins=gate, mean=gmean, covariance=covariance,
                          chunk_power=np.array(chunk_power).reshape(-1, len(gate)),
                          chunk_t_s=np.array(chunk_t), n_chirps=n,
                          clipped_fraction=clipped / (n * n_ch * params.n_samples))


def slow_time(reader, bins, weights, *, window="hann", zero_pad=1, chunk_chirps=256, dtype="float32",
              all_bins=False):
    """Pass 2: complex slow-time signals of ``bins`` (padded grid), channels combined with ``weights``.

    Parameters
    ----------
    bins : array_like (K,) of int
    weights : ndarray (K, C) complex
        Signal of bin k is ``sum_c weights[k, c] * X[c, k]``.
    dtype : {"float32", "float64"}
        Precision of the transform.
    all_bins : bool
        Take the full FFT and pick the bins, instead of the DFT at those bins only.

    Returns
    -------
    ndarray, complex, shape (n_chirps, K)
    """
    params = reader.params
    real = np.dtype(dtype)
    complex_ = np.result_type(real, np.complex64)
    n = np.arange(params.n_samples)
    bins = np.asarray(bins)
    win = range_window(window, params.n_samples).astype(real)
    # conj(sum_n w x e^{-j 2 pi k n / Nfft}) = sum_n w x e^{+j 2 pi k n / Nfft} for real x
    dft = win[:, None] * np.exp(2j * np.pi * np.outer(n, bins) / (zero_pad * params.n_samples))
    dft_re, dft_im = dft.real.astype(real), dft.imag.astype(real)  # real products on real samples
    out = np.empty((reader.n_chirps, len(bins)), dtype=complex_)
    w = np.asarray(weights, dtype=complex_)
    for first, block in reader.iter_chunks(chunk_chirps=chunk_chirps):
        block = block.astype(real, copy=False)
        if all_bins:
            x = np.conj(np.fft.rfft(block * win, n=zero_pad * params.n_samples, axis=-1))[..., bins]
        else:
            x = np.empty(block.shape[:2] + (len(bins),), dtype=complex_)  # (M, C, K)
            x.real = block @ dft_re
            x.imag = block @ dft_im
        out[first:first + block.shape[0]] = np.einsum("mck,kc->mk", x, w)
    return out
