"""FMCW relations: range <-> beat frequency, range rate <-> Doppler, carrier phase.

Sign convention: ``range_rate_mps`` is positive when the range increases (receding target).
Doppler frequencies follow the paper (Eq. 2): a target at range rate v appears at
``f_D = -2 v / lambda``, so approaching targets have positive Doppler.
"""

import numpy as np

SPEED_OF_LIGHT_MPS = 299_792_458.0


def beat_frequency_hz(range_m, *, slope_hz_per_s):
    """Beat frequency ``f_b = 2 S R / c`` of a point at ``range_m``."""
    return 2.0 * slope_hz_per_s * np.asarray(range_m, dtype=np.float64) / SPEED_OF_LIGHT_MPS


def range_from_beat_frequency_m(beat_hz, *, slope_hz_per_s):
    """Inverse of :func:`beat_frequency_hz`."""
    return np.asarray(beat_hz, dtype=np.float64) * SPEED_OF_LIGHT_MPS / (2.0 * slope_hz_per_s)


def doppler_hz(range_rate_mps, *, wavelength_m):
    """Doppler frequency ``-2 v / lambda`` of a scatterer moving at ``range_rate_mps``."""
    return -2.0 * np.asarray(range_rate_mps, dtype=np.float64) / wavelength_m


def range_rate_from_doppler_mps(doppler_hz_, *, wavelength_m):
    """Inverse of :func:`doppler_hz`."""
    return -0.5 * np.asarray(doppler_hz_, dtype=np.float64) * wavelength_m


def two_way_phase_rad(range_m, *, frequency_hz):
    """Two-way carrier phase ``4 pi f R / c`` wrapped to (-pi, pi].

    The unwrapped phase is ~3e6 rad at 1 km and 76 GHz, where float32 steps are ~0.25 rad; the
    cycle count is formed in float64 and its integer part removed before scaling by 2 pi, so the
    result keeps float64 precision (~1e-10 rad per metre of range) and can be cast afterwards.
    """
    cycles = 2.0 * frequency_hz * np.asarray(range_m, dtype=np.float64) / SPEED_OF_LIGHT_MPS
    return 2.0 * np.pi * (cycles - np.round(cycles))
