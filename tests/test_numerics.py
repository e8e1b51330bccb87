"""The numpy stand-ins on the processing path equal the scipy functions they replace (which stay oracles)."""

import numpy as np
import pytest
from scipy import ndimage
from scipy.signal import ShortTimeFFT
from scipy.signal.windows import hann

from mdpipe.process import doppler, filters


@pytest.fixture
def x():
    return np.random.default_rng(7).normal(size=503)


@pytest.mark.parametrize("size", [1, 2, 3, 8, 25])
@pytest.mark.parametrize("mode", ["nearest", "wrap", "constant"])
def test_moving_average_is_uniform_filter1d(x, size, mode):
    np.testing.assert_allclose(filters.moving_average(x, size, mode=mode),
                               ndimage.uniform_filter1d(x, size, mode=mode), atol=1e-12)


def test_moving_average_along_an_axis(x):
    rows = x[:500].reshape(5, 100)
    np.testing.assert_allclose(filters.moving_average(rows, 9, axis=1),
                               ndimage.uniform_filter1d(rows, 9, axis=1, mode="nearest"), atol=1e-12)


@pytest.mark.parametrize("size", [2, 3, 8, 25, 600])
def test_moving_average_inside_averages_only_the_samples_inside(x, size):
    """``mode="inside"``: zeros beyond the edges, divided by how many samples lie inside the window (a window
    longer than the signal too)."""
    inside = ndimage.uniform_filter1d(x, size, mode="constant") / ndimage.uniform_filter1d(
        np.ones_like(x), size, mode="constant")
    np.testing.assert_allclose(filters.moving_average(x, size, mode="inside"), inside, atol=1e-12)
    rows = np.stack([x, 2 * x])
    np.testing.assert_allclose(filters.moving_average(rows.T, size, mode="inside", axis=0),
                               np.stack([inside, 2 * inside]).T, atol=1e-12)


@pytest.mark.parametrize("size", [1, 3, 5, 11])
def test_running_min_and_median(x, size):
    np.testing.assert_array_equal(filters.running_min(x, size), ndimage.minimum_filter1d(x, size, mode="nearest"))
    np.testing.assert_array_equal(filters.running_max(x, size), ndimage.maximum_filter1d(x, size, mode="nearest"))
    np.testing.assert_array_equal(filters.running_median(x, size), ndimage.median_filter(x, size=size, mode="nearest"))
    np.testing.assert_array_equal(filters.running_median(x, size, mode="wrap"),
                                  ndimage.median_filter(x, size=size, mode="wrap"))


@pytest.mark.parametrize("n", [filters.MEDIAN_CHUNK - 1, filters.MEDIAN_CHUNK, 2 * filters.MEDIAN_CHUNK + 7])
def test_running_median_taken_in_chunks_is_scipy_s(n):
    """A running median longer than one chunk (taken a chunk at a time, its windows' copy bounded) is scipy's at
    every sample, the chunks' seams and both edges included."""
    x = np.random.default_rng(n).exponential(1.0, n)
    for mode in ("nearest", "wrap"):
        np.testing.assert_array_equal(filters.running_median(x, 257, mode=mode),
                                      ndimage.median_filter(x, size=257, mode=mode))

def test_local_maxima_against_argrelextrema():
    """Strict maxima are scipy's; a plateau counts once at its left end; NaN is never a maximum."""
    from scipy.signal import argrelextrema

    x = np.random.default_rng(5).normal(size=500)
    np.testing.assert_array_equal(filters.local_maxima(x), argrelextrema(x, np.greater)[0])
    np.testing.assert_array_equal(filters.local_maxima(np.array([0, 2, 2, 1, np.nan, 3, 0.0])), [1, 5])



def test_parabolic_offset_is_the_vertex_and_stays_within_half_a_sample():
    """Three samples of -(x - 0.3)^2 peak at +0.3; a plateau or an upward curve gives 0; three nearly collinear
    values off a maximum (an autocorrelation's slope at a search window's edge, where an unclipped vertex
    lay 8505 samples away) give at most half a sample."""
    np.testing.assert_allclose(filters.parabolic_offset(-1.69, -0.09, -0.49), 0.3)
    np.testing.assert_array_equal(filters.parabolic_offset([1.0, 0.0], [1.0, 1.0], [1.0, 2.0]), [0.0, 0.0])
    slope = (0.018841896515679905, 0.017571506601014898, 0.016300967316577424)
    assert slope[0] - 2 * slope[1] + slope[2] < 0  # curves down, by rounding only
    assert filters.parabolic_offset(*slope) == -0.5


@pytest.mark.parametrize("n_window, hop", [(64, 16), (24, 3), (33, 7), (128, 1)])
def test_spectrogram_is_short_time_fft(n_window, hop):
    prf = 15625.0
    signal = np.random.default_rng(3).normal(size=(4000, 2)) @ np.array([1.0, 1j])
    mine = doppler.spectrogram(signal, prf_hz=prf, window_s=n_window / prf, hop_s=hop / prf)
    stft = ShortTimeFFT(hann(n_window, sym=False), hop=hop, fs=prf, fft_mode="centered", scale_to="magnitude")
    p0, p1 = stft.lower_border_end[1], stft.upper_border_begin(len(signal))[1]
    reference = np.abs(stft.stft(signal, p0=p0, p1=p1)) ** 2
    np.testing.assert_allclose(mine.power, reference, rtol=1e-9, atol=1e-12 * reference.max())
    np.testing.assert_allclose(mine.t_s, stft.t(len(signal), p0=p0, p1=p1))
    np.testing.assert_allclose(mine.f_hz, stft.f)


@pytest.mark.parametrize("pad", [2, 8])
def test_padded_spectrogram_is_zero_padded_short_time_fft(pad):
    """``pad``: the same frames transformed on ``pad`` times as many bins (scipy's ``mfft``), the unpadded bins among
    them unchanged."""
    prf, n_window, hop = 15625.0, 33, 7
    signal = np.random.default_rng(3).normal(size=(4000, 2)) @ np.array([1.0, 1j])
    mine = doppler.spectrogram(signal, prf_hz=prf, window_s=n_window / prf, hop_s=hop / prf, pad=pad)
    stft = ShortTimeFFT(hann(n_window, sym=False), hop=hop, fs=prf, fft_mode="centered", mfft=pad * n_window,
                        scale_to="magnitude")
    p0, p1 = stft.lower_border_end[1], stft.upper_border_begin(len(signal))[1]
    reference = np.abs(stft.stft(signal, p0=p0, p1=p1)) ** 2
    np.testing.assert_allclose(mine.power, reference, rtol=1e-9, atol=1e-12 * reference.max())
    np.testing.assert_allclose(mine.f_hz, stft.f)
    plain = doppler.spectrogram(signal, prf_hz=prf, window_s=n_window / prf, hop_s=hop / prf)
    zero = int(np.argmin(np.abs(mine.f_hz)))
    np.testing.assert_allclose(mine.power[zero % pad::pad], plain.power, rtol=1e-9, atol=1e-12 * plain.power.max())


def test_spectrogram_of_a_short_signal_has_one_frame():
    spec = doppler.spectrogram(np.ones(20, complex), prf_hz=1000.0, window_s=0.1, hop_s=0.05)
    assert spec.power.shape[1] == 1 and np.all(np.isfinite(spec.power))
    assert spec.f_hz[np.argmax(spec.power[:, 0])] == 0.0


@pytest.mark.parametrize("k", [2, 5, 12, 20])
def test_lagrange_basis_is_barycentric_interpolator(k):
    from scipy.interpolate import BarycentricInterpolator

    from mdpipe.simulate.synth import chebyshev_nodes_s, lagrange_basis

    nodes = chebyshev_nodes_s(k, 51.2e-6)
    times = np.arange(2048) / 40e6
    expected = BarycentricInterpolator(nodes, np.eye(k))(times).T
    np.testing.assert_allclose(lagrange_basis(nodes, times), expected, atol=1e-9)
    np.testing.assert_allclose(lagrange_basis(nodes, nodes), np.eye(k), atol=1e-12)  # exactly on the nodes


def test_fold_hz_into_the_span():
    np.testing.assert_allclose(doppler.fold_hz([0.0, 499.0, 500.0, 1250.0, -1250.0, -500.0], prf_hz=1000.0),
                               [0.0, 499.0, -500.0, 250.0, -250.0, -500.0])

