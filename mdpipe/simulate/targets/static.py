"""A fixed point scatterer (a tree, a mast): clutter."""

from dataclasses import dataclass, field

import numpy as np

from mdpipe.simulate.schema import POSITIVE
from mdpipe.simulate.targets.common import Echo, point_signal
from mdpipe.simulate.targets.point import (  # noqa: F401 (one point scatterer: a point's draws, bounds, truth)
    micro_doppler_bound_hz, peak_amplitude_v, realize, truth)


@dataclass(frozen=True)
class Target:
    """A fixed point scatterer at ``range_m``, azimuth and elevation (degrees)."""

    range_m: float = field(metadata=POSITIVE)
    name: str = "static"
    azimuth_deg: float = 0.0
    elevation_deg: float = 0.0
    rcs_m2: float = field(default=1.0, metadata=POSITIVE)
    kind = "static"
    expected_class = "none"

    @property
    def position_m(self):
        az, el = np.deg2rad(self.azimuth_deg), np.deg2rad(self.elevation_deg)
        return self.range_m * np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])


def body_track(target, realization, t_s):
    shape = np.shape(t_s) + (3,)
    return np.broadcast_to(target.position_m, shape), np.zeros(shape)


def echo(target, realization, t_s, *, f0_hz):
    """A constant echo."""
    shape = np.shape(t_s)
    value = point_signal(target.range_m, target.rcs_m2, f0_hz)
    return Echo(np.full(shape, value, dtype=np.complex128), np.full(shape, target.range_m),
                np.broadcast_to(target.position_m / target.range_m, shape + (3,)))
