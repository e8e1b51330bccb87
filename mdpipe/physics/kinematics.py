"""Body motion seen from the radar.

Radar frame: the radar sits at the origin, x is boresight, y is the RX array axis (horizontal),
z is up. Positions are (..., 3) arrays in metres.
"""

import numpy as np


def body_position_m(t_s, *, start_m, velocity_mps, sway_amplitude_m=(0.0, 0.0, 0.0), sway_period_s=np.inf,
                    sway_phase_rad=0.0):
    """Straight-line motion plus an optional sinusoidal sway.

    ``p(t) = start + v t + a (cos(2 pi t / T + phi) - cos(phi))``, so ``p(0) = start``.

    Returns
    -------
    ndarray, shape (len(t_s), 3), m
    """
    t = np.asarray(t_s, dtype=np.float64)[..., None]
    sway = np.cos(2.0 * np.pi * t / sway_period_s + sway_phase_rad) - np.cos(sway_phase_rad)
    return np.asarray(start_m) + np.asarray(velocity_mps) * t + np.asarray(sway_amplitude_m) * sway


def body_velocity_mps(t_s, *, velocity_mps, sway_amplitude_m=(0.0, 0.0, 0.0), sway_period_s=np.inf,
                      sway_phase_rad=0.0, **_position):
    """Time derivative of :func:`body_position_m`, shape (len(t_s), 3), m/s."""
    t = np.asarray(t_s, dtype=np.float64)[..., None]
    rate = -2.0 * np.pi / sway_period_s * np.sin(2.0 * np.pi * t / sway_period_s + sway_phase_rad)
    return np.asarray(velocity_mps) + np.asarray(sway_amplitude_m) * rate


def range_m(position_m):
    """Distance from the radar of positions (..., 3)."""
    return np.linalg.norm(position_m, axis=-1)


def line_of_sight(position_m):
    """Unit vectors (..., 3) from the radar towards ``position_m``."""
    return position_m / range_m(position_m)[..., None]


def range_rate_mps(position_m, velocity_mps):
    """Rate of change of range, positive when receding."""
    return np.sum(line_of_sight(position_m) * velocity_mps, axis=-1)
