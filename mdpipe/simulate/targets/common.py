"""What every target kind shares: body motion, the echo record and the carrier phase.

A target kind is a module of this package providing

* ``Target``: the frozen dataclass read from the scene YAML (class attributes ``kind`` and
  ``expected_class``, the class a classifier should give: ``drone``, ``bird`` or ``none``);
* ``realize(target, *, seed, index, duration_s)``: the target's seeded random draws for one capture
  (or None);
* ``body_track(target, realization, t_s)``: position (..., 3) and velocity (..., 3) of its reference point;
* ``echo(target, realization, t_s, *, f0_hz)``: its :class:`Echo` at times ``t_s`` of any shape;
* ``micro_doppler_bound_hz(target, realization, *, wavelength_m)``: bound on |Doppler| of any of its
  scatterers relative to the reference point (the fidelity choice and the aliasing warning use it);
* ``peak_amplitude_v(target, realization, min_range_m)``: bound on |echo|;
* ``truth(target, realization, *, radar, n_chirps, body_doppler_hz)``: its kind's entries in ``/Truth``.

Echoes follow the paper's convention ``sum a exp(-j 4 pi R / lambda0)`` (lambda0 at the chirp start
frequency; the range FFT then puts the Doppler at the sweep centre, see :mod:`mdpipe.simulate.synth`).
Amplitudes follow the radar equation ``sqrt(rcs) / R^2`` in volts (1 V for 1 m^2 at 1 m).
"""

from dataclasses import dataclass, field

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.physics import kinematics
from mdpipe.physics.radar import doppler_hz, two_way_phase_rad
from mdpipe.simulate.schema import POSITIVE, Vec3


@dataclass(frozen=True)
class Echo:
    """Echo of one target: ``signal`` (complex, V), ``range_m`` and ``los`` (shape + (3,)) at the same times."""

    signal: np.ndarray
    range_m: np.ndarray
    los: np.ndarray


@dataclass(frozen=True)
class Motion:
    """Straight-line motion plus an optional sway ``a (cos(2 pi t / T + phase) - cos(phase))``."""

    position_m: Vec3
    velocity_mps: Vec3 = (0.0, 0.0, 0.0)
    sway_amplitude_m: Vec3 = (0.0, 0.0, 0.0)
    sway_period_s: float = field(default=float("inf"), metadata=POSITIVE)
    sway_phase_deg: float = 0.0

    def __post_init__(self):
        if np.linalg.norm(self.position_m) == 0:
            raise ParameterError("position_m must not be the radar's own position [0, 0, 0]")

    @property
    def kwargs(self):
        """Keyword arguments of :func:`mdpipe.physics.kinematics.body_position_m`."""
        return dict(start_m=np.array(self.position_m), velocity_mps=np.array(self.velocity_mps),
                    sway_amplitude_m=np.array(self.sway_amplitude_m), sway_period_s=self.sway_period_s,
                    sway_phase_rad=np.deg2rad(self.sway_phase_deg))

    def position(self, t_s):
        """Position (..., 3) at times ``t_s``."""
        return kinematics.body_position_m(t_s, **self.kwargs)

    def track(self, t_s):
        """Position (..., 3) and velocity (..., 3) at times ``t_s``."""
        return self.position(t_s), kinematics.body_velocity_mps(t_s, **self.kwargs)


def body_track(target, realization, t_s):
    """``body_track`` of the kinds that move by a :class:`Motion` (``target.motion``)."""
    return target.motion.track(t_s)


def carrier(range_m, f0_hz):
    """``exp(-j 4 pi f0 R / c)`` of scatterers at ``range_m``."""
    return np.exp(-1j * two_way_phase_rad(range_m, frequency_hz=f0_hz))


def point_signal(range_m, rcs_m2, f0_hz):
    """Echo signal (V) of a point scatterer of ``rcs_m2`` at ``range_m``: ``sqrt(rcs) / R^2 exp(-j 4 pi f0 R / c)``."""
    return np.sqrt(rcs_m2) / range_m**2 * carrier(range_m, f0_hz)


def point_echo(position_m, rcs_m2, f0_hz):
    """Echo of one point scatterer at positions (..., 3)."""
    ranges = kinematics.range_m(position_m)
    return Echo(point_signal(ranges, rcs_m2, f0_hz), ranges, kinematics.line_of_sight(position_m))


def max_speed_doppler_hz(position_m, velocity_mps, *, wavelength_m):
    """Largest |Doppler| of the reference point along a body track (T, 3)."""
    rates = kinematics.range_rate_mps(position_m, velocity_mps)
    return float(np.max(np.abs(doppler_hz(rates, wavelength_m=wavelength_m)), initial=0.0))


def amplitude_bound_v(total_sqrt_rcs, reach_m, min_range_m):
    """Bound on |echo| of scatterers of summed ``sqrt(rcs)`` within ``reach_m`` of a reference point that comes
    no closer than ``min_range_m`` (triangle inequality, each scatterer at its closest possible range)."""
    return float(total_sqrt_rcs / max(min_range_m - reach_m, 0.5 * min_range_m) ** 2)
