"""Scene YAML validation: every message names the key path and the problem."""

import copy

import pytest

from mdpipe.errors import ParameterError
from mdpipe.params import RadarParams
from mdpipe.simulate.scene import load_scene_mapping, scene_from_mapping

RADAR = dict(f_start_hz=76e9, f_stop_hz=76.04e9, ramp_up_s=51.2e-6, chirp_period_s=64e-6, sample_rate_hz=5e6,
             n_samples=256, n_chirps=64)
DRONE = {"type": "multirotor", "motion": {"position_m": [5.0, 0, 0]},
         "rotors": {"count": 4, "blade_length_m": 0.1, "rev_per_s": 80}}


def with_change(path, value):
    data = {"radar": copy.deepcopy(RADAR), "targets": [copy.deepcopy(DRONE)]}
    *parents, last = path
    node = data
    for key in parents:
        node = node[key]
    if value is KeyError:
        del node[last]
    else:
        node[last] = value
    return data


@pytest.mark.parametrize("path, value, message", [
    (("radar", "n_sample"), 3, r"^radar\.n_sample: unknown key \(known keys: f_start_hz, "),
    (("radar", "n_samples"), "many", r"^radar\.n_samples: expected an integer, got 'many'$"),
    (("radar", "n_samples"), 2.5, r"^radar\.n_samples: expected an integer, got 2\.5$"),
    (("radar", "n_chirps"), 0, r"^radar\.n_chirps: must be >= 1, got 0$"),
    (("radar", "n_channels"), 17, r"^radar\.n_channels: must be between 1 and 16, got 17$"),
    (("radar", "f_start_hz"), True, r"^radar\.f_start_hz: expected a number, got True$"),
    (("radar", "f_stop_hz"), 75e9, r"^radar: f_stop_hz=75000000000\.0 must exceed f_start_hz=76000000000\.0"),
    (("radar", "chirp_period_s"), 20e-6, r"^radar: ramp_up_s=5\.12e-05 exceeds chirp_period_s=2e-05$"),
    (("radar", "rx_positions_m"), [0.0, "x"], r"^radar\.rx_positions_m\[1\]: expected a number, got 'x'$"),
    (("radar", "ramp_up_s"), KeyError, r"^radar\.ramp_up_s: missing \(required key\)$"),
    (("targets", 0, "rotors", "blade_length_m"), -0.1, r"^targets\[0\]\.rotors\.blade_length_m: must be > 0, got -0\.1$"),
    (("targets", 0, "rotors", "rev_per_s"), [80, 0, 80, 80], r"^targets\[0\]\.rotors\.rev_per_s: must be non-zero"),
    (("targets", 0, "rotors", "rev_per_s"), [80, 80], r"^targets\[0\]\.rotors: rev_per_s has 2 entries; give 1 or count=4$"),
    (("targets", 0, "rotors", "root_m"), 0.2, r"^targets\[0\]\.rotors: root_m=0\.2 must be shorter than blade_length_m=0\.1$"),
    (("targets", 0, "motion", "position_m"), [1, 2], r"^targets\[0\]\.motion\.position_m: expected a list of 3 numbers"),
    (("targets", 0, "motion", "position_m"), [0, 0, 0], r"^targets\[0\]\.motion: position_m must not be the radar's own"),
    (("targets", 0, "elevation_deg"), 95, r"^targets\[0\]\.elevation_deg: must be within \[-90, 90\], got 95\.0$"),
    (("targets", 0, "type"), "plane", r"^targets\[0\]\.type: unknown target type 'plane' \(one of multirotor, bird, point, static, branch\)$"),
    (("targets", 0, "type"), KeyError, r"^targets\[0\]\.type: missing \(one of multirotor, bird, point, static, branch\)$"),
    (("targets", 0, "motion"), "here", r"^targets\[0\]\.motion: expected a mapping of keys to values, got 'here'$"),
    (("targets",), {"a": 1}, r"^targets: expected a list of targets"),
])
def test_scene_errors_name_the_key(path, value, message):
    with pytest.raises(ParameterError, match=message):
        scene_from_mapping(with_change(path, value))


def test_missing_radar_and_not_a_mapping():
    with pytest.raises(ParameterError, match=r"^radar: missing \(every scene needs a radar block; see configs/radarlog\.yaml\)$"):
        scene_from_mapping({"targets": []})
    with pytest.raises(ParameterError, match=r"^scene: expected a mapping at the top of the file, got list$"):
        scene_from_mapping([1, 2])


def test_noise_and_fidelity_errors():
    base = {"radar": RADAR}
    with pytest.raises(ParameterError, match=r"^noise: give snr_db or sigma_v, not both$"):
        scene_from_mapping(base | {"noise": {"snr_db": 3, "sigma_v": 1e-3}})
    with pytest.raises(ParameterError, match=r"^fidelity\.in_chirp_motion: must be one of auto, on, off, exact, got 'maybe'$"):
        scene_from_mapping(base | {"fidelity": {"in_chirp_motion": "maybe"}})
    with pytest.raises(ParameterError, match=r"^noise\.sigma_v: must be >= 0, got -1\.0$"):
        scene_from_mapping(base | {"noise": {"sigma_v": -1}})


def test_bird_defaults_a2_to_a1_and_heading_from_velocity():
    bird = {"type": "bird", "motion": {"position_m": [15, -10, 10], "velocity_mps": [0, 2, 0]}, "wingbeat_hz": 1,
            "upper_arm_m": 0.6, "forearm_m": 0.6, "a1_deg": 33}
    scene = scene_from_mapping({"radar": RADAR, "targets": [bird]})
    assert scene.targets[0].flap_kwargs["a2_deg"] == 33
    assert scene.targets[0].heading_rad == pytest.approx(1.5707963267948966)


def test_yaml_reads_exponent_floats_and_reports_bad_files(tmp_path):
    good = tmp_path / "s.yaml"
    good.write_text("radar: {f_start_hz: 76e9, f_stop_hz: 76.04e9, ramp_up_s: 51.2e-6, chirp_period_s: 64e-6,\n"
                    "        sample_rate_hz: 5e6, n_samples: 256, n_chirps: 4}\n")
    assert load_scene_mapping(good)["radar"]["f_start_hz"] == 76e9
    bad = tmp_path / "bad.yaml"
    bad.write_text("radar: [1, 2\n")
    with pytest.raises(ParameterError, match=r"bad\.yaml: not valid YAML"):
        load_scene_mapping(bad)
    with pytest.raises(ParameterError, match=r"absent\.yaml: cannot read \(No such file or directory\)"):
        load_scene_mapping(tmp_path / "absent.yaml")


def test_radar_params_derived_quantities():
    p = RadarParams(f_start_hz=76e9, f_stop_hz=76.04e9, ramp_up_s=51.2e-6, chirp_period_s=64e-6,
                    sample_rate_hz=40e6, n_samples=2048)
    assert p.slope_hz_per_s == pytest.approx(40e6 / 51.2e-6)
    assert p.range_bin_m == pytest.approx(3.7474, abs=1e-4)  # c / (2 B) with N / fs = TRampUp
    assert p.doppler_span_hz == pytest.approx(15625.0)
    assert p.wavelength_m == pytest.approx(299792458 / 76.02e9)
    assert p.velocity_span_mps == pytest.approx(15625.0 * p.wavelength_m / 2)
    assert p.max_range_m == pytest.approx(p.range_bin_m * 1024)
    with pytest.raises(ParameterError, match=r"^n_samples=2 must be a finite number in \[8, 65536\] \(samples per chirp"):
        RadarParams(f_start_hz=76e9, f_stop_hz=76.04e9, ramp_up_s=51.2e-6, chirp_period_s=64e-6,
                    sample_rate_hz=40e6, n_samples=2)
    with pytest.raises(ParameterError, match=r"^rx_positions_m has 2 entries for n_channels=1$"):
        RadarParams(f_start_hz=76e9, f_stop_hz=76.04e9, ramp_up_s=51.2e-6, chirp_period_s=64e-6,
                    sample_rate_hz=40e6, n_samples=8, rx_positions_m=(0.0, 1.0))
