"""mdpipe evaluate: scoring rules on hand-built rows, estimability, sweep drawing, the command."""

import json
from pathlib import Path

import h5py
import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from conftest import XBAND, scene_mapping, simulate, slow_time
from mdpipe.cli import main
from mdpipe.errors import MdpipeError, ParameterError
from mdpipe.evaluate import run, scoring, summary, sweep
from mdpipe.simulate.scene import scene_from_mapping, scene_to_yaml

ROOT = Path(__file__).resolve().parents[1]
SWEEPS = ROOT / "configs" / "sweeps"
# A 4-rotor, 2-blade drone at 80 rev/s, r = 0.12 m, seen at beta = 10 deg by X band at PRF 40 kHz for 0.1 s.
DRONE = scoring.Physics(kind="multirotor", expected_class="drone", dwell_s=0.1, prf_hz=40000.0,
                        micro_line_snr_db=30.0, body_line_snr_db=40.0, rotor_rates_hz=(80.0,) * 4, n_blades=2,
                        blade_length_m=0.12, elevation_deg=10.0, blades_given=True, elevation_given=True,
                        tip_doppler_hz=4.0 * np.pi * 80 * 0.12 * np.cos(np.deg2rad(10)) / 0.0306,
                        has_body=True, body_velocity_mps=2.0, body_doppler_max_hz=2 * 2.0 / 0.0306)


def test_a_value_12_percent_off_is_confidently_wrong_and_8_percent_is_right():
    wrong = scoring.score_value("rotation_rate_hz", truth=100.0, estimable=True, value=112.0, status=None)
    right = scoring.score_value("rotation_rate_hz", truth=100.0, estimable=True, value=92.0, status="ok")
    assert wrong == {"confident": True, "error": pytest.approx(0.12), "verdict": "wrong"}
    assert right == {"confident": True, "error": pytest.approx(0.08), "verdict": "right"}


def test_a_value_under_a_caveat_is_not_confident():
    scored = scoring.score_value("rotation_rate_hz", truth=100.0, estimable=True, value=150.0, status="assumed_blades")
    assert scored["verdict"] == "withheld" and not scored["confident"] and np.isnan(scored["error"])


def test_a_confident_value_where_the_truth_is_not_estimable_is_confidently_wrong():
    # right by luck (N = 2 guessed for a 2-blade rotor whose blade count the echo does not tell): still a guess
    scored = scoring.score_value("rotation_rate_hz", truth=80.0, estimable=False, value=80.0, status=None)
    assert scored["verdict"] == "unwarranted" and scored["verdict"] in scoring.CONFIDENTLY_WRONG
    assert scoring.score_value("wingbeat_freq_hz", truth=float("nan"), estimable=False, value=None,
                               status=None)["verdict"] == "n/a"
    assert scoring.score_value("wingbeat_freq_hz", truth=3.0, estimable=True, value=None,
                               status=None)["verdict"] == "missed"


def test_body_velocity_needs_a_detectable_unaliased_body_line():
    import dataclasses

    assert scoring.body_velocity_estimable(DRONE) == (True, "")
    # 2 m/s at X band is 131 Hz; 25 kHz is beyond +-20 kHz: the velocity is known only modulo lambda PRF / 2
    assert scoring.body_velocity_estimable(dataclasses.replace(DRONE, body_doppler_max_hz=25000.0)) \
        == (False, "aliased")
    assert scoring.body_velocity_estimable(dataclasses.replace(DRONE, body_line_snr_db=10.0)) == (False, "below_noise")
    assert scoring.body_velocity_estimable(dataclasses.replace(DRONE, has_body=False)) == (False, "no_body")
    # hovering without sway: the body is one more static scatterer of its bin, removed with the clutter; a sway
    # whose echo the mean removal keeps 1 % of (-20 dB) leaves its line 20 dB above the noise
    still = dataclasses.replace(DRONE, body_velocity_mps=0.0, body_doppler_max_hz=0.0, body_kept_share=0.0)
    assert scoring.body_velocity_estimable(still) == (False, "static")
    assert scoring.body_velocity_estimable(dataclasses.replace(still, body_kept_share=0.01)) == (True, "")


def test_body_velocity_error_is_relative_to_at_least_1_mps():
    assert scoring.relative_error("body_velocity_mps", 0.0, 0.05) == pytest.approx(0.05)
    assert scoring.relative_error("body_velocity_mps", -4.0, -3.0) == pytest.approx(0.25)


def test_rotation_needs_a_knowable_blade_count():
    import dataclasses

    assert scoring.rotation_estimable(DRONE) == (True, "")
    unknown = dataclasses.replace(DRONE, blades_given=False)
    assert scoring.rotation_estimable(unknown) == (False, "blades_unknown")
    # an odd N's flashes tell that N is odd and the chopping frequency N f_rot, not N: 3 and 5 blades alike
    assert scoring.rotation_estimable(dataclasses.replace(unknown, n_blades=3)) == (False, "blades_unknown")
    # one blade 2x: its lines stand 12 dB (3 blades) or 9.5 dB (2) under the chopping lines, 30 dB out here
    odd_tagged = dataclasses.replace(unknown, n_blades=3, imbalance_line_db=scoring.imbalance_line_db([1.0, 1.0, 2.0]))
    assert scoring.rotation_estimable(odd_tagged) == (True, "")
    assert scoring.rotation_estimable(dataclasses.replace(unknown, imbalance_line_db=scoring.imbalance_line_db(
        [1.0, 2.0]))) == (True, "")
    # the lines a blade 1.3x brighter adds stand 17.7 dB under the chopping lines; they must be detectable too
    tagged = dataclasses.replace(unknown, imbalance_line_db=scoring.imbalance_line_db([1.0, 1.3]))
    assert scoring.rotation_estimable(dataclasses.replace(tagged, micro_line_snr_db=31.0)) == (True, "")
    assert scoring.rotation_estimable(dataclasses.replace(tagged, micro_line_snr_db=30.0)) == (False, "blades_unknown")
    # 3 turns at 80 rev/s take 37.5 ms
    assert scoring.rotation_estimable(dataclasses.replace(DRONE, dwell_s=0.03)) == (False, "dwell_short")
    assert scoring.rotation_estimable(dataclasses.replace(DRONE, micro_line_snr_db=12.0)) == (False, "below_noise")
    # near face-on the tips' band shrinks with cos(beta): at 87 deg it holds 1.3 chopping harmonics a side at X band
    # (no comb to read), at 94 GHz 12 of them
    face_on = dataclasses.replace(DRONE, elevation_deg=87.0,
                                  tip_doppler_hz=4.0 * np.pi * 80 * 0.12 * np.cos(np.deg2rad(87)) / 0.0306)
    assert scoring.rotation_estimable(face_on) == (False, "few_lines")
    assert scoring.rotation_estimable(dataclasses.replace(face_on, tip_doppler_hz=face_on.tip_doppler_hz * 0.0306
                                                          / 0.00319)) == (True, "")


def test_imbalance_lines_of_unequal_blades():
    """Two blades 1 and g: (g - 1) / (g + 1) in amplitude; three blades 1, 1, g: |g - 1| / (g + 2)."""
    assert scoring.imbalance_line_db([1.0, 1.3]) == pytest.approx(20 * np.log10(0.3 / 2.3))
    assert scoring.imbalance_line_db([1.0, 1.0, 2.0]) == pytest.approx(20 * np.log10(1.0 / 4.0))
    assert scoring.imbalance_line_db([1.0, 1.0]) == float("-inf")


def test_blade_length_rules():
    import dataclasses

    assert scoring.blade_length_estimable(DRONE) == (True, "")  # tip 3.1 kHz < 20 kHz, 78 harmonics
    aliased = dataclasses.replace(DRONE, prf_hz=6000.0)  # tip 3.1 kHz > 3 kHz; chopping 160 Hz still sampled
    assert scoring.rotation_estimable(aliased) == (True, "")
    assert scoring.blade_length_estimable(aliased) == (False, "aliased")
    # beta not given: Eq. 6 gives r cos(beta), so r is an assumption even at beta = 10 deg (cos 0.985)
    assert scoring.blade_length_estimable(dataclasses.replace(DRONE, elevation_given=False)) \
        == (False, "elevation_unknown")
    assert scoring.blade_length_estimable(dataclasses.replace(DRONE, tip_doppler_hz=900.0)) == (False, "few_harmonics")
    # each disc at the drone's beta plus its tilt; given beta only, r is known to |cos(beta + tau) / cos(beta) - 1|
    tilted = dataclasses.replace(DRONE, rotor_elevations_deg=(14.0, 6.0, 13.0, 7.0))  # tau <= 4 deg at 10 deg: 1.3 %
    assert scoring.blade_length_estimable(tilted) == (True, "")
    steep = dataclasses.replace(tilted, elevation_deg=40.0, rotor_elevations_deg=(44.0, 36.0, 43.0, 37.0))  # 6.1 %
    assert scoring.blade_length_estimable(steep) == (False, "tilt")


def test_body_velocity_rules():
    import dataclasses

    point = scoring.Physics(kind="point", expected_class="none", dwell_s=2.0, prf_hz=6400.0, body_line_snr_db=30.0,
                            has_body=True, body_velocity_mps=7.0, body_doppler_max_hz=3600.0,
                            velocity_span_mps=12.5, range_bin_m=1.5)
    # aliased (3.6 kHz > 3.2 kHz), but one 1.5 m bin over 2 s (0.75 m/s) is below a quarter span (3.1 m/s)
    assert scoring.body_velocity_estimable(point) == (True, "")
    assert scoring.body_velocity_estimable(dataclasses.replace(point, dwell_s=0.25)) == (False, "aliased")
    assert scoring.body_velocity_estimable(dataclasses.replace(point, body_doppler_max_hz=3000.0, dwell_s=0.25)) \
        == (True, "")


def test_score_row_and_coverage_arithmetic():
    bird = scoring.Physics(kind="bird", expected_class="bird", dwell_s=2.0, prf_hz=4000.0, micro_line_snr_db=20.0,
                           body_line_snr_db=30.0, wingbeat_hz=3.0, flap_run_s=2.0, has_body=True,
                           body_velocity_mps=-5.0, body_doppler_max_hz=2 * 5.0 / 0.0306)
    rows = [  # 3 drones, rotation estimable in all: 1 right, 1 wrong, 1 withheld; 1 bird called a drone
        (DRONE, {"class": "drone", "rotation_rate_hz": 80.4, "body_velocity_mps": 2.05}),
        (DRONE, {"class": "drone", "rotation_rate_hz": 120.0, "body_velocity_mps": None}),
        (DRONE, {"class": "drone", "rotation_rate_hz": 40.0, "rotation_rate_hz_status": "assumed_blades"}),
        (bird, {"class": "drone", "rotation_rate_hz": 12.0, "wingbeat_freq_hz": 3.05, "body_velocity_mps": -5.2}),
    ]
    records = [{"scene": f"s{i}", "family": p.kind, "band": "X", "target": "subject", **scoring.score_row(p, row)}
               for i, (p, row) in enumerate(rows)]
    frame = pd.DataFrame(records)
    table = summary.feature_table(frame).set_index("feature")
    rotation = table.loc["rotation_rate_hz"]
    assert (rotation["estimable"], rotation["confident"], rotation["right"], rotation["wrong"],
            rotation["withheld"], rotation["unwarranted"]) == (3, 2, 1, 1, 1, 1)
    assert rotation["coverage_%"] == pytest.approx(200 / 3)
    assert rotation["err_median_%"] == pytest.approx((0.5 + 50.0) / 2)
    velocity = table.loc["body_velocity_mps"]
    assert (velocity["estimable"], velocity["confident"], velocity["missed"]) == (4, 2, 2)
    assert velocity["coverage_%"] == pytest.approx(50.0)
    assert velocity["err_max_%"] == pytest.approx(4.0)  # 0.2 m/s of 5 m/s
    assert summary.confusion(frame).loc["bird", "drone"] == 1 and int(frame["class_ok"].sum()) == 3
    wrong = summary.confidently_wrong(frame)
    assert sorted(zip(wrong["scene"], wrong["feature"], wrong["verdict"])) == [
        ("s1", "rotation_rate_hz", "wrong"), ("s3", "rotation_rate_hz", "unwarranted")]


def test_rotation_coverage_splits_by_band_and_blade_profile():
    cases = [("X", "points", True, "right"), ("X", "points", True, "missed"), ("X", "uniform", True, "wrong"),
             ("K", "points", True, "withheld"), ("K", "uniform", False, "n/a"), ("K", None, False, "n/a"),
             ("W94", None, True, "right")]
    wavelengths = {"X": 0.03, "K": 0.0125, "W94": 0.0032}
    frame = pd.DataFrame([{"band": band, "wavelength_m": wavelengths[band], "blade_profile": profile,
                           "rotation_rate_hz_estimable": estimable, "rotation_rate_hz_verdict": verdict}
                          for band, profile, estimable, verdict in cases])
    grid = summary.coverage_grid(frame, "rotation_rate_hz", rows="band", columns="blade_profile",
                                 order="wavelength_m").set_index("band")
    assert list(grid.columns) == ["-", "points", "uniform", "all"]
    assert list(grid.index) == ["X", "K", "W94", "all"]  # by wavelength, longest first
    assert grid.loc["X"].tolist() == ["", "1 / 2", "1 / 1", "2 / 3"]  # a wrong value is confident, as in the coverage
    assert grid.loc["K"].tolist() == ["", "0 / 1", "", "0 / 1"]  # withheld: not confident; K uniform: none estimable
    assert grid.loc["W94"].tolist() == ["1 / 1", "", "", "1 / 1"]  # a missing profile has its column: rows add up
    assert grid.loc["all"].tolist() == ["1 / 1", "1 / 3", "1 / 1", "3 / 5"]
    # flags read back from a CSV are strings; NaN is no flag
    frame["rotation_rate_hz_estimable"] = ["True", "True", "True", "True", "False", np.nan, "False"]
    grid = summary.coverage_grid(frame, "rotation_rate_hz", rows="band", columns="blade_profile").set_index("band")
    assert grid.loc["all", "all"] == "2 / 4"
    frame["rotation_rate_hz_estimable"] = False
    assert summary.coverage_grid(frame, "rotation_rate_hz", rows="band", columns="blade_profile") is None


def test_wrong_classes_are_those_a_measurement_could_tell():
    cases = [("s0", "bird", "drone", True, 20.0), ("s1", "drone", "none", False, 8.0),  # under the lines: not listed
             ("s2", "drone", "none", True, 16.0), ("s3", "none", "bird", False, -np.inf),
             ("s4", "drone", "error", True, 30.0), ("s5", "bird", "bird", True, 25.0),
             ("s6", "drone", "none", True, 14.0)]
    frame = pd.DataFrame([{"scene": scene, "family": expected, "band": "X", "target": "subject",
                           "expected_class": expected, "measured_class": measured, "class_ok": expected == measured,
                           "detectable": detectable, "micro_line_snr_db": snr,
                           "chopping_freq_hz_status": "no_flashes", "wingbeat_freq_hz_status": "no_wingbeat"}
                          for scene, expected, measured, detectable, snr in cases])
    frame.loc[frame["scene"] == "s6", "chopping_freq_hz_status"] = None  # no row matched to it
    misread = summary.wrong_classes(frame)
    # drones first, then birds, then the rest; a failed capture is listed with the failed captures instead; each with
    # the status of what tells its expected class
    assert misread[["scene", "expected_class", "measured_class", "evidence_status"]].values.tolist() == [
        ["s2", "drone", "none", "no_flashes"], ["s6", "drone", "none", "not_detected"],
        ["s0", "bird", "drone", "no_wingbeat"], ["s3", "none", "bird", ""]]


def test_line_snr_of_a_point_matches_the_measured_doppler_line(tmp_path):
    """A point receding by 3 Doppler bins (0.459 m/s: off 0 Hz, where the mean removal would take its line; on a
    bin, not between two) at snr_db = 0: after a Hann range FFT (gain N/3 on a real IF) and an n_chirps DFT its
    Doppler line stands 10 log10(64 / 3 x 4000) = 49.3 dB above the mean noise bin."""
    speed_mps = 3 * (299792458.0 / 9.8e9) / (2 * 4000 * 25e-6)
    mapping = scene_mapping(XBAND, [{"type": "point", "rcs_m2": 1.0, "motion": {"position_m": [30.0, 0.0, 0.0],
                                                                               "velocity_mps": [speed_mps, 0.0, 0.0]}}],
                            noise={"snr_db": 0.0}, seed=4)
    path, truth = simulate(tmp_path, mapping)
    scene = scene_from_mapping(mapping)
    physics = scoring.physics_of(0, truth["targets"][0], scene=scene,
                                 noise_sigma_v=truth["simulation"]["noise_sigma_v"], process={})
    assert physics.body_line_snr_db == pytest.approx(10 * np.log10(64 / 3 * 4000), abs=0.05)
    signal, _params = slow_time(path, truth["targets"][0]["range_bin"])
    power = np.abs(np.fft.fft(signal)) ** 2
    noise = np.median(np.delete(power, power.argmax())) / np.log(2)  # exponential noise: mean = median / ln 2
    assert 10 * np.log10(power.max() / noise) == pytest.approx(physics.body_line_snr_db, abs=1.0)


def test_sweep_draws_are_seeded_per_scene_and_valid():
    spec = sweep.load_sweep(SWEEPS / "smoke.yaml")
    draws = sweep.draw_scenes(spec)
    assert len(draws) == 6 and sweep.draw_scene(spec, 4) == draws[4]
    assert sweep.draw_scenes(spec, limit=2) == draws[:2]
    fresh = sweep.draw_scenes(spec, seed=777)
    assert fresh == sweep.draw_scenes({**spec, "seed": 777}) and spec["seed"] != 777
    assert all(a.scene["seed"] != b.scene["seed"] for a, b in zip(fresh, draws))  # other scenes
    for draw in draws:
        scene = scene_from_mapping(draw.scene)
        assert scene.radar.params.prf_hz == pytest.approx(20000.0 if draw.band == "K" else 4000.0)
        if draw.family == "quadrotor":
            assert draw.process["n_blades"] == 2 and draw.process["elevation_deg"] == scene.targets[0].elevation_deg
            rates = scene.targets[0].rotors.per_rotor("rev_per_s")
            assert np.all(np.sign(rates) == [1, -1, 1, -1]) and np.ptp(np.abs(rates)) == 0


def test_default_sweep_is_large_varied_and_every_scene_is_accepted():
    draws = sweep.draw_scenes(sweep.load_sweep(SWEEPS / "default.yaml"))
    assert len(draws) >= 200 and {d.band for d in draws} == {"X", "K", "W77", "W94"}
    kinds = [d.scene["targets"][0]["type"] if d.scene["targets"] and d.family != "clutter_only" else "clutter"
             for d in draws]
    assert {"multirotor", "bird", "point", "branch", "clutter"} == set(kinds)
    assert max(d.scene["radar"]["n_chirps"] for d in draws) <= 40000
    given = [d.process["n_blades"] is not None for d in draws if d.scene["targets"][0].get("type") == "multirotor"]
    assert 0.3 < np.mean(given) < 0.7  # N given to about half of the drones
    for draw in draws:  # every scene accepted by the simulator
        scene_from_mapping(draw.scene)


def test_distributions():
    rng = np.random.default_rng(1)
    values = [sweep.draw_value({"loguniform": [1.0, 100.0]}, rng, "x") for _ in range(2000)]
    assert min(values) >= 1.0 and max(values) <= 100.0
    assert np.mean(np.log10(values)) == pytest.approx(1.0, abs=0.05)  # uniform in log: mean of log10 is 1
    rates = sweep.draw_value({"rotor_rates": {"mean_hz": 100.0, "spread_fraction": 0.05}}, rng, "r", count=6)
    assert np.all(np.abs(np.abs(rates) - 100.0) <= 5.0) and np.all(np.sign(rates) == [1, -1] * 3)
    with pytest.raises(ParameterError, match=r"x: loguniform needs a low bound > 0"):
        sweep.draw_value({"loguniform": [0.0, 1.0]}, rng, "x")
    with pytest.raises(ParameterError, match=r"y: per_rotor is for keys inside a multirotor's rotors block"):
        sweep.draw_value({"per_rotor": 1.0}, rng, "y")


def test_evaluate_command_writes_its_files(tmp_path):
    (tmp_path / "scenes").mkdir()
    (tmp_path / "scenes" / "0099_old_run.yaml").write_text("name: old\n")
    result = CliRunner().invoke(main, ["evaluate", str(SWEEPS / "smoke.yaml"), "--out", str(tmp_path), "-j", "1"])
    assert result.exit_code == 0, result.output
    table = pd.read_csv(tmp_path / "scenes.csv")
    subjects = table[table["target"] == "subject"]
    assert sorted(subjects["scene"]) == sorted(p.stem for p in (tmp_path / "scenes").glob("*.yaml"))
    assert len(subjects) == 6 and not (tmp_path / "captures").exists()
    for feature in scoring.FEATURES:
        assert {f"{feature}_truth", f"{feature}_value", f"{feature}_verdict"} <= set(table.columns)
    text = (tmp_path / "summary.md").read_text()
    assert "## Class" in text and "## Confidently wrong" in text and text.strip() in result.output
    drones = subjects[subjects["kind"] == "multirotor"]
    assert len(drones) and drones["blade_profile"].isin(("uniform", "tapered", "points")).all()
    assert subjects.loc[subjects["kind"] != "multirotor", "blade_profile"].isna().all()
    assert "## Rotation rate by band and blade profile" in text


def test_kept_captures_are_processed_again_instead_of_simulated(tmp_path, monkeypatch):
    """A run with --keep-captures, then one with --reuse-captures on its folder: every scored column the same, no
    scene simulated. A capture of another scene (its /Truth YAML differs), a file that does not open or none is
    simulated anew; a folder another simulator kept, or the run's own, is refused with the fix."""
    from mdpipe.evaluate import captures

    first, second = tmp_path / "first", tmp_path / "second"
    args = ["evaluate", str(SWEEPS / "smoke.yaml"), "-j", "1", "--limit", "3"]
    result = CliRunner().invoke(main, [*args, "--out", str(first), "--keep-captures"])
    assert result.exit_code == 0, result.output
    kept = first / "captures"
    assert len(list(kept.glob("*.h5"))) == 3 and (kept / captures.SIMULATOR_FILE).exists()
    result = CliRunner().invoke(main, [*args, "--out", str(second), "--reuse-captures", str(kept)])
    assert result.exit_code == 0, result.output
    before, after = pd.read_csv(first / "scenes.csv"), pd.read_csv(second / "scenes.csv")
    timing = ["simulate_s", "process_s", "reused"]
    pd.testing.assert_frame_equal(before.drop(columns=timing), after.drop(columns=timing))
    assert (after["simulate_s"] == 0).all() and after["reused"].all() and not before["reused"].any()
    assert not (second / "captures").exists() and "3 of 3 captures reused" in result.output
    both = tmp_path / "both"  # reused and kept again: the same files, marked reusable in turn
    result = CliRunner().invoke(main, [*args, "--out", str(both), "--reuse-captures", str(kept), "--keep-captures"])
    assert result.exit_code == 0 and "3 of 3 captures reused" in result.output
    assert all((both / "captures" / p.name).read_bytes() == p.read_bytes() for p in kept.glob("*.h5"))
    assert (both / "captures" / captures.SIMULATOR_FILE).read_text() == (kept / captures.SIMULATOR_FILE).read_text()

    draws = sweep.draw_scenes(sweep.load_sweep(SWEEPS / "smoke.yaml"), limit=3)
    (kept / f"{draws[0].name}.h5").rename(kept / f"{draws[1].name}.h5")  # scene 1's name, scene 0's capture
    (tmp_path / "third" / "scenes").mkdir(parents=True)
    (tmp_path / "third" / "captures").mkdir()
    simulated = []
    monkeypatch.setattr("mdpipe.simulate.run.simulate_to_file",
                        lambda *a, **k: simulated.append(a[1].name) or pytest.fail("simulated"))
    with pytest.raises(pytest.fail.Exception):
        run.run_scene(draws[1], tmp_path / "third", reuse_dir=kept)
    assert simulated == [f"{draws[1].name}.h5"]
    (kept / "garbage.h5").write_bytes(b"\x89HDF\r\n\x1a\n" + bytes(100))  # an HDF5 signature, nothing after it
    assert captures.kept_truth(kept / "garbage.h5", "") is None
    assert captures.kept_truth(kept / "absent.h5", "") is None
    scene_yaml = scene_to_yaml(draws[2].scene)
    assert captures.kept_truth(kept / f"{draws[2].name}.h5", scene_yaml) is not None
    with h5py.File(kept / f"{draws[2].name}.h5", "r+") as h5:  # a truth without what scoring reads
        expected = json.loads(h5["Truth"].attrs["expected_json"])
        h5["Truth"].attrs["expected_json"] = json.dumps({k: v for k, v in expected.items() if k != "simulation"})
    assert captures.kept_truth(kept / f"{draws[2].name}.h5", scene_yaml) is None
    assert not captures.mark_simulator(tmp_path / "third" / "captures", "0" * 64)  # code changed during the run
    assert not (tmp_path / "third" / "captures" / captures.SIMULATOR_FILE).exists()
    sources = {path.relative_to(ROOT).as_posix() for path in captures.simulator_sources()}
    assert {"mdpipe/params.py", "mdpipe/io/radarlog.py", "mdpipe/__init__.py", "mdpipe/simulate/run.py"} <= sources
    assert not any(name.startswith("mdpipe/process/") for name in sources)  # the simulator imports no processing

    def unscorable(*_args, **_kwargs):
        raise KeyError("duration_s")

    monkeypatch.setattr(run, "score_scene", unscorable)  # a kept /Truth whose inner keys are missing
    with pytest.raises(MdpipeError, match=rf"{draws[0].name}.h5: its /Truth cannot be scored .*delete the file"):
        run.run_scene(draws[0], tmp_path / "third", reuse_dir=both / "captures")

    (kept / captures.SIMULATOR_FILE).write_text("0" * 64 + "\n")
    result = CliRunner().invoke(main, [*args, "--out", str(second), "--reuse-captures", str(kept)])
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert "was simulated by other simulator code" in result.output and "--keep-captures" in result.output
    result = CliRunner().invoke(main, [*args, "--out", str(first), "--reuse-captures", str(kept)])
    assert result.exit_code == 2 and "is this run's own captures folder" in result.output


def test_a_capture_the_processing_fails_on_is_recorded_as_a_wrong_class(tmp_path, monkeypatch):
    import mdpipe.process.pipeline

    def fail(*_args, **_kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(mdpipe.process.pipeline, "process_capture", fail)
    draw = sweep.draw_scene(sweep.load_sweep(SWEEPS / "smoke.yaml"), 5)
    (tmp_path / "scenes").mkdir()
    (tmp_path / "captures").mkdir()
    [record] = run.run_scene(draw, tmp_path)
    assert record["measured_class"] == "error" and not record["class_ok"]
    assert record["error"] == "RuntimeError: boom" and not list((tmp_path / "captures").iterdir())
    text = summary.report(summary.records_frame([record]), title="t", wall_s=1.0, jobs=1)
    assert "1 captures failed" in text and "| 0005_moving_point | moving_point | RuntimeError: boom |" in text


def test_evaluate_rejects_a_bad_sweep(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("seed: 1\nn_scenes: 3\nbands: {X: 9.8e9}\n")
    result = CliRunner().invoke(main, ["evaluate", str(bad), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert "families: missing (see configs/sweeps/default.yaml)" in result.output
    assert "Traceback" not in result.output
    bad.write_text((SWEEPS / "smoke.yaml").read_text().replace("type: point,", "type: point, wobble_hz: 3,"))
    result = CliRunner().invoke(main, ["evaluate", str(bad), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert "targets[0].wobble_hz: unknown key" in result.output


def test_kept_share_of_a_body_under_mean_removal():
    """At rest: nothing kept. Moving 2 m/s for 1 s at X band (130 wavelengths), sampled every lambda / 2 exactly
    (a sampled phase that aliases to a constant): all kept, the phase integrated along each piece. Swaying
    A sin(2 pi t / P) over whole periods: 1 - J0(4 pi A / lambda)^2."""
    from scipy.special import j0

    lam = 0.0306
    t = np.linspace(0.0, 1.0, 101)
    assert scoring.kept_share(t, np.full(101, 30.0), wavelength_m=lam) == pytest.approx(0.0, abs=1e-12)
    assert scoring.kept_share(t, 30.0 + (lam / 2) * 100 * t, wavelength_m=lam) == pytest.approx(1.0, abs=1e-3)
    fine = np.linspace(0.0, 2.0, 4001)
    amplitude = 0.004
    sway = 30.0 + amplitude * np.sin(2 * np.pi * fine / 1.0)
    assert scoring.kept_share(fine, sway, wavelength_m=lam) == pytest.approx(1 - j0(4 * np.pi * amplitude / lam) ** 2,
                                                                              abs=1e-4)


@pytest.mark.parametrize("beta", [1.0, 2.0, 5.0])
def test_strongest_line_share_of_a_sinusoidal_fm(beta):
    """``exp(j beta sin(2 pi f t))`` holds ``J_k(beta)^2`` of its power in the line at ``k f`` (each on a bin here):
    the share read is the largest over ``k != 0``; the line at 0 Hz (``J_0(1)^2 = 0.59``, the largest at beta 1)
    is the pattern's mean, not a line of its repeat."""
    from scipy.special import jv
    chirp_period_s, n_chirps, beat_hz = 1e-3, 4000, 5.0  # 0.25 Hz bins: the lines on bins 20 k
    t_s = np.arange(n_chirps) * chirp_period_s
    signal = np.exp(1j * beta * np.sin(2 * np.pi * beat_hz * t_s))
    orders = np.arange(1, 20)
    expected = float(np.max(jv(orders, beta) ** 2))
    assert scoring.strongest_line_share(signal, chirp_period_s=chirp_period_s, spacing_hz=beat_hz) == \
        pytest.approx(expected, rel=1e-6)
