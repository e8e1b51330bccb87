"""Per-target choice of model fidelity, decided from the scene's physics and recorded in ``/Truth``.

Two effects can be left out when they are small:

* **In-chirp motion.** The echo changes during the ramp by ``c = f_max T_s`` cycles, where f_max
  bounds the target's Doppler (body plus blade tips or wing points) and ``T_s = N / fs`` is the
  sampled ramp; ``c`` is also the two-way travel within a ramp in wavelengths, and the shift of the
  echo in range bins (range-Doppler coupling). The echo is evaluated at K Chebyshev nodes across the
  ramp and interpolated; K = 1 freezes it at mid-ramp (stop-and-hop). For a signal whose spectrum
  lies within ``|f| <= f_max`` the interpolation error is at most ``2 (pi c / 2)^K / K!`` of its
  amplitude; K is the smallest that meets the tolerance.
* **Range migration.** With it, the beat frequency follows the body range chunk by chunk; without
  it, the echo keeps the beat frequency of the capture's mean range. Leaving it out costs about
  ``pi dR / range_bin`` of the amplitude, with dR the largest distance from the mean range.
"""

import math
from dataclasses import dataclass

import numpy as np

from mdpipe.physics import kinematics
from mdpipe.simulate.targets import module_of
from mdpipe.simulate.targets.common import max_speed_doppler_hz


@dataclass(frozen=True)
class TargetModel:
    """How one target is synthesised, and why."""

    nodes_per_chirp: int
    range_migration: bool
    in_chirp_cycles: float
    travel_bins: float
    interpolation_error_bound: float
    migration_error_bound: float

    def as_dict(self):
        return dict(self.__dict__)


def interpolation_error_bound(nodes, cycles):
    """Relative error bound ``2 (pi c / 2)^K / K!`` of K-node Chebyshev interpolation (c cycles per ramp)."""
    return 2.0 * (math.pi * cycles / 2.0) ** nodes / math.factorial(nodes)


def nodes_for_tolerance(cycles, tolerance, n_samples):
    """Smallest node count K >= 1 whose bound meets ``tolerance``; ``n_samples`` (exact) at most."""
    k = 1
    while k < n_samples and interpolation_error_bound(k, cycles) > tolerance:
        k += 1
    return k


def max_doppler_hz(target, realization, position_m, velocity_mps, *, wavelength_m):
    """Bound on |Doppler| of any scatterer of the target: its body track's (T, 3) plus its kind's micro-Doppler."""
    body = max_speed_doppler_hz(position_m, velocity_mps, wavelength_m=wavelength_m)
    return body + module_of(target).micro_doppler_bound_hz(target, realization, wavelength_m=wavelength_m)


def choose_model(target, realization, *, radar, position_m, velocity_mps, fidelity, chunk_chirps):
    """Decide the :class:`TargetModel` of ``target`` from its body track (T, 3) at the chirps, and the radar."""
    ranges = kinematics.range_m(position_m)
    travel_bins = float(np.max(np.abs(ranges - ranges.mean())) / radar.range_bin_m)
    migration_bound = math.pi * travel_bins
    if fidelity.range_migration == "auto":
        migration = migration_bound > fidelity.tolerance
    else:
        migration = fidelity.range_migration == "on"
    chunk_travel_bins = 0.0
    if migration:
        speed = float(np.max(np.linalg.norm(velocity_mps, axis=-1)))
        chunk_travel_bins = speed * chunk_chirps * radar.chirp_period_s / radar.range_bin_m
    cycles = max_doppler_hz(target, realization, position_m, velocity_mps, wavelength_m=radar.wavelength_m) \
        * radar.sampled_duration_s
    cycles += chunk_travel_bins
    if fidelity.in_chirp_motion == "off":
        nodes = 1
    elif fidelity.in_chirp_motion == "exact":
        nodes = radar.n_samples
    else:
        nodes = nodes_for_tolerance(cycles, fidelity.tolerance, radar.n_samples)
        if fidelity.in_chirp_motion == "on":
            nodes = max(nodes, min(2, radar.n_samples))
    bound = 0.0 if nodes == radar.n_samples else interpolation_error_bound(nodes, cycles)
    return TargetModel(nodes_per_chirp=nodes, range_migration=bool(migration), in_chirp_cycles=float(cycles),
                       travel_bins=travel_bins, interpolation_error_bound=float(bound),
                       migration_error_bound=0.0 if migration else migration_bound)
