"""Scene plausibility (refused or warned, with the numbers) and number validation, each message pinned."""

import copy

import pytest
import yaml
from click.testing import CliRunner

from conftest import XBAND
from mdpipe.cli import main
from mdpipe.errors import ParameterError
from mdpipe.simulate.plausibility import scene_warnings
from mdpipe.simulate.scene import load_scene_mapping, scene_from_mapping

# 24 GHz, 0.6 m bins, 128 samples: maximum range 64 bins = 38.4 m; PRF 40 kHz
K_BAND = dict(f_start_hz=24.0e9, f_stop_hz=24.25e9, ramp_up_s=20e-6, chirp_period_s=25e-6, sample_rate_hz=6.4e6,
              n_samples=128, n_chirps=256)
DRONE = {"type": "multirotor", "motion": {"position_m": [20.0, 0, 0]},
         "rotors": {"count": 4, "blade_length_m": 0.12, "rev_per_s": 100}}


def scene(radar=None, targets=None, **extra):
    return {"radar": copy.deepcopy(radar or K_BAND), "targets": copy.deepcopy([DRONE] if targets is None else targets),
            **extra}


def drone(**rotors):
    return DRONE | {"rotors": DRONE["rotors"] | rotors}


@pytest.mark.parametrize("data, message", [
    (scene(K_BAND | {"f_start_hz": 24.0, "f_stop_hz": 24.25e9}),
     r"^radar: f_start_hz=24.0 must be a finite number in \[1e\+08, 3e\+11\] Hz \(chirp start frequency: "
     r"100 MHz to 300 GHz\); did you mean 24e9\?$"),
    (scene(K_BAND | {"f_stop_hz": 30e9}),
     r"^radar: the sweep is 6 GHz wide, 22 % of its 27 GHz centre \(at most 20 %\); check f_start_hz and f_stop_hz$"),
    (scene(targets=[drone(blade_length_m=12)]),
     r"^targets\[0\]\.rotors: blade_length_m=12\.0 m is longer than any drone blade \(at most 2\.0 m\); "
     r"did you mean 0\.12 m\?$"),
    (scene(targets=[drone(blade_length_m=1.0, rev_per_s=100)]),
     r"^targets\[0\]\.rotors: blade tips would move at 2 pi x 100 rev/s x 1 m = 628 m/s, faster than sound"),
    (scene(targets=[DRONE | {"motion": {"position_m": [40.0, 0, 0]}}]),
     r"^targets\[0\] \(drone\): range reaches 40\.0 m, beyond the radar's maximum range 38\.4 m \(beat frequency "
     r"fs/2 = 3\.2 MHz\); bring the target closer or raise radar\.sample_rate_hz$"),
    (scene(K_BAND | {"chirp_period_s": 1e-3}),
     r"^targets\[0\] \(drone\): micro-Doppler reaches 1\.213e\+04 Hz, 12x the Doppler span 1000 Hz \(at most 10x\)"),
    (scene(seed=-1), r"^seed: must be >= 0, got -1$"),
    (scene(noise={"snr_db": 1e5}), r"^noise\.snr_db: must be within \[-100, 100\] dB, got 100000\.0$"),
    (scene(noise={"moving_snr_db": float("nan")}), r"^noise\.moving_snr_db: expected a finite number, got nan$"),
    (scene(noise={"moving_snr_db": 0.0, "snr_db": 3.0}), r"^noise: give one of snr_db, moving_snr_db, sigma_v, not "
                                                          r"snr_db and moving_snr_db$"),
    (scene(K_BAND | {"n_chirps": 10**400}), r"^radar\.n_chirps: expected a finite number, got 1000000000000"),
    (scene(targets=[drone(blade_gains=[1, 2, 3])]), r"^targets\[0\]\.rotors: blade_gains has 3 entries; give 1 or "
                                                    r"blades=2$"),
    (scene(targets=[drone(tilt_deg=[1, 2])]), r"^targets\[0\]\.rotors: tilt_deg has 2 entries; give 1 or count=4$"),
    (scene(targets=[drone(blade_profile="points")]), r"^targets\[0\]\.rotors: blade_profile points needs "
                                                     r"points_per_blade \(the Q of Eq\. 1\)$"),
    (scene(targets=[drone(blade_profile="tapered", points_per_blade=3)]),
     r"^targets\[0\]\.rotors: points_per_blade applies to blade_profile points, not tapered$"),
    (scene(targets=[drone(blade_profile="smooth")]),
     r"^targets\[0\]\.rotors\.blade_profile: must be one of uniform, tapered, points, got 'smooth'$"),
    (scene(targets=[drone(rate_wander_fraction=0.5)]),
     r"^targets\[0\]\.rotors\.rate_wander_fraction: must be within \[0, 0\.3\]"),
    (scene(targets=[DRONE | {"body_scatterers": [{"offset_m": [0, 0], "rcs_m2": 0.1}]}]),
     r"^targets\[0\]\.body_scatterers\[0\]\.offset_m: expected a list of 3 numbers"),
    (scene(targets=[{"type": "branch", "position_m": [10, 0, 0], "leaves": -1}]),
     r"^targets\[0\]\.leaves: must be from 0 to 1000, got -1$"),
    (scene(targets=[{"type": [1]}]), r"^targets\[0\]\.type: unknown target type \[1\] \(one of"),
    (scene(targets=[{"type": "bird", "motion": {"position_m": [20, 0, 0]}, "wingbeat_hz": 3, "upper_arm_m": 0.3,
                     "forearm_m": 0.3, "flap_glide": {"flap_s": 1.0}}]),
     r"^targets\[0\]\.flap_glide\.glide_s: missing \(required key\)$"),
    (scene(targets=[DRONE | {"name": "x" * 500}], noise="y" * 500),
     r"^noise: expected a mapping of keys to values, got 'yyyyyyyyyyyy[y]*\.\.\.$"),
])
def test_implausible_scenes_and_bad_numbers_are_refused(data, message):
    with pytest.raises(ParameterError, match=message):
        scene_from_mapping(data)


def test_aliasing_is_a_warning_with_its_numbers():
    """Tip Doppler 2 (2 pi 100) 0.12 / 0.0124 = 12.1 kHz: inside +-20 kHz at PRF 40 kHz, beyond +-5 kHz at 10 kHz."""
    assert scene_warnings(scene_from_mapping(scene())) == []
    warnings = scene_warnings(scene_from_mapping(scene(K_BAND | {"chirp_period_s": 100e-6})))
    assert warnings == ["targets[0] (drone): Doppler reaches -1.213e+04 .. 1.213e+04 Hz, beyond the unambiguous "
                        "+-5000 Hz (PRF 1e+04 Hz): its micro-Doppler aliases"]


def test_cli_prints_the_warning_and_simulates(tmp_path):
    config = tmp_path / "aliased.yaml"
    config.write_text(yaml.safe_dump(scene(K_BAND | {"chirp_period_s": 100e-6, "n_chirps": 16})))
    result = CliRunner().invoke(main, ["simulate", "--config", str(config), "-o", str(tmp_path / "a.h5")])
    assert result.exit_code == 0, result.output
    assert "warning: targets[0] (drone): Doppler reaches" in result.stderr and (tmp_path / "a.h5").exists()


def test_yaml_errors_keep_line_and_column_and_bad_files_give_one_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("radar:\n  f_start_hz: 76e9\n  f_stop_hz: [1, 2\n")
    with pytest.raises(ParameterError, match=r"bad\.yaml: not valid YAML at line 4, column 1 \(expected ',' or ']', "
                                             r"but got '<stream end>'\)$"):
        load_scene_mapping(bad)
    latin = tmp_path / "latin.yaml"
    latin.write_bytes("name: caf\xe9\n".encode("latin-1"))
    with pytest.raises(ParameterError, match=r"latin\.yaml: not UTF-8 text \(byte 0xe9 at offset 9\); save the scene "
                                             r"as UTF-8$"):
        load_scene_mapping(latin)
    deep = tmp_path / "deep.yaml"
    deep.write_text("[" * 100_000 + "]" * 100_000)
    with pytest.raises(ParameterError, match=r"deep\.yaml: nested too deeply to be a scene") as info:
        load_scene_mapping(deep)
    assert "\n" not in str(info.value)
    huge = tmp_path / "huge.yaml"
    huge.write_bytes(b"#" * 10_000_001)
    with pytest.raises(ParameterError, match=r"huge\.yaml: over 10 MB, too large to be a scene YAML$"):
        load_scene_mapping(huge)
    bom = tmp_path / "bom.yaml"
    bom.write_bytes("\ufeffname: café\n".encode("utf-8"))
    assert load_scene_mapping(bom) == {"name": "café"}
    tab = tmp_path / "tab.yaml"
    tab.write_text("radar:\n\tf_start_hz: 1\n")
    with pytest.raises(ParameterError, match=r"tab\.yaml: not valid YAML at line 2, column 1 \(found character "
                                             r"'\\t' that cannot start any token\)$"):
        load_scene_mapping(tab)


def test_cli_seed_and_snr_overrides_are_validated(tmp_path):
    config = tmp_path / "s.yaml"
    config.write_text(yaml.safe_dump(scene(XBAND | {"n_chirps": 8}, [])))
    for args, message in ([["--seed", "-1"], "Error: seed: must be >= 0, got -1"],
                          [["--snr-db", "1e5"], "Error: noise.snr_db: must be within [-100, 100] dB, got 100000.0"],
                          [["--snr-db", "inf"], "Error: noise.snr_db: expected a finite number, got inf"]):
        result = CliRunner().invoke(main, ["simulate", "--config", str(config), "-o", str(tmp_path / "x.h5"), *args])
        assert result.exit_code == 2 and message in result.output and "Traceback" not in result.output, result.output
