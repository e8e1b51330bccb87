"""The evaluation's in-bin share: how much of a target's moving echo the range FFT leaves in its body's bin."""

import numpy as np
import pytest

from mdpipe.evaluate.range_share import body_bins, in_bin_share, range_dft
from mdpipe.evaluate.scoring import _without_body
from mdpipe.physics.radar import beat_frequency_hz
from mdpipe.process.ranging import range_response
from mdpipe.simulate.scene import scene_from_mapping
from mdpipe.simulate.targets import module_of, target_echo

CHIRPS = 4096
POINT_RADIUS_M = 0.15  # the one point of a blade from 0.1 to 0.2 m: the middle of its one piece
REV_PER_S = 100.0


def one_point_rotor(f_start_hz):
    """A body at rest at 20 m and one rotor of one blade reflecting at one point (Eq. 1 with Q = 1), face-on."""
    return {"name": "share", "seed": 1,
            "radar": {"f_start_hz": f_start_hz, "f_stop_hz": f_start_hz + 1e8, "ramp_up_s": 76.8e-6,
                      "chirp_period_s": 96e-6, "sample_rate_hz": 128 / 76.8e-6, "n_samples": 128,
                      "n_chirps": CHIRPS, "n_channels": 1},
            "noise": {"snr_db": 0.0},
            "targets": [{"type": "multirotor", "motion": {"position_m": [20.0, 0.0, 0.0]}, "elevation_deg": 0.0,
                         "body_rcs_m2": 0.01,
                         "rotors": {"count": 1, "blades": 1, "blade_length_m": 0.2, "root_m": 0.1,
                                    "blade_profile": "points", "points_per_blade": 1, "rev_per_s": REV_PER_S}}]}


@pytest.mark.parametrize("f_start_hz, offset_bins", [(94e9, 4.54), (9.8e9, 0.476)])
def test_a_turning_point_keeps_the_windows_mean_response_over_its_doppler_shifts(f_start_hz, offset_bins):
    """A point at radius rho turning at f_rot has Doppler f_p sin(theta), f_p = 4 pi rho f_rot / lambda, which
    moves its beat f_p sin(theta) N / fs bins off the body's: the share in the body's bin is the mean of the
    Hann window's squared range response over a turn (94 GHz: 4.5 bins at most, 0.107; 9.8 GHz: 0.48, 0.869)."""
    scene = scene_from_mapping(one_point_rotor(f_start_hz))
    radar = scene.radar.params
    target = scene.targets[0]
    reach_bins = 4 * np.pi * POINT_RADIUS_M * REV_PER_S / radar.wavelength_m * radar.sampled_duration_s
    assert reach_bins == pytest.approx(offset_bins, rel=2e-3)
    theta = np.linspace(0.0, 2 * np.pi, 4096, endpoint=False)
    expected = np.mean(range_response(reach_bins * np.sin(theta), window="hann", n_samples=128, zero_pad=1) ** 2)
    share = in_bin_share(_without_body(target), radar=radar, seed=1, index=0,
                         n_chirps=CHIRPS, chirps=CHIRPS)
    assert share == pytest.approx(expected, rel=0.02)


def test_a_moving_bodys_bin_is_its_range_moved_by_its_doppler_shift():
    """A point approaching at 15 m/s seen at 94 GHz in a 76.8 us ramp: its beat lies 2 v / lambda N / fs = -0.72
    bins from its range's (lower: nearer), where the range DFT of its simulated IF peaks."""
    mapping = one_point_rotor(94e9)
    mapping["targets"] = [{"type": "point", "motion": {"position_m": [20.0, 0.0, 0.0], "velocity_mps": [-15.0, 0, 0]},
                           "rcs_m2": 1.0}]
    scene = scene_from_mapping(mapping)
    radar = scene.radar.params
    target = scene.targets[0]
    realization = module_of(target).realize(target, seed=1, index=0, duration_s=radar.duration_s(CHIRPS))
    tau = radar.sample_times_s
    echo = target_echo(target, realization, np.arange(4)[:, None] * radar.chirp_period_s + tau, f0_hz=94e9)
    centre_m = echo.range_m.mean(axis=-1)
    if_real = np.real(echo.signal * np.exp(-2j * np.pi * beat_frequency_hz(
        centre_m, slope_hz_per_s=radar.slope_hz_per_s)[:, None] * tau))
    grid = np.arange(-3.0, 3.0, 1.0 / 256)
    power = np.abs([range_dft(np.broadcast_to(chirp, (len(grid), len(chirp))), centre / radar.range_bin_m + grid)
                    for chirp, centre in zip(if_real, centre_m)]) ** 2
    peaks = centre_m / radar.range_bin_m + grid[np.argmax(power, axis=1)]
    assert np.allclose(body_bins(echo.range_m, radar=radar, f0_hz=94e9), peaks, atol=2.0 / 256)
    assert np.allclose(peaks - centre_m / radar.range_bin_m, -0.723, atol=2.0 / 256)
