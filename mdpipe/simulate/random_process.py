"""Seeded smooth random processes for scene realism (rotor rate wander, rough wings, swaying branches).

A process is a sum of K random-phase sinusoids ``w(t) = sqrt(2 / K) sum_k cos(2 pi f_k t + phi_k)``
with ``f_k ~ N(0, 1 / (2 pi T))``: Gaussian autocorrelation ``exp(-tau^2 / (2 T^2))`` (T, the
correlation time) and unit variance over realisations. Each realisation is then normalised to zero
mean and unit rms over the capture ``[0, D]`` exactly (both are closed-form integrals), so a scene's
``fraction`` means the same rms on every seed. It can be evaluated, and integrated in closed form, at
any times, so chunked synthesis gives the same values whatever the chunking.

Seeds: ``target_rng(seed, index, purpose)`` derives a generator from the scene seed, the target's
index and a purpose number, independent of the noise streams (which use ``SeedSequence(seed)``'s
spawned children).
"""

import numpy as np

COMPONENTS = 32
GRID_STEPS_PER_CORRELATION = 20
MAX_GRID = 100_000
TAG = 0x6D64  # keeps target draws apart from the noise streams of the same seed


def target_rng(seed, index, purpose):
    """Generator for the random draws of target ``index`` (``purpose`` separates independent uses)."""
    return np.random.Generator(np.random.PCG64(np.random.SeedSequence([seed, TAG, index, purpose])))


def _cos_integral(rate, phase, duration_s):
    """``int_0^D cos(rate t + phase) dt = D cos(phase + rate D / 2) sinc(rate D / (2 pi))``, elementwise.

    Written this way it has no cancellation as ``rate D`` goes to 0."""
    half = 0.5 * rate * duration_s
    return duration_s * np.cos(phase + half) * np.sinc(half / np.pi)


class SmoothProcess:
    """``n_series`` independent smooth processes normalised over ``[0, duration_s]``.

    Parameters
    ----------
    rng : numpy.random.Generator
    n_series : int
    correlation_s : float
        Correlation time T (s).
    duration_s : float
        The capture D over which each series has zero mean and unit rms.
    """

    def __init__(self, rng, n_series, *, correlation_s, duration_s):
        self.freqs_hz = rng.normal(0.0, 1.0 / (2.0 * np.pi * correlation_s), (n_series, COMPONENTS))
        self.phases_rad = rng.uniform(0.0, 2.0 * np.pi, (n_series, COMPONENTS))
        amplitude = np.sqrt(2.0 / COMPONENTS)
        omega = 2.0 * np.pi * self.freqs_hz
        mean = amplitude * _cos_integral(omega, self.phases_rad, duration_s).sum(axis=1) / duration_s
        # mean square: products of cosines -> cosines at the sums and differences of the components
        diff = _cos_integral(omega[:, :, None] - omega[:, None, :],
                             self.phases_rad[:, :, None] - self.phases_rad[:, None, :], duration_s)
        total = _cos_integral(omega[:, :, None] + omega[:, None, :],
                              self.phases_rad[:, :, None] + self.phases_rad[:, None, :], duration_s)
        mean_square = 0.5 * amplitude**2 * (diff + total).sum(axis=(1, 2)) / duration_s
        sigma = np.sqrt(np.maximum(mean_square - mean**2, 1e-300))
        self.gain = amplitude / sigma  # w = gain sum_k cos(...) - shift: zero mean, unit rms over [0, D]
        self.shift = mean / sigma
        self.correlation_s = correlation_s
        self.duration_s = duration_s

    def value(self, t_s, series):
        """Normalised ``w(t)`` of one series at times ``t_s`` (any shape)."""
        t = np.asarray(t_s, dtype=np.float64)
        out = np.zeros_like(t)
        for f, phi in zip(self.freqs_hz[series], self.phases_rad[series]):
            out += np.cos(2.0 * np.pi * f * t + phi)
        return self.gain[series] * out - self.shift[series]

    def integral(self, t_s, series):
        """``int_0^t w(s) ds`` of one series at times ``t_s`` (closed form)."""
        t = np.asarray(t_s, dtype=np.float64)
        out = np.zeros_like(t)
        for f, phi in zip(self.freqs_hz[series], self.phases_rad[series]):
            if f == 0.0:
                out += t * np.cos(phi)
            else:  # 2 sin(w t / 2) cos(phi + w t / 2) / w: no cancellation as w t goes to 0
                half = np.pi * f * t
                out += np.sin(half) * np.cos(phi + half) / (np.pi * f)
        return self.gain[series] * out - self.shift[series] * t

    def slope_bound(self, series):
        """Bound on ``|dw/dt|`` (1/s)."""
        return float(self.gain[series] * np.sum(2.0 * np.pi * np.abs(self.freqs_hz[series])))

    def max_abs(self, series):
        """Bound on ``|w(t)|`` over the capture: the largest value on a grid plus half a grid step times the slope
        bound, or the sum of the components' amplitudes if that is smaller (long captures, coarse grids)."""
        n = int(min(MAX_GRID, np.ceil(GRID_STEPS_PER_CORRELATION * self.duration_s / self.correlation_s) + 1))
        t = np.linspace(0.0, self.duration_s, max(n, 2))
        on_grid = np.max(np.abs(self.value(t, series))) + 0.5 * (t[1] - t[0]) * self.slope_bound(series)
        return float(min(on_grid, self.gain[series] * COMPONENTS + abs(self.shift[series])))
