"""The features the physics predicts for a scene: the known answer stored in ``/Truth``.

Doppler quantities use the sweep-centre wavelength (what the range FFT measures) and the paper's
sign (approaching = positive). ``aliased`` is true when the predicted Doppler extent does not fit
within the unambiguous span ``+-1/(2 Tp)``.
"""

import numpy as np

from mdpipe.physics import kinematics, rotor
from mdpipe.physics.radar import doppler_hz
from mdpipe.simulate.echoes import bird_points_m, body_track

TRACK_POINTS = 101


def _track(target, radar, n_chirps):
    t_s = np.arange(n_chirps) * radar.chirp_period_s
    position, velocity = body_track(target, t_s)
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


def _extent(low_hz, high_hz, radar):
    half_span = 0.5 * radar.doppler_span_hz
    return {"doppler_extent_hz": [float(low_hz), float(high_hz)],
            "aliased": bool(high_hz > half_span or low_hz < -half_span)}


def _multirotor(target, radar, body_doppler):
    rotors = target.rotors
    lam = radar.wavelength_m
    rates = np.abs(rotors.per_rotor("rev_per_s"))
    rate = float(rates.mean())
    tip = rotor.tip_doppler_hz(rates.max(), blade_length_m=rotors.blade_length_m, wavelength_m=lam,
                               elevation_deg=target.elevation_deg)
    bandwidth = rotor.doppler_bandwidth_hz(rates.max(), blade_length_m=rotors.blade_length_m, wavelength_m=lam,
                                           elevation_deg=target.elevation_deg)
    chopping = float(rotor.chopping_frequency_hz(rate, n_blades=rotors.blades))
    return {
        "n_blades": rotors.blades,
        "n_rotors": rotors.count,
        "blade_length_m": rotors.blade_length_m,
        "elevation_deg": target.elevation_deg,
        "rotor_rates_hz": rates.tolist(),
        "rotation_rate_hz": rate,
        "rotation_period_s": 1.0 / rate,
        "chopping_freq_hz": chopping,
        "chopping_aliased": bool(chopping > 0.5 * radar.doppler_span_hz),
        "flashes_per_revolution": rotor.flashes_per_revolution(rotors.blades),
        "flash_period_s": float(rotor.flash_period_s(rate, n_blades=rotors.blades)),
        "tip_doppler_hz": float(tip),
        "doppler_bw_hz": float(bandwidth),
        "doppler_bw_mps": float(bandwidth * lam / 2.0),
        **_extent(body_doppler.min() - tip, body_doppler.max() + tip, radar),
    }


def _bird(target, radar, n_chirps):
    duration_s = n_chirps * radar.chirp_period_s
    step_s = min(radar.chirp_period_s * max(1, n_chirps // 20000), 1.0 / (200.0 * target.wingbeat_hz))
    t_s = np.arange(0.0, duration_s, step_s)
    ranges = kinematics.range_m(bird_points_m(target, t_s))
    point_doppler = doppler_hz(np.gradient(ranges, t_s, axis=0), wavelength_m=radar.wavelength_m)
    spread = point_doppler.max(axis=1) - point_doppler.min(axis=1)
    return {
        "wingbeat_freq_hz": target.wingbeat_hz,
        "wingbeat_period_s": 1.0 / target.wingbeat_hz,
        "micro_doppler_spread_hz": float(spread.max()),
        "micro_doppler_spread_mps": float(spread.max() * radar.wavelength_m / 2.0),
        **_extent(point_doppler.min(), point_doppler.max(), radar),
    }


def expected_features(scene, plans):
    """Predicted features of every target of ``scene`` (a JSON-ready dict)."""
    radar, n_chirps = scene.radar.params, scene.radar.n_chirps
    targets = []
    for plan in plans:
        target = plan.target
        entry, body_doppler = _track(target, radar, n_chirps)
        entry = {"name": target.name, "kind": target.kind, **entry, "model": plan.model.as_dict()}
        if target.kind == "multirotor":
            entry.update(_multirotor(target, radar, body_doppler))
        elif target.kind == "bird":
            entry.update(_bird(target, radar, n_chirps))
        targets.append(entry)
    return {
        "radar": {"wavelength_m": radar.wavelength_m, "range_bin_m": radar.range_bin_m,
                  "doppler_span_hz": radar.doppler_span_hz, "n_chirps": n_chirps,
                  "duration_s": radar.duration_s(n_chirps)},
        "targets": targets,
    }
