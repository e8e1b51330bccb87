"""Slow-time Doppler analysis: spectrogram, dwell power spectrum, the strongest line of each frame.

Frequencies follow the paper's sign (approaching positive) and are centred (``-PRF/2 .. PRF/2``).
Arrays are (frequency, time) for spectrograms, as ``scipy.signal.ShortTimeFFT`` returns them.

The spectrogram is that of ``ShortTimeFFT(hann(n, sym=False), hop, fs, fft_mode="centered",
scale_to="magnitude")`` over its frames clear of the borders (a test holds the two equal), written
out in numpy: importing scipy.signal takes 0.7 s (it pulls in scipy.stats), more than reading a
whole 1.3 GB capture.
"""

from dataclasses import dataclass

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from mdpipe.process.filters import parabolic_offset


STFT_BLOCK_FRAMES = 4096
STFT_BLOCK_BYTES = 8 * 2**20   # ... and at most this much of frames' transforms at once (long, zero-padded frames)


@dataclass(frozen=True)
class Spectrogram:
    """Power (f, t) in V^2 per bin, with its axes ``f_hz`` (centred) and ``t_s`` (frame centres)."""

    power: np.ndarray
    t_s: np.ndarray
    f_hz: np.ndarray
    window_s: float
    hop_s: float


@dataclass(frozen=True)
class PowerSpectrum:
    """Dwell power spectrum (Hann-windowed periodogram), ``power`` per bin at centred ``f_hz``."""

    power: np.ndarray
    f_hz: np.ndarray

    @property
    def resolution_hz(self):
        return float(self.f_hz[1] - self.f_hz[0])


def periodic_hann(n):
    """Hann window of length n for spectral analysis (``scipy.signal.windows.hann(n, sym=False)``)."""
    return np.hanning(n + 1)[:-1]


def noise_level_per_bin(noise_power, n_window):
    """Expected power per bin of white noise of variance ``noise_power`` in a Hann spectrum of ``n_window``
    samples scaled as :func:`spectrogram` and :func:`power_spectrum` are (a tone of amplitude a gives a^2)."""
    window = periodic_hann(n_window)
    return noise_power * np.sum(window ** 2) / np.sum(window) ** 2


def spectrogram(signal, *, prf_hz, window_s, hop_s, pad=1):
    """Short-time power spectrum of a complex slow-time ``signal`` (Hann window).

    ``window_s`` and ``hop_s`` are rounded to whole chirps (window at least 8, at most half the
    signal; hop at least 1). Frame p covers chirps ``p hop - n // 2 ... p hop - n // 2 + n - 1``;
    the frames kept are those whose non-zero window samples (all but the first, which a periodic
    Hann window zeroes) lie inside the signal (at least one, zero-padded, for a signal shorter
    than two windows and a hop). ``pad``: each frame's transform is read on ``pad`` times as many Doppler bins
    (the frame zero-padded), the same spectrum sampled finer.
    """
    signal = np.asarray(signal)
    n_window = min(max(8, int(round(window_s * prf_hz))), max(2, len(signal) // 2))
    hop = max(1, int(round(hop_s * prf_hz)))
    middle = n_window // 2
    first = -(-(middle - 1) // hop)
    last = (len(signal) - n_window + middle) // hop + 1
    padded = np.pad(signal, (1, 0))  # the zero under the window's zero first sample
    starts = np.arange(first, last) * hop - middle + 1
    if last <= first:  # too short for a frame free of the borders: one padded frame in the middle
        padded = np.pad(signal, (middle, n_window))
        first = last = len(signal) // 2 // hop
        last += 1
        starts = np.array([first * hop])
    views = sliding_window_view(padded, n_window)
    window = periodic_hann(n_window)
    n_fft = n_window * int(pad)
    power = np.empty((n_fft, len(starts)))
    step = max(1, min(STFT_BLOCK_FRAMES, STFT_BLOCK_BYTES // (16 * n_fft)))
    for block in range(0, len(starts), step):  # bounded temporaries, whatever the dwell and frame
        frames = views[starts[block:block + step]] * window
        spectra = np.fft.fftshift(np.fft.fft(frames, n=n_fft, axis=-1), axes=-1) / window.sum()
        power[:, block:block + step] = np.abs(spectra.T) ** 2
    return Spectrogram(power=power, t_s=np.arange(first, last) * hop / prf_hz,
                       f_hz=np.fft.fftshift(np.fft.fftfreq(n_fft, 1.0 / prf_hz)),
                       window_s=n_window / prf_hz, hop_s=hop / prf_hz)


def power_spectrum(signal, *, prf_hz):
    """Hann-windowed periodogram of the whole dwell, normalised so a tone of amplitude a has power a^2."""
    n = len(signal)
    window = periodic_hann(n)
    spectrum = np.fft.fftshift(np.fft.fft(signal * window)) / window.sum()
    return PowerSpectrum(power=np.abs(spectrum) ** 2, f_hz=np.fft.fftshift(np.fft.fftfreq(n, 1.0 / prf_hz)))


def frame_peaks_hz(spec, *, prf_hz):
    """Doppler of the strongest line of each frame of ``spec`` (Hz), refined by a parabola through its neighbours
    and unwrapped across the ends of the span (a body whose Doppler drifts past +-PRF/2 goes on beyond it, not
    back from the other end: :func:`fold_hz` folds it back)."""
    log_power = np.log(spec.power + np.finfo(float).tiny)
    peak = np.argmax(spec.power, axis=0)
    inner = np.clip(peak, 1, len(spec.f_hz) - 2)
    left, mid, right = (log_power[inner + d, np.arange(len(peak))] for d in (-1, 0, 1))
    f_peak = spec.f_hz[inner] + parabolic_offset(left, mid, right) * (spec.f_hz[1] - spec.f_hz[0])
    return np.unwrap(f_peak, period=prf_hz)


def fold_hz(doppler_hz, *, prf_hz):
    """Doppler folded into the unambiguous span ``[-PRF/2, PRF/2)``: what the slow-time samples show of it."""
    return np.mod(np.asarray(doppler_hz, dtype=np.float64) + prf_hz / 2, prf_hz) - prf_hz / 2


def demodulate(signal, doppler_hz, *, prf_hz):
    """Remove a time-varying Doppler: multiply by ``exp(-j 2 pi integral f dt)``; ``signal`` (n_chirps, ...): its
    first axis is time, any further axes (channels, ramp parts) share the phase."""
    phase = 2 * np.pi * np.cumsum(doppler_hz) / prf_hz
    factor = np.exp(-1j * phase).astype(np.complex64)
    return signal * factor.reshape(factor.shape + (1,) * (np.ndim(signal) - 1))
