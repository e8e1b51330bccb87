"""A moving point scatterer (a body without micro-motion): a negative for the classifier."""

from dataclasses import dataclass, field

import numpy as np

from mdpipe.simulate.schema import POSITIVE
from mdpipe.simulate.targets.common import Motion, amplitude_bound_v, body_track, point_echo  # noqa: F401


@dataclass(frozen=True)
class Target:
    """A moving point scatterer."""

    motion: Motion
    name: str = "point"
    rcs_m2: float = field(default=1.0, metadata=POSITIVE)
    kind = "point"
    expected_class = "none"


def realize(target, *, seed, index, duration_s):
    return None


def echo(target, realization, t_s, *, f0_hz):
    return point_echo(target.motion.position(t_s), target.rcs_m2, f0_hz)


def micro_doppler_bound_hz(target, realization, *, wavelength_m):
    return 0.0


def peak_amplitude_v(target, realization, min_range_m):
    return amplitude_bound_v(np.sqrt(target.rcs_m2), 0.0, min_range_m)


def truth(target, realization, *, radar, n_chirps, body_doppler_hz):
    return {}
