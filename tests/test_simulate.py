"""Known-answer tests of the simulator: what lands in the file is what the physics predicts."""

import numpy as np
import pytest
from scipy import special

from conftest import RADARLOG_SMALL, XBAND, range_profiles, scene_mapping, slow_time
from mdpipe.io import open_capture
from mdpipe.physics import rotor
from mdpipe.physics.radar import SPEED_OF_LIGHT_MPS, beat_frequency_hz, doppler_hz
from mdpipe.simulate.scene import scene_from_mapping
from mdpipe.simulate.synth import noise_free_if, plan_targets


def rotor_target(*, rev=80.0, blade_length_m=0.105, root_m=0.0, count=1, points_per_blade=None, elevation=0.0,
                 position=(30.0, 0.0, 0.0), blades=2, body_rcs_m2=0.0):
    rotors = {"count": count, "blades": blades, "blade_length_m": blade_length_m, "root_m": root_m,
              "rev_per_s": rev}
    if points_per_blade is not None:
        rotors["points_per_blade"] = points_per_blade
    return {"type": "multirotor", "motion": {"position_m": list(position)}, "elevation_deg": elevation,
            "body_rcs_m2": body_rcs_m2, "rotors": rotors}


@pytest.mark.parametrize("range_m", [11.0, 57.3, 200.0])
def test_point_target_lands_at_predicted_beat_frequency(tmp_capture, range_m):
    path, truth = tmp_capture(scene_mapping(RADARLOG_SMALL | {"n_chirps": 16},
                                            [{"type": "static", "range_m": range_m}]))
    profiles, params = range_profiles(path)
    assert truth["targets"][0]["range_bin"] == round(range_m / params.range_bin_m)
    assert np.argmax(np.abs(profiles).mean(axis=0)) == round(range_m / params.range_bin_m)
    pad = 64  # zero-padded FFT: frequency grid fs / (64 N), a 64th of a bin
    with open_capture(path) as cap:
        chirp = cap.read_chirps(0, 1)[0, 0].astype(np.float64)
    spectrum = np.abs(np.fft.rfft(chirp * np.hanning(params.n_samples), n=pad * params.n_samples))
    f_peak = np.argmax(spectrum) * params.sample_rate_hz / (pad * params.n_samples)
    f_b = beat_frequency_hz(range_m, slope_hz_per_s=params.slope_hz_per_s)
    assert abs(f_peak - f_b) <= params.sample_rate_hz / (pad * params.n_samples)


@pytest.mark.parametrize("velocity_mps", [-3.0, 1.2])
def test_moving_point_at_predicted_doppler(tmp_capture, velocity_mps):
    """A point at 40 m moving radially: slow-time peak at -2 v / lambda (centre wavelength), positive approaching."""
    path, truth = tmp_capture(scene_mapping(RADARLOG_SMALL, [
        {"type": "point", "motion": {"position_m": [40.0, 0.0, 0.0], "velocity_mps": [velocity_mps, 0, 0]}}]))
    signal, params = slow_time(path, round(40.0 / RADARLOG_SMALL_BIN))
    n = len(signal)
    spectrum = np.abs(np.fft.fft(signal * np.hanning(n), n=16 * n))
    freqs = np.fft.fftfreq(16 * n, params.chirp_period_s)
    expected = doppler_hz(velocity_mps, wavelength_m=params.wavelength_m)
    assert truth["targets"][0]["body_doppler_hz"]["mean"] == pytest.approx(expected, rel=1e-6)
    assert abs(freqs[np.argmax(spectrum)] - expected) <= params.prf_hz / (16 * n)
    assert np.sign(freqs[np.argmax(spectrum)]) == -np.sign(velocity_mps)


RADARLOG_SMALL_BIN = SPEED_OF_LIGHT_MPS * RADARLOG_SMALL["sample_rate_hz"] * RADARLOG_SMALL["ramp_up_s"] / (
    2 * (RADARLOG_SMALL["f_stop_hz"] - RADARLOG_SMALL["f_start_hz"]) * RADARLOG_SMALL["n_samples"])


def range_fft_response(freqs_hz, params, range_m, range_bin):
    """What the Hann range FFT does to a slow-time line at Doppler f (conftest's convention).

    A line ``C exp(j 2 pi f t)`` of the echo reaches the conjugated bin k as
    ``C conj(W(f_b - k fs / N - f)) / 2`` with ``W(f) = sum_n w[n] exp(j 2 pi f n / fs)``: the window's
    response at the tone's offset from the bin, Doppler included.
    """
    n = np.arange(params.n_samples)
    offset = beat_frequency_hz(range_m, slope_hz_per_s=params.slope_hz_per_s) - range_bin * params.sample_rate_hz / params.n_samples
    w = np.hanning(params.n_samples) * np.exp(2j * np.pi * np.outer(offset - np.asarray(freqs_hz), n) / params.sample_rate_hz)
    return np.conj(w.sum(axis=1)) / 2


def compare_lines(measured, oracle, on):
    """Measured complex lines equal the oracle up to one common complex factor (amplitude, hub phase)."""
    scale = np.vdot(oracle[on], measured[on]) / np.vdot(oracle[on], oracle[on])
    np.testing.assert_allclose(measured[on], scale * oracle[on], atol=1e-3 * np.abs(scale * oracle).max())
    assert np.max(np.abs(measured[~on])) < 1e-3 * np.max(np.abs(measured[on]))


def line_spectrum(path, rate_hz, harmonics):
    """Slow-time lines at ``harmonics * rate_hz`` of the target at 30 m (bin 4), X band; exact bins."""
    signal, params = slow_time(path, 4)
    df = params.prf_hz / len(signal)
    return np.fft.fft(signal)[np.round(harmonics * rate_hz / df).astype(int)] / len(signal), params


@pytest.mark.parametrize("n_blades", [2, 3])
def test_rotor_lines_at_multiples_of_chopping_with_bessel_weights(tmp_capture, n_blades):
    """One point per blade at radius 5 cm: lines at m N f_rot with weights J_m(Gamma) (Eqs. 2-4).

    X band, 80 rev/s, 0.1 s = 8 turns exactly (4000 chirps at 25 us), so every line sits on an FFT bin.
    """
    radius, m = 0.05, np.arange(-40, 41)
    target = rotor_target(blade_length_m=radius + 0.005, root_m=radius - 0.005, points_per_blade=1,
                          blades=n_blades)
    path, truth = tmp_capture(scene_mapping(XBAND, [target]))
    measured, params = line_spectrum(path, 80.0, m)
    oracle = rotor.bessel_line_weights(m, radius_m=radius, wavelength_m=SPEED_OF_LIGHT_MPS / params.f_start_hz,
                                       n_blades=n_blades)
    compare_lines(measured, oracle * range_fft_response(m * 80.0, params, 30.0, 4), m % n_blades == 0)
    assert truth["targets"][0]["chopping_freq_hz"] == n_blades * 80.0
    assert truth["targets"][0]["flash_period_s"] == pytest.approx(1 / (80.0 * (2 if n_blades == 2 else 6)))


def blade_line_oracle(m, *, blade_length_m, wavelength_m, n_blades, elevation_deg):
    """Exact lines of N closed-form blades (root at the hub): sum of Eq. 3 over the blade, ``int_0^L J_m dr``."""
    rho = (np.arange(4000) + 0.5) / 4000 * blade_length_m
    gamma = 4 * np.pi * rho * np.cos(np.deg2rad(elevation_deg)) / wavelength_m
    integral = special.jv(m[:, None], gamma[None, :]).mean(axis=1) * blade_length_m
    return np.where(m % n_blades == 0, n_blades * integral * np.exp(-1j * m * np.pi / 2), 0.0)


@pytest.mark.parametrize("rev, blade_length_m, elevation", [(80.0, 0.105, 0.0), (70.0, 0.13, 60.0), (100.0, 0.266, 0.0)])
def test_doppler_extent_matches_eq6(tmp_capture, rev, blade_length_m, elevation):
    """Closed-form blades, X band, no aliasing: the whole line spectrum and its extent (Eq. 6).

    The lines equal the blade-integrated Bessel oracle. Their envelope ends at the tip Doppler
    ``Gamma f_rot`` of Eq. 6 up to the transition of J_m(Gamma) around m = Gamma, about
    (Gamma / 2)^(1/3) lines wide: the edge where 1e-3 of the energy lies outside must sit within
    that width plus one chopping interval of Eq. 6.
    """
    path, truth = tmp_capture(scene_mapping(XBAND | {"n_chirps": 8000}, [rotor_target(
        rev=rev, blade_length_m=blade_length_m, elevation=elevation)]))
    lam0 = SPEED_OF_LIGHT_MPS / XBAND["f_start_hz"]
    gamma_tip = 4 * np.pi * blade_length_m * np.cos(np.deg2rad(elevation)) / lam0
    m = np.arange(-int(gamma_tip) - 40, int(gamma_tip) + 41)
    measured, params = line_spectrum(path, rev, m)
    oracle = blade_line_oracle(m, blade_length_m=blade_length_m, wavelength_m=lam0, n_blades=2,
                               elevation_deg=elevation)
    compare_lines(measured, oracle * range_fft_response(m * rev, params, 30.0, 4), m % 2 == 0)

    tip = rotor.tip_doppler_hz(rev, blade_length_m=blade_length_m, wavelength_m=params.wavelength_m,
                               elevation_deg=elevation)
    assert truth["targets"][0]["tip_doppler_hz"] == pytest.approx(tip)
    assert truth["targets"][0]["doppler_bw_hz"] == pytest.approx(2 * tip)
    assert not truth["targets"][0]["aliased"]
    power = np.abs(measured) ** 2
    outside = np.cumsum(power[::-1])[::-1] / power.sum()  # energy at and above each line
    edge_hz = m[np.nonzero(outside >= 1e-3)[0][-1]] * rev
    assert abs(edge_hz - tip) <= rev * ((gamma_tip / 2) ** (1 / 3) + 2)


def test_phase_accurate_at_one_kilometre_76ghz(tmp_capture):
    """A point at 1 km approaching at 0.5 m/s: slow-time phase steps 4 pi v Tp / lambda, no float32 jitter."""
    radar = RADARLOG_SMALL | {"n_chirps": 512, "n_samples": 2048, "sample_rate_hz": 40e6}  # 3.8 km reach
    path, truth = tmp_capture(scene_mapping(radar, [
        {"type": "point", "motion": {"position_m": [1000.0, 0, 0], "velocity_mps": [-0.5, 0, 0]}}]))
    signal, params = slow_time(path, truth["targets"][0]["range_bin"])
    phase = np.unwrap(np.angle(signal))
    t = np.arange(len(signal)) * params.chirp_period_s
    slope, intercept = np.polyfit(t, phase, 1)
    expected = 2 * np.pi * doppler_hz(-0.5, wavelength_m=params.wavelength_m)
    assert slope == pytest.approx(expected, rel=1e-5)
    residual = phase - (slope * t + intercept)
    assert np.std(residual) < 2e-3  # float32 phases at 1 km would scatter by ~0.1 rad


def fimi_rotor_scene(in_chirp, migration="auto"):
    radar = RADARLOG_SMALL | {"n_samples": 128, "sample_rate_hz": 2.5e6, "n_chirps": 256}
    target = rotor_target(rev=80.0, position=(3.8, 0.0, 0.0), count=2) | {
        "motion": {"position_m": [3.8, 0.0, 0.0], "velocity_mps": [-2.0, 0.0, 0.0]}}
    return scene_from_mapping(scene_mapping(radar, [target], fidelity={"in_chirp_motion": in_chirp,
                                                                       "range_migration": migration}))


def noise_free(scene):
    radar = scene.radar.params
    return noise_free_if(plan_targets(scene), 0, scene.radar.n_chirps, radar=radar).astype(np.float64)


def test_fidelity_choice_meets_its_bound_and_stop_and_hop_does_not():
    """FIMI blades at 76 GHz move ~1.4 wavelengths (two-way) during a ramp: in-chirp motion matters."""
    exact = noise_free(fimi_rotor_scene("exact"))
    scale = np.sqrt(np.mean(exact ** 2))
    auto_scene = fimi_rotor_scene("auto")
    model = plan_targets(auto_scene)[0].model
    assert model.in_chirp_cycles == pytest.approx(1.4, abs=0.05) and model.nodes_per_chirp > 1
    assert model.range_migration
    auto_err = np.sqrt(np.mean((noise_free(auto_scene) - exact) ** 2)) / scale
    hop_err = np.sqrt(np.mean((noise_free(fimi_rotor_scene("off")) - exact) ** 2)) / scale
    assert auto_err <= max(model.interpolation_error_bound, 1e-5)
    assert hop_err > 100 * auto_err and hop_err > 0.1
    fixed_err = np.sqrt(np.mean((noise_free(fimi_rotor_scene("auto", "off")) - exact) ** 2)) / scale
    assert fixed_err > 10 * auto_err


def test_static_scene_needs_no_in_chirp_model():
    scene = scene_from_mapping(scene_mapping(RADARLOG_SMALL, [{"type": "static", "range_m": 11.0}]))
    model = plan_targets(scene)[0].model
    assert model.nodes_per_chirp == 1 and not model.range_migration and model.in_chirp_cycles == 0.0


def test_noise_level_snr_and_independence(tmp_capture):
    target = {"type": "point", "motion": {"position_m": [20.0, 0, 0], "velocity_mps": [1.0, 0, 0]}}
    mapping = scene_mapping(RADARLOG_SMALL | {"n_channels": 3, "n_chirps": 512}, [target], noise={"snr_db": 3.0})
    path, truth = tmp_capture(mapping)
    sigma = truth["simulation"]["noise_sigma_v"]
    scene = scene_from_mapping(mapping)
    clean = noise_free_if(plan_targets(scene), 0, 512, radar=scene.radar.params)
    assert np.mean(clean.astype(np.float64) ** 2) / sigma**2 == pytest.approx(10 ** 0.3, rel=0.01)
    with open_capture(path) as cap:
        noise = cap.read_chirps(0, 512).transpose(1, 0, 2).astype(np.float64) - clean
    n = noise[0].size
    assert np.std(noise) == pytest.approx(sigma, rel=0.01)
    flat = noise.reshape(3, -1)
    correlation = np.corrcoef(flat)
    assert np.max(np.abs(correlation - np.eye(3))) < 5 / np.sqrt(n)
    lag = np.corrcoef(flat[0, :-1], flat[0, 1:])[0, 1]  # successive samples
    chirp_lag = np.corrcoef(noise[0, :-1].ravel(), noise[0, 1:].ravel())[0, 1]  # successive chirps
    assert abs(lag) < 5 / np.sqrt(n) and abs(chirp_lag) < 5 / np.sqrt(n)


def test_seeded_and_deterministic(tmp_path):
    from conftest import simulate
    mapping = scene_mapping(RADARLOG_SMALL | {"n_chirps": 64}, [rotor_target(position=(20.0, 0, 0))],
                            noise={"snr_db": 0.0}, seed=5)
    a, _ = simulate(tmp_path, mapping, "a.h5")
    b, _ = simulate(tmp_path, mapping, "b.h5")
    c, _ = simulate(tmp_path, mapping | {"seed": 6}, "c.h5")
    assert a.read_bytes() == b.read_bytes()  # the same scene and seed give the same file, byte for byte
    with open_capture(a) as ca, open_capture(b) as cb, open_capture(c) as cc:
        assert np.array_equal(ca.read_chirps(0, 64), cb.read_chirps(0, 64))
        assert not np.array_equal(ca.read_chirps(0, 64), cc.read_chirps(0, 64))


def test_int16_scaled_without_clipping_and_clipping_on_request(tmp_capture):
    target = rotor_target(position=(5.0, 0, 0), body_rcs_m2=0.01)
    path, truth = tmp_capture(scene_mapping(RADARLOG_SMALL | {"n_chirps": 128}, [target], noise={"snr_db": 20.0}))
    assert truth["simulation"]["clipped_samples"] == 0
    with open_capture(path) as cap:
        raw = cap.read_chirps(0, 128) / cap.params.full_scale_v_per_lsb
    assert np.max(np.abs(raw)) < 32767 and np.max(np.abs(raw)) > 2000  # uses the range, never clips
    small_scale = truth["simulation"]["lsb_v"] * 32767 / 10
    path, truth = tmp_capture(scene_mapping(RADARLOG_SMALL | {"n_chirps": 128}, [target], noise={"snr_db": 20.0},
                                            adc={"full_scale_v": small_scale}), "clip.h5")
    with open_capture(path) as cap:
        raw = np.rint(cap.read_chirps(0, 128) / cap.params.full_scale_v_per_lsb)
    clipped = np.count_nonzero((raw >= 32767) | (raw <= -32768))
    assert truth["simulation"]["clipped_samples"] > 0
    assert clipped >= truth["simulation"]["clipped_samples"]


def test_channel_phases_follow_azimuth(tmp_capture):
    """RX at y_c is nearer a target at azimuth az by y_c sin(az): in exp(-j 4 pi R / lambda) its echo leads by
    2 pi d sin(az) / lambda0 per element of spacing d."""
    az = np.deg2rad(20.0)
    position = [float(30.0 * np.cos(az)), float(30.0 * np.sin(az)), 0.0]
    path, truth = tmp_capture(scene_mapping(RADARLOG_SMALL | {"n_chirps": 8, "n_channels": 4},
                                            [{"type": "point", "motion": {"position_m": position}}]))
    with open_capture(path) as cap:
        block = cap.read_chirps(0, 8).astype(np.float64)
        params = cap.params
    bins = np.conj(np.fft.rfft(block * np.hanning(params.n_samples), axis=-1)[:, :, 8])
    steps = np.angle(bins[:, 1:] * np.conj(bins[:, :-1]))
    expected = 2 * np.pi * 1.948e-3 * np.sin(az) * params.f_start_hz / SPEED_OF_LIGHT_MPS
    np.testing.assert_allclose(steps, expected, atol=1e-3)


def test_bird_truth_wingbeat_and_spread(tmp_capture):
    bird = {"type": "bird", "motion": {"position_m": [15.0, -1.0, 10.0], "velocity_mps": [0.0, 2.0, 0.0]},
            "wingbeat_hz": 4.0, "upper_arm_m": 0.3, "forearm_m": 0.3}
    radar = XBAND | {"chirp_period_s": 250e-6, "n_chirps": 4000}
    path, truth = tmp_capture(scene_mapping(radar, [bird]))
    entry = truth["targets"][0]
    assert entry["wingbeat_freq_hz"] == 4.0 and entry["wingbeat_period_s"] == 0.25
    # the wing tip's speed is bounded by the angular rates: |dpsi1| L1 + (|dpsi1 - dpsi2| + |dphi2|) L2
    omega = 2 * np.pi * 4.0
    bound_mps = 2.0 + omega * np.deg2rad(40) * 0.6 + omega * np.deg2rad(20) * 0.3
    assert 0 < entry["micro_doppler_spread_mps"] <= 2 * bound_mps
    signal, params = slow_time(path, 2)
    assert np.abs(signal).max() > 0
