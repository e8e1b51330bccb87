"""The features the physics predicts for a scene: the known answer stored in ``/Truth``.

Every target records its ``kind``, ``expected_class`` (``drone``, ``bird`` or ``none``), its range
track, the model chosen for it, its SNRs and its kind's own entries (see the modules of
:mod:`mdpipe.simulate.targets`). Doppler quantities use the sweep-centre wavelength (what the range
FFT measures) and the paper's sign (approaching = positive). ``aliased`` is true when the predicted
Doppler extent does not fit within the unambiguous span ``+-1/(2 Tp)``.

SNRs (per IF sample and channel, before any processing gain, dB; None without noise): ``snr_db`` of the
target's whole echo, ``moving_snr_db`` of the part MTI keeps (the echo minus its slow-time mean).
"""

import numpy as np

from mdpipe.physics import kinematics
from mdpipe.physics.radar import doppler_hz
from mdpipe.simulate.targets import module_of

TRACK_POINTS = 101


def _track(plan, radar, n_chirps):
    t_s = np.arange(n_chirps) * radar.chirp_period_s
    position, velocity = module_of(plan.target).body_track(plan.target, plan.realization, t_s)
    ranges = kinematics.range_m(position)
    rates = kinematics.range_rate_mps(position, velocity)
    body_doppler = doppler_hz(rates, wavelength_m=radar.wavelength_m)
    pick = np.unique(np.linspace(0, n_chirps - 1, min(TRACK_POINTS, n_chirps)).round().astype(int))
    return {
        "range_m": {"start": float(ranges[0]), "mean": float(ranges.mean()), "min": float(ranges.min()),
                    "max": float(ranges.max())},
        "range_bin": int(round(float(ranges.mean()) / radar.range_bin_m)),
        "range_rate_mps": {"mean": float(rates.mean()), "min": float(rates.min()), "max": float(rates.max())},
        "body_doppler_hz": {"mean": float(body_doppler.mean()), "min": float(body_doppler.min()),
                            "max": float(body_doppler.max())},
        "track": {"t_s": t_s[pick].tolist(), "range_m": ranges[pick].tolist(), "range_rate_mps": rates[pick].tolist()},
    }, body_doppler


def _snr_db(power_v2, sigma_v):
    if sigma_v == 0.0 or power_v2 == 0.0:
        return None
    return float(10.0 * np.log10(power_v2 / sigma_v**2))


def expected_features(scene, plans, *, powers_v2=None, sigma_v=0.0):
    """Predicted features of every target of ``scene`` (a JSON-ready dict).

    ``powers_v2`` lists each target's (whole, moving) IF power (V^2, per sample and channel) and
    ``sigma_v`` the noise standard deviation, for the per-target SNRs. Where the chirps take transmitters in turn,
    the prediction is for the first transmitter's chirps (Tp times the cycle), which the processing reads.
    """
    radar, n_chirps = scene.radar.analysed  # a cycle of transmitters: the first one's chirps, as processed
    targets = []
    for index, plan in enumerate(plans):
        target = plan.target
        entry, body_doppler = _track(plan, radar, n_chirps)
        entry = {"name": target.name, "kind": target.kind, "expected_class": target.expected_class, **entry,
                 "model": plan.model.as_dict()}
        if powers_v2 is not None:
            whole, moving = powers_v2[index]
            entry.update(snr_db=_snr_db(whole, sigma_v), moving_snr_db=_snr_db(moving, sigma_v))
        kind_entries = module_of(target).truth(target, plan.realization, radar=radar, n_chirps=n_chirps,
                                               body_doppler_hz=body_doppler)
        entry.update(kind_entries)
        if "doppler_extent_hz" in kind_entries:
            low, high = kind_entries["doppler_extent_hz"]
            entry["aliased"] = radar.aliases(low, high)
        targets.append(entry)
    return {
        "radar": {"wavelength_m": radar.wavelength_m, "range_bin_m": radar.range_bin_m,
                  "doppler_span_hz": radar.doppler_span_hz, "n_chirps": n_chirps,
                  "duration_s": radar.duration_s(n_chirps),
                  **({"tx_sequence": list(scene.radar.tx_sequence), "transmit_cycle": scene.radar.transmit_cycle}
                     if scene.radar.transmit_cycle > 1 else {})},
        "targets": targets,
    }
