"""The occupied band counts single lines that stand out of the noise, not only the smoothed spectrum."""

import numpy as np

from mdpipe.process.doppler import PowerSpectrum
from mdpipe.process.spectral import LINE_DB, OCCUPIED_DB, occupied_band

RESOLUTION_HZ = 4.0
SPAN_HZ = 14000.0
SMOOTH_HZ = 70.0


def spectrum(power):
    f = (np.arange(len(power)) - len(power) // 2) * RESOLUTION_HZ
    return PowerSpectrum(power=power, f_hz=f)


def test_a_sparse_comb_18_db_out_sets_the_band():
    """Rotor lines 18 dB over the noise every 200 Hz to +-2 kHz: averaged over 70 Hz they stand only
    10 log10(63 / 17.5 + 1) = 6.6 dB out (< OCCUPIED_DB), one by one 18 dB (> LINE_DB)."""
    rng = np.random.default_rng(1)
    n = int(SPAN_HZ / RESOLUTION_HZ)
    power = rng.exponential(1.0, n)
    f = spectrum(power).f_hz
    lines = (np.abs(f) <= 2000) & (np.abs(f) % 200 == 0)
    power[lines] = 10 ** 1.8
    assert 10 * np.log10(10 ** 1.8 / (SMOOTH_HZ / RESOLUTION_HZ) + 1) < OCCUPIED_DB < 18 and LINE_DB < 18
    band = occupied_band(spectrum(power), 1.0, smooth_hz=SMOOTH_HZ)
    assert (band.low_hz, band.high_hz) == (-2000.0, 2000.0)
    assert not band.aliased and np.isnan(band.dense_low_hz)


def test_noise_alone_makes_no_line():
    """2^18 bins of noise: the largest is about ln(2^18) = 12.5 times the mean (11 dB), under LINE_DB."""
    power = np.random.default_rng(2).exponential(1.0, 1 << 18)
    band = occupied_band(spectrum(power), 1.0, smooth_hz=SMOOTH_HZ)
    assert np.isnan(band.low_hz) and band.reason == "no Doppler band above the noise"


def test_a_dense_band_keeps_its_dense_extent():
    """A continuous band 20 dB over the noise within +-500 Hz: both extents are that band."""
    rng = np.random.default_rng(3)
    power = rng.exponential(1.0, int(SPAN_HZ / RESOLUTION_HZ))
    f = spectrum(power).f_hz
    inside = np.abs(f) <= 500
    power[inside] = 100 * rng.exponential(1.0, inside.sum())
    band = occupied_band(spectrum(power), 1.0, smooth_hz=SMOOTH_HZ)
    assert abs(band.dense_low_hz + 500) <= SMOOTH_HZ and abs(band.dense_high_hz - 500) <= SMOOTH_HZ
    assert abs(band.low_hz + 500) <= SMOOTH_HZ and abs(band.high_hz - 500) <= SMOOTH_HZ
