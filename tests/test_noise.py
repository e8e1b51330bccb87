"""The Box-Muller noise generator: standard normal, independent, reproducible."""

import numpy as np
import pytest
from scipy import stats

from mdpipe.simulate.noise import noise_streams, standard_normal_f32


@pytest.fixture(scope="module")
def draws():
    out = np.empty(2_000_001, dtype=np.float32)  # odd size: the unpaired last sample
    return standard_normal_f32(np.random.Generator(np.random.SFC64(3)), out).astype(np.float64)


def test_normal_distribution(draws):
    n = draws.size
    assert abs(draws.mean()) < 5 / np.sqrt(n)
    assert draws.var() == pytest.approx(1.0, abs=5 * np.sqrt(2 / n))
    assert stats.kurtosis(draws) == pytest.approx(0.0, abs=5 * np.sqrt(24 / n))
    assert stats.kstest(draws, "norm").pvalue > 1e-3
    beyond = np.count_nonzero(np.abs(draws) > 4.0)  # expected 2 n (1 - Phi(4)) = 127
    expected = 2 * n * stats.norm.sf(4.0)
    assert abs(beyond - expected) < 5 * np.sqrt(expected)


def test_independence(draws):
    """Neighbours, the two halves paired by one (r, t), and their squares are uncorrelated."""
    n, half = draws.size, (draws.size + 1) // 2
    tol = 5 / np.sqrt(half)
    assert abs(np.corrcoef(draws[:-1], draws[1:])[0, 1]) < tol
    pair = draws[: n - half], draws[half:]
    assert abs(np.corrcoef(*pair)[0, 1]) < tol
    assert abs(np.corrcoef(pair[0] ** 2, pair[1] ** 2)[0, 1]) < tol


def test_scale_and_streams_reproducible_and_distinct():
    a, b = noise_streams(9, 3), noise_streams(9, 2)
    x = standard_normal_f32(a[1], np.empty((64, 100), np.float32), scale=2.5)
    y = standard_normal_f32(b[1], np.empty((64, 100), np.float32), scale=2.5)
    z = standard_normal_f32(a[0], np.empty((64, 100), np.float32), scale=2.5)
    np.testing.assert_array_equal(x, y)  # channel 1 does not depend on how many channels there are
    assert not np.array_equal(x, z)
    assert np.std(x) == pytest.approx(2.5, rel=0.05)
