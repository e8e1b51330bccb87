"""Is a scene physically plausible for its radar? Refusals (errors) and warnings, with the numbers.

Refused (:func:`check_scene`, called when a scene is built): a target whose range reaches beyond the
radar's maximum range (the beat frequency of ``fs / 2``), and micro-Doppler (blade tips, wings, leaves)
over ``MAX_SPAN_RATIO`` times the Doppler span ``1 / Tp``, which no processing could read. The sweep and
blade checks live with their blocks (:class:`mdpipe.simulate.scene.RadarConfig`,
:class:`mdpipe.simulate.targets.multirotor.Rotors`).

Warned (:func:`scene_warnings`): a target whose Doppler extent (body plus micro-Doppler) leaves the
unambiguous span ``+-1 / (2 Tp)``, so its micro-Doppler aliases.

Where the chirps take transmitters in turn, the span is that of one transmitter's chirps (what the processing reads:
Tp times the cycle).
"""

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.physics import kinematics
from mdpipe.physics.radar import doppler_hz
from mdpipe.simulate.targets import module_of, realize_all

MAX_SPAN_RATIO = 10.0
TRACK_SAMPLES = 2001


def _tracks(scene):
    """Per target: its module, realization, and the range and Doppler of its reference point on a coarse grid."""
    radar = scene.radar.params
    n = scene.radar.n_chirps
    t_s = np.linspace(0.0, (n - 1) * radar.chirp_period_s, min(n, TRACK_SAMPLES))
    for index, (target, realization) in enumerate(zip(scene.targets, realize_all(scene))):
        module = module_of(target)
        position, velocity = module.body_track(target, realization, t_s)
        body_doppler = doppler_hz(kinematics.range_rate_mps(position, velocity), wavelength_m=radar.wavelength_m)
        micro = module.micro_doppler_bound_hz(target, realization, wavelength_m=radar.wavelength_m)
        yield index, target, kinematics.range_m(position), body_doppler, micro


def check_scene(scene):
    """Raise :class:`ParameterError` naming the first implausible target, with its numbers and the fix."""
    radar = scene.radar.analysed[0]
    for index, target, ranges, _, micro_hz in _tracks(scene):
        where = f"targets[{index}] ({target.name})"
        if ranges.max() > radar.max_range_m:
            raise ParameterError(
                f"{where}: range reaches {ranges.max():.1f} m, beyond the radar's maximum range "
                f"{radar.max_range_m:.1f} m (beat frequency fs/2 = {radar.sample_rate_hz / 2e6:g} MHz); "
                "bring the target closer or raise radar.sample_rate_hz")
        if micro_hz > MAX_SPAN_RATIO * radar.doppler_span_hz:
            raise ParameterError(
                f"{where}: micro-Doppler reaches {micro_hz:.4g} Hz, {micro_hz / radar.doppler_span_hz:.0f}x the "
                f"Doppler span {radar.doppler_span_hz:.4g} Hz (at most {MAX_SPAN_RATIO:g}x); shorten "
                "radar.chirp_period_s or check the target's rates and sizes")


def scene_warnings(scene):
    """One sentence per target whose Doppler extent leaves the unambiguous span (its micro-Doppler aliases)."""
    radar = scene.radar.analysed[0]
    half_span = 0.5 * radar.doppler_span_hz
    warnings = []
    for index, target, _, body_doppler, micro_hz in _tracks(scene):
        low, high = body_doppler.min() - micro_hz, body_doppler.max() + micro_hz
        if radar.aliases(low, high):
            warnings.append(
                f"targets[{index}] ({target.name}): Doppler reaches {low:.4g} .. {high:.4g} Hz, beyond the "
                f"unambiguous +-{half_span:.4g} Hz (PRF {radar.prf_hz:.4g} Hz"
                f"{' of one transmitter' if scene.radar.transmit_cycle > 1 else ''}): its micro-Doppler aliases")
    return warnings
