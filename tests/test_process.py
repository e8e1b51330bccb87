"""Known answers: simulate, process, compare with the truth the simulator stored."""

import copy

import numpy as np
import pytest

from conftest import RADARLOG_SMALL, XBAND, scene_mapping, simulate
from mdpipe.io import open_capture
from mdpipe.params import ProcessParams
from mdpipe.process.pipeline import process_capture
from mdpipe.simulate.scene import load_scene_mapping

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]


def config(name, **radar):
    data = load_scene_mapping(ROOT / "configs" / name)
    data["radar"].update(radar)
    return data


def run(tmp_path, mapping, **params):
    path, truth = simulate(tmp_path, mapping)
    result = process_capture(path, ProcessParams(**params))
    return result, truth


@pytest.mark.parametrize("number", [1, 2, 3, 6, 7])
def test_table1_drones_rotation_and_blade_length(tmp_path, number):
    """Rotation rate within 0.5 %, blade length within 3 % (not aliased), bandwidths against Eq. 6."""
    data = config(f"paper/table1_config{number}.yaml", n_chirps=16000)  # >= one 0.25 s bandwidth segment
    beta = data["targets"][0]["elevation_deg"]
    result, truth = run(tmp_path, data, elevation_deg=beta)
    row, expected = result.rows[0], truth["targets"][0]
    assert row["class"] == "drone"
    assert row["range_bin"] == expected["range_bin"]
    assert row["rotation_rate_hz"] == pytest.approx(expected["rotation_rate_hz"], rel=0.005)
    assert row["chopping_freq_hz"] == pytest.approx(expected["chopping_freq_hz"], rel=0.005)
    assert row["rotation_period_s"] == pytest.approx(1 / expected["rotation_rate_hz"], rel=0.005)
    assert row["flash_period_s"] == pytest.approx(expected["flash_period_s"], rel=0.005)
    assert not row["aliased"]
    assert row["blade_length_m"] == pytest.approx(expected["blade_length_m"], rel=0.03)
    assert row["doppler_bw_spectrogram_hz"] == pytest.approx(expected["doppler_bw_hz"], rel=0.03)
    # the paper's 20 dB-above-mean rule on 0.25 s segments reads the band narrower than Eq. 6 (documented,
    # not used for r); the blade count is not given and 2 identical blades do not tell it: assumed, and said so
    assert 0.5 * expected["doppler_bw_hz"] < row["doppler_bw_hz"] < expected["doppler_bw_hz"]
    assert row["doppler_bw_hz_status"] == "ok" and row["chopping_freq_hz_status"] == "ok"
    assert row["n_blades"] == 2 and row["n_blades_source"] == "assumed"
    assert row["rotation_rate_hz_status"] == row["blade_length_m_status"] == "assumed_blades"


@pytest.mark.parametrize("number", [2, 3])
def test_table1_chopping_exact_over_the_paper_dwell(tmp_path, number):
    """Table I configs 2 and 3 as `make paper` runs them (31 250 chirps, 0.5 s): the chopping frequency within 0.01 %.
    The coarse search's 4 Hz bins put their combs 0.4-1 Hz off (config 3: 281.0 for 280.0 Hz); a comb taken at the
    edge of the third of a bin searched about it lies beyond that window (config 2 read 140.11, config 3 280.10 Hz
    once a first search a bin wide had changed what followed), and the bin either side holds it."""
    data = config(f"paper/table1_config{number}.yaml")
    result, truth = run(tmp_path, data, elevation_deg=data["targets"][0]["elevation_deg"])
    row, expected = result.rows[0], truth["targets"][0]
    assert row["chopping_freq_hz_status"] == "ok"
    assert row["chopping_freq_hz"] == pytest.approx(expected["chopping_freq_hz"], rel=1e-4)


def test_table1_config4_flash_edges_blur(tmp_path):
    """Table I config 4: four rotors at one rate (flashes 34-67 deg of a turn apart), beta = 60 deg, Gamma = 26.7.
    A quarter chopping period spans 3.3 Doppler bins of the tips a side, a quarter turn (the longest frame over which
    the tips' Doppler holds) 6.7, under the 8 the flash edges need (at 3-4 bins they read 4-6 % wide). The rate is
    exact; r is withheld and the tip Doppler given with that caveat (its edges, read wide, say 6.9 bins)."""
    data = config("paper/table1_config4.yaml", n_chirps=16000)
    result, truth = run(tmp_path, data, elevation_deg=60.0)
    row, expected = result.rows[0], truth["targets"][0]
    assert row["class"] == "drone"
    assert row["rotation_rate_hz"] == pytest.approx(expected["rotation_rate_hz"], rel=0.005)
    assert row["blade_length_m"] is None and row["blade_length_m_status"] == "few_harmonics"
    assert "Doppler bins a side (< 8)" in row["notes"]
    assert row["doppler_bw_spectrogram_hz_status"] == "few_harmonics"


def test_face_on_rotor_is_not_estimable(tmp_path):
    """Table I config 5, beta = 90 deg: cos(beta) = 0, the blades never modulate the echo (paper: no BW, no T_c)."""
    result, truth = run(tmp_path, config("paper/table1_config5.yaml", n_chirps=8000), elevation_deg=90.0)
    row = result.rows[0]
    assert truth["targets"][0]["doppler_bw_hz"] == pytest.approx(0.0, abs=1e-9)
    assert row["class"] == "none" and row["rotation_rate_hz"] is None and row["blade_length_m"] is None
    assert "no moving target" in row["notes"]


def test_fimi_76ghz_aliased_but_chopping_measured():
    """The bundled FIMI sample (76 GHz, 0.13 s): tips at +-26.8 kHz alias in +-7.8 kHz; 160 Hz does not."""
    path = ROOT / "data_samples" / "fimi_1rx.h5"
    result = process_capture(path, ProcessParams())
    with open_capture(path) as cap:
        expected = cap.truth["expected"]["targets"][0]
    row = result.rows[0]
    assert expected["aliased"] and row["aliased"]
    assert row["class"] == "drone" and row["range_bin"] == expected["range_bin"]
    assert row["chopping_freq_hz"] == pytest.approx(160.0, rel=0.005)
    assert row["rotation_rate_hz"] == pytest.approx(expected["rotation_rate_hz"], rel=0.005)
    assert row["blade_length_m"] is None and row["doppler_bw_hz"] is None
    assert "not estimable: aliased" in row["notes"]
    assert row["body_velocity_mps"] == pytest.approx(expected["range_rate_mps"]["mean"], abs=0.05)


@pytest.mark.parametrize("name", ["table2_c.yaml", "table2_d.yaml", "table2_f.yaml"])
def test_table2_birds_wingbeat(tmp_path, name):
    result, truth = run(tmp_path, config(f"paper/{name}"))
    row, expected = result.rows[0], truth["targets"][0]
    assert row["class"] == "bird"
    assert row["wingbeat_freq_hz"] == pytest.approx(expected["wingbeat_freq_hz"], rel=0.03)
    assert row["rotation_rate_hz"] is None
    assert row["micro_doppler_halfwidth_mps"] < 10


@pytest.mark.parametrize("name", ["table2_a.yaml", "table2_b.yaml", "table2_e.yaml"])
def test_table2_slow_strokes_are_birds_by_their_dark_turns(tmp_path, name):
    """The paper's Table II birds beating 0.5 Hz: their wings go dark at the stroke's turns (lit 83 % of the
    dwell) while the body line holds, read as a flapping share with the body line's rows (2 bins: the window's
    main lobe to its nulls) left out; with 1.5 bins left out, the body's leakage kept those rows lit and the
    three birds read none."""
    result, _ = run(tmp_path, config(f"paper/{name}"))
    row = result.rows[0]
    assert row["class"] == "bird" and row["flapping_share_status"] == "ok"
    assert 0.5 < row["flapping_share"] < 1.0


def test_bird_followed_across_range_bins(tmp_path):
    """A gull flying away at 4 m/s for 6 s: 15 m -> 39 m, across four 7.5 m bins, stitched phase-continuously."""
    bird = {"type": "bird", "motion": {"position_m": [15.0, 0.0, 3.0], "velocity_mps": [4.0, 0.0, 0.0]},
            "wingbeat_hz": 2.5, "upper_arm_m": 0.375, "forearm_m": 0.375, "wing_rcs_m2": 0.05, "body_rcs_m2": 0.05}
    radar = XBAND | {"chirp_period_s": 250e-6, "n_chirps": 24000}
    result, truth = run(tmp_path, scene_mapping(radar, [bird], noise={"snr_db": 10.0}))
    row = result.rows[0]
    assert row["range_max_m"] - row["range_min_m"] >= 15.0
    assert row["class"] == "bird"
    assert row["wingbeat_freq_hz"] == pytest.approx(2.5, rel=0.03)
    assert row["body_velocity_mps"] == pytest.approx(truth["targets"][0]["range_rate_mps"]["mean"], abs=0.1)


def test_gull_sample_wingbeat():
    result = process_capture(ROOT / "data_samples" / "gull_flyby.h5", ProcessParams())
    assert result.rows[0]["class"] == "bird"
    assert result.rows[0]["wingbeat_freq_hz"] == pytest.approx(3.0, rel=0.03)


def test_empty_scene_is_none():
    result = process_capture(ROOT / "data_samples" / "clutter_only.h5", ProcessParams())
    assert len(result.rows) == 1 and result.rows[0]["class"] == "none" and result.rows[0]["range_m"] is None


DRONE_X = {"type": "multirotor", "name": "quad", "motion": {"position_m": [40.0, 0.0, 0.0], "velocity_mps": [-2.0, 0, 0]},
           "body_rcs_m2": 0.01, "rotors": {"count": 4, "arm_m": 0.2, "blade_length_m": 0.12, "root_m": 0.01,
                                           "rev_per_s": [90, -90, 90, -90], "phase_deg": [0, 30, 65, 100],
                                           "blade_rcs_m2": 0.01}}


def test_right_bin_beside_a_30db_stronger_static_scatterer(tmp_path):
    """A static scatterer 30 dB above the whole drone echo, 4 bins nearer: MTI keeps the drone."""
    drone_power = 0.01 + 8 * 0.01  # body and blades' flash RCS, at 40 m
    tree_rcs = 1000 * drone_power * (20.0 / 40.0) ** 4  # +30 dB at the receiver from 20 m
    mapping = scene_mapping(XBAND | {"n_chirps": 8000}, [DRONE_X, {"type": "static", "range_m": 20.0, "rcs_m2": tree_rcs}],
                            noise={"snr_db": 0.0})
    result, truth = run(tmp_path, mapping)
    static_db = 10 * np.log10(result.stats.static_power.max() / result.stats.static_power[truth["targets"][0]["range_bin"]])
    assert static_db > 25  # the tree dominates the static profile ...
    row = result.rows[0]
    assert row["range_bin"] == truth["targets"][0]["range_bin"]  # ... but the drone is found
    assert row["class"] == "drone"
    assert row["body_velocity_mps"] == pytest.approx(-2.0, abs=0.05)
    assert row["rotation_rate_hz"] == pytest.approx(90.0, rel=0.005)


def test_two_drones_in_different_bins(tmp_path):
    far = copy.deepcopy(DRONE_X)
    far["motion"] = {"position_m": [70.0, 0.0, 0.0]}
    far["body_rcs_m2"] = 0.1
    far["rotors"].update(rev_per_s=[60, -60, 60, -60], blade_rcs_m2=0.1)
    result, truth = run(tmp_path, scene_mapping(XBAND | {"n_chirps": 8000}, [DRONE_X, far], noise={"snr_db": 10.0}))
    rows = sorted(result.rows, key=lambda r: r["range_m"])
    assert [r["class"] for r in rows] == ["drone", "drone"]
    assert [r["range_bin"] for r in rows] == [t["range_bin"] for t in truth["targets"]]
    assert rows[0]["rotation_rate_hz"] == pytest.approx(90.0, rel=0.005)
    assert rows[1]["rotation_rate_hz"] == pytest.approx(60.0, rel=0.005)


def test_snr_known_answer_and_channel_combining_gain(tmp_path):
    """Per-sample SNR -5 dB, 256 samples, Hann: the bin holds -5 + 10 log10(256) - 1.76 (window) - 3.01 (a real IF
    splits its power between +-f) = 14.31 dB; four RX combined coherently add 10 log10(4) = 6.02 dB."""
    az = np.deg2rad(15.0)
    target = {"type": "point", "motion": {"position_m": [float(30 * np.cos(az)), float(30 * np.sin(az)), 0.0],
                                          "velocity_mps": [1.0, 0.0, 0.0]}}
    radar = RADARLOG_SMALL | {"n_chirps": 512}
    one, _ = run(tmp_path, scene_mapping(radar, [target], noise={"snr_db": -5.0}))
    four, _ = run(tmp_path, scene_mapping(radar | {"n_channels": 4}, [target], noise={"snr_db": -5.0}), range_m=30.0)
    window = np.hanning(256)
    expected = -5.0 + 10 * np.log10(256) - 10 * np.log10(256 * np.sum(window ** 2) / np.sum(window) ** 2) - 10 * np.log10(2)
    assert one.rows[0]["snr_db"] == pytest.approx(expected, abs=0.5)
    assert four.rows[0]["snr_db"] - one.rows[0]["snr_db"] == pytest.approx(10 * np.log10(4), abs=0.5)
    assert four.rows[0]["rx_gain_db"] == pytest.approx(10 * np.log10(4), abs=0.5)
    assert abs(four.rows[0]["range_m"] - 30.0) < 3.75
    assert one.rows[0]["class"] == "none" and "neither blade flashes nor a wingbeat" in one.rows[0]["notes"]


def test_dwell_too_short_for_rotation_is_flagged(tmp_path):
    result, truth = run(tmp_path, config("paper/table1_config2.yaml", n_chirps=256))  # 4 ms < two flash periods
    row = result.rows[0]
    assert row["rotation_rate_hz"] is None
    assert "rotation not estimable: dwell" in row["notes"] or "no periodic blade flashes" in row["notes"]
