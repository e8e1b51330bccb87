"""Simulator realism: every switch changes the echo as the physics says it must."""

from pathlib import Path

import numpy as np
import pytest
from scipy import special

from conftest import XBAND, scene_mapping, slow_time
from mdpipe.physics import bird as bird_physics
from mdpipe.physics import rotor
from mdpipe.physics.radar import SPEED_OF_LIGHT_MPS
from mdpipe.simulate.random_process import SmoothProcess, target_rng
from mdpipe.simulate.run import target_powers_v2
from mdpipe.simulate.scene import load_scene_mapping, scene_from_mapping
from mdpipe.simulate.synth import noise_free_if, plan_targets
from mdpipe.simulate.targets import target_echo
from mdpipe.simulate.truth import expected_features
from test_simulate import line_spectrum, range_fft_response, rotor_target

CONFIGS = Path(__file__).resolve().parent.parent / "configs" / "realism"
LAMBDA0 = SPEED_OF_LIGHT_MPS / XBAND["f_start_hz"]


def plan_of(mapping, index=0):
    return plan_targets(scene_from_mapping(mapping))[index]


def echo_at(plan, t_s):
    return target_echo(plan.target, plan.realization, t_s, f0_hz=XBAND["f_start_hz"]).signal


# ---- rotors ----

def test_each_rotor_shows_its_own_chopping_comb(tmp_capture):
    """Two rotors at 80 and 86 rev/s: the dwell spectrum's two lines in 100-200 Hz sit at 2 x 80 and 2 x 86 Hz
    (within one 2 Hz bin of a 0.5 s dwell), and /Truth lists each rotor."""
    target = rotor_target(count=2, rev=[80.0, -86.0])
    path, truth = tmp_capture(scene_mapping(XBAND | {"n_chirps": 20000}, [target]))
    signal, params = slow_time(path, 4)
    spectrum = np.abs(np.fft.fft(signal * np.hanning(len(signal))))
    freqs = np.fft.fftfreq(len(signal), params.chirp_period_s)
    band = np.nonzero((freqs > 100) & (freqs < 200))[0]
    peaks = [i for i in band if spectrum[i] >= spectrum[i - 1] and spectrum[i] >= spectrum[i + 1]]
    strongest = sorted(peaks, key=lambda i: spectrum[i])[-2:]
    resolution = params.prf_hz / len(signal)
    np.testing.assert_allclose(np.sort(freqs[strongest]), [160.0, 172.0], atol=resolution)
    entry = truth["targets"][0]
    assert entry["rotor_rates_hz"] == [80.0, 86.0] and entry["rotation_rate_hz"] == 83.0
    assert entry["rotor_chopping_freqs_hz"] == [160.0, 172.0] and entry["expected_class"] == "drone"


def weighted_blade_oracle(m, *, blade_length_m, weight, n_blades=1):
    """Lines of blades rooted at the hub whose reflectivity along the span is ``weight(rho / L)``:
    ``N int_0^L weight J_m(4 pi rho / lambda) d rho exp(-j m pi / 2)`` at multiples of N."""
    u = (np.arange(4000) + 0.5) / 4000
    gamma = 4 * np.pi * u * blade_length_m / LAMBDA0
    integral = (special.jv(m[:, None], gamma[None, :]) * weight(u)).mean(axis=1) * blade_length_m
    return np.where(m % n_blades == 0, n_blades * integral * np.exp(-1j * m * np.pi / 2), 0.0)


def test_tapered_blade_lines_follow_the_tapered_integral_and_keep_the_tip_edge(tmp_capture):
    """Reflectivity 1 at the root falling to 0.3 at the tip: the lines are the Bessel integral weighted by the
    taper, and the tip Doppler (Eq. 6) is where the spectrum ends, as for uniform blades."""
    rev, length = 80.0, 0.105
    target = rotor_target(rev=rev, blade_length_m=length)
    target["rotors"] |= {"blade_profile": "tapered", "tip_reflectivity": 0.3}
    path, truth = tmp_capture(scene_mapping(XBAND | {"n_chirps": 8000}, [target]))
    gamma_tip = 4 * np.pi * length / LAMBDA0
    m = np.arange(-int(gamma_tip) - 40, int(gamma_tip) + 41)
    measured, params = line_spectrum(path, rev, m)
    oracle = weighted_blade_oracle(m, blade_length_m=length, weight=lambda u: 1 - 0.7 * u, n_blades=2)
    oracle = oracle * range_fft_response(m * rev, params, 30.0, 4)
    uniform = weighted_blade_oracle(m, blade_length_m=length, weight=np.ones_like, n_blades=2)
    on = m % 2 == 0
    scale = np.vdot(oracle[on], measured[on]) / np.vdot(oracle[on], oracle[on])
    np.testing.assert_allclose(measured[on], scale * oracle[on], atol=1e-3 * np.abs(scale * oracle).max())
    assert np.max(np.abs(measured[~on])) < 1e-3 * np.max(np.abs(measured[on]))
    # the taper matters: the uniform blade's lines do not fit
    uniform = uniform * range_fft_response(m * rev, params, 30.0, 4)
    u_scale = np.vdot(uniform[on], measured[on]) / np.vdot(uniform[on], uniform[on])
    assert np.max(np.abs(measured[on] - u_scale * uniform[on])) > 0.05 * np.abs(measured).max()
    power = np.abs(measured) ** 2
    outside = np.cumsum(power[::-1])[::-1] / power.sum()
    edge_hz = m[np.nonzero(outside >= 1e-3)[0][-1]] * rev
    tip = rotor.tip_doppler_hz(rev, blade_length_m=length, wavelength_m=params.wavelength_m)
    assert abs(edge_hz - tip) <= rev * ((gamma_tip / 2) ** (1 / 3) + 2)
    assert truth["targets"][0]["blade_profile"] == "tapered" and truth["targets"][0]["tip_reflectivity"] == 0.3


def test_tapered_closed_form_equals_quadrature():
    """The spherical-Bessel closed form against a 20000-point midpoint sum, small and large phase spreads."""
    ra, rb = np.array([0.0, 0.01, -0.02, 0.0]), np.array([1e-6, 0.05, 0.08, 0.3])
    lam, taper = 0.0305, 0.3
    w = (np.arange(20000) + 0.5) / 20000
    ranges = ra[:, None] + w * (rb - ra)[:, None]
    quadrature = ((1 - (1 - taper) * w) * np.exp(-4j * np.pi * ranges / lam)).mean(axis=1) * 0.1
    closed = rotor.tapered_segment_echo(ra, rb, length_m=0.1, wavelength_m=lam, end_reflectivity=taper)
    np.testing.assert_allclose(closed, quadrature, atol=1e-8)
    np.testing.assert_allclose(rotor.tapered_segment_echo(ra, rb, length_m=0.1, wavelength_m=lam, end_reflectivity=1.0),
                               rotor.segment_echo(ra, rb, length_m=0.1, wavelength_m=lam), atol=1e-15)


def test_blade_gains_create_lines_at_the_rotation_rate(tmp_capture):
    """Blades of gains 1 and 2 (N = 2): line m of one blade, c_m, becomes c_m (1 + 2 (-1)^m): 3 c_m at even m and
    -c_m at odd m, so lines appear at odd multiples of f_rot, 1/3 as strong as a balanced pair would make them."""
    rev, length = 80.0, 0.105
    target = rotor_target(rev=rev, blade_length_m=length)
    target["rotors"]["blade_gains"] = [1.0, 2.0]
    path, truth = tmp_capture(scene_mapping(XBAND | {"n_chirps": 8000}, [target]))
    m = np.arange(-60, 61)
    measured, params = line_spectrum(path, rev, m)
    single = weighted_blade_oracle(m, blade_length_m=length, weight=np.ones_like)
    oracle = single * (1 + 2 * (-1.0) ** m) * range_fft_response(m * rev, params, 30.0, 4)
    scale = np.vdot(oracle, measured) / np.vdot(oracle, oracle)
    np.testing.assert_allclose(measured, scale * oracle, atol=1e-3 * np.abs(scale * oracle).max())
    odd = m % 2 == 1
    assert np.max(np.abs(measured[odd])) > 0.05 * np.max(np.abs(measured))
    assert truth["targets"][0]["blade_gains"] == [1.0, 2.0] and truth["targets"][0]["blade_imbalance"]


def test_rate_wander_rms_measured_from_the_flashes_matches_the_fraction():
    """Rate 80 (1 + 0.05 w(t)), correlation 0.1 s, over 2 s: the flash times (a 2-blade rotor flashes every half
    turn) give the rate between flashes; its mean is 80 rev/s and its rms deviation 5 % (w: unit rms over the
    capture; averaging over 6 ms intervals loses (pi 6 ms / 0.1 s)^2 / 6 ~ 0.6 % of the rms at most). Means are
    time-weighted: a plain mean over half-turns would weigh fast intervals more (biased up by rms^2 / mean)."""
    target = rotor_target(rev=80.0)
    target["rotors"] |= {"rate_wander_fraction": 0.05, "rate_wander_period_s": 0.1}
    plan = plan_of(scene_mapping(XBAND | {"n_chirps": 80000}, [target]))
    dt = 2e-6
    t = np.arange(0, 2.0, dt)
    mag = np.abs(echo_at(plan, t))
    peak = (mag[1:-1] > mag[:-2]) & (mag[1:-1] >= mag[2:]) & (mag[1:-1] > 0.5 * mag.max())
    i = np.nonzero(peak)[0] + 1
    a, b, c = mag[i - 1], mag[i], mag[i + 1]
    times = t[i] + dt * 0.5 * (a - c) / (a - 2 * b + c)  # parabolic refinement
    intervals = np.diff(times)
    rates = 0.5 / intervals  # half a turn between flashes
    mean = np.sum(rates * intervals) / np.sum(intervals)  # time-weighted, as w's normalisation is
    rms = np.sqrt(np.sum((rates - mean) ** 2 * intervals) / np.sum(intervals))
    assert mean == pytest.approx(80.0, rel=2e-4)
    assert rms / 80.0 == pytest.approx(0.05, rel=0.02)
    other = plan_of(scene_mapping(XBAND | {"n_chirps": 80000}, [target], seed=1))
    assert not np.allclose(echo_at(other, t[:20000]), echo_at(plan, t[:20000]))


def test_smooth_process_zero_mean_unit_rms_and_correlation_time():
    process = SmoothProcess(target_rng(3, 0, 0), 64, correlation_s=0.05, duration_s=1.0)
    t = np.linspace(0, 1.0, 20001)
    w = np.array([process.value(t, k) for k in range(64)])
    mean = np.trapezoid(w, t, axis=1)
    rms = np.sqrt(np.trapezoid(w**2, t, axis=1))
    np.testing.assert_allclose(mean, 0.0, atol=1e-7)  # the trapezoid rule itself errs by ~h^2 |w"| / 12 ~ 1e-8
    np.testing.assert_allclose(rms, 1.0, rtol=1e-6)
    np.testing.assert_allclose(process.integral(t[-1], 5), np.trapezoid(w[5], t), atol=1e-7)
    lag = 1000  # 0.05 s: exp(-1/2) = 0.61 for the Gaussian autocorrelation, over the realisations
    corr = np.mean(np.sum(w[:, :-lag] * w[:, lag:], axis=1) / np.sum(w[:, :-lag] ** 2, axis=1))
    assert corr == pytest.approx(np.exp(-0.5), abs=0.12)
    assert all(process.max_abs(k) >= np.abs(w[k]).max() for k in range(64))


def test_tilt_adds_to_the_elevation_and_body_scatterers_add_their_echo():
    tilted = rotor_target(rev=80.0, elevation=10.0)
    tilted["rotors"]["tilt_deg"] = 50.0
    level = rotor_target(rev=80.0, elevation=60.0)
    t = np.linspace(0, 0.0125, 501)
    np.testing.assert_array_equal(echo_at(plan_of(scene_mapping(XBAND, [tilted])), t),
                                  echo_at(plan_of(scene_mapping(XBAND, [level])), t))
    body = rotor_target(rev=80.0) | {"body_scatterers": [{"offset_m": [0.1, 0.0, 0.0], "rcs_m2": 0.04}]}
    bare = echo_at(plan_of(scene_mapping(XBAND, [rotor_target()])), t)
    extra = echo_at(plan_of(scene_mapping(XBAND, [body])), t) - bare
    expected = 0.2 / 30.0**2 * np.exp(-4j * np.pi * 30.1 / LAMBDA0)
    np.testing.assert_allclose(extra, expected, rtol=1e-9)


# ---- birds ----

def hovering_bird(**extra):
    return {"type": "bird", "motion": {"position_m": [20.0, 0.0, 0.0]}, "wingbeat_hz": 5.0, "upper_arm_m": 0.3,
            "forearm_m": 0.3, "body_rcs_m2": 0.0, **extra}


def test_flap_glide_moves_the_wings_only_while_flapping():
    """flap 2 s / glide 3 s over 10 s: the wings leave the mean (glide) pose exactly while the envelope is
    above 0, that is flap_s plus one ramp (0.2 s: one wingbeat) a cycle, 2 x 2.2 / 10 = 0.44 of the time; the
    flapping share (envelope above 1/2) in /Truth is 2 x 2 / 10 = 0.4."""
    mapping = scene_mapping(XBAND | {"chirp_period_s": 1e-3, "n_chirps": 10000},
                            [hovering_bird(flap_glide={"flap_s": 2.0, "glide_s": 3.0})])
    plan = plan_of(mapping)
    t = np.arange(0, 10.0, 1e-4)
    signal = echo_at(plan, t)
    glide = echo_at(plan, np.array([3.5]))[0]
    deviation = np.abs(signal - glide)
    active = np.mean(deviation > 1e-6 * deviation.max())
    assert active == pytest.approx(2 * 2.2 / 10, abs=2e-3)
    truth = expected_features(scene_from_mapping(mapping), [plan])["targets"][0]
    assert truth["flapping_share"] == pytest.approx(0.4) and truth["expected_class"] == "bird"


def test_flap_glide_envelope_is_smooth_and_crosses_half_at_the_switches():
    t = np.array([0.0, 2.0, 5.0, 7.0, 1.0, 3.5])
    e = bird_physics.flap_glide_envelope(t, flap_s=2.0, glide_s=3.0, ramp_s=0.2)
    np.testing.assert_allclose(e, [0.5, 0.5, 0.5, 0.5, 1.0, 0.0], atol=1e-12)
    fine = np.linspace(0, 10, 2000001)
    slope = np.diff(bird_physics.flap_glide_envelope(fine, flap_s=2.0, glide_s=3.0, ramp_s=0.2)) / np.diff(fine)
    assert np.max(np.abs(slope)) == pytest.approx(np.pi / 0.4, rel=1e-3)
    assert np.max(np.abs(np.diff(slope))) < 1e-2  # no jump in the slope
    assert bird_physics.flapping_share(6.0, flap_s=1.2, glide_s=1.8) == pytest.approx(0.4)
    assert bird_physics.flapping_share(4.0, flap_s=1.2, glide_s=1.8) == pytest.approx(2.2 / 4)


def test_wingbeat_drift_measured_from_the_beats():
    """Wingbeat 4 Hz drifting by +20 % over 4 s: the wings return to the top of the stroke (the echo at t = 0)
    once a beat; the beat rate rises linearly from 3.6 to 4.4 Hz (slope 0.2 Hz/s) and is 4 Hz mid-capture."""
    mapping = scene_mapping(XBAND | {"chirp_period_s": 1e-3, "n_chirps": 4000},
                            [hovering_bird(wingbeat_hz=4.0, wingbeat_drift_fraction=0.2)])
    plan = plan_of(mapping)
    t = np.arange(0, 4.0, 2e-5)
    distance = np.abs(echo_at(plan, t) - echo_at(plan, np.array([0.0]))[0])
    d = distance / distance.max()
    minima = np.nonzero((d[1:-1] < d[:-2]) & (d[1:-1] <= d[2:]))[0] + 1
    # the pose returns exactly (distance ~1e-7: quadratic in the 20 us sampling offset); other near-returns
    # of the echo's many-cycle phase stay above 1e-3
    tops = t[minima[d[minima] < 1e-5]]
    assert len(tops) == 15  # phase / 2 pi = 4 (4 + 0.2 (16 / 8 - 2)) = 16 beats: tops k = 1 .. 15 inside the capture
    rates = 1.0 / np.diff(tops)
    middle = 0.5 * (tops[1:] + tops[:-1])
    slope, intercept = np.polyfit(middle, rates, 1)
    assert slope == pytest.approx(0.2 * 4.0 / 4.0, rel=0.02)
    assert intercept + slope * 2.0 == pytest.approx(4.0, rel=2e-3)


def test_rough_wings_are_seeded_and_change_the_echo():
    """r = 0 is the mirror-smooth wing; r = 0.3 multiplies each wing scatterer by exp(0.3 (a + j b)), a and b of
    unit rms: the echo changes, by the same amount on the same seed and differently on another."""
    smooth = plan_of(scene_mapping(XBAND | {"chirp_period_s": 1e-3, "n_chirps": 2000}, [hovering_bird()]))
    rough_map = scene_mapping(XBAND | {"chirp_period_s": 1e-3, "n_chirps": 2000}, [hovering_bird(wing_roughness=0.3)])
    rough, again = plan_of(rough_map), plan_of(rough_map)
    other = plan_of(rough_map | {"seed": 9})
    t = np.linspace(0, 2.0, 4001)
    s0, s1 = echo_at(smooth, t), echo_at(rough, t)
    np.testing.assert_array_equal(s1, echo_at(again, t))
    relative = np.sqrt(np.mean(np.abs(s1 - s0) ** 2) / np.mean(np.abs(s0) ** 2))
    assert 0.1 < relative < 1.0
    assert not np.allclose(echo_at(other, t), s1)


# ---- branch ----

def test_branch_has_zero_mean_doppler_within_its_speed_bound():
    """Sway 5 cm at 0.8 Hz and leaves fluttering 1 cm at <= 4 Hz: every scatterer's speed is below
    2 pi (0.8 x 0.05 + 4 x 0.01) = 0.503 m/s, so the echo's spectrum lies within +-2 x 0.503 / lambda (33 Hz at
    X band), and the power-weighted mean Doppler of 20 s is ~0 (under 0.5 Hz: the net displacement over the dwell
    is at most 0.1 m, 2 x 0.1 / (lambda 20 s) = 0.33 Hz)."""
    branch = {"type": "branch", "position_m": [15.0, 0.0, 2.0]}
    mapping = scene_mapping(XBAND | {"chirp_period_s": 1e-3, "n_chirps": 20000}, [branch])
    plan = plan_of(mapping)
    t = np.arange(20000) * 1e-3
    signal = echo_at(plan, t)
    spectrum = np.abs(np.fft.fft(signal * np.hanning(len(t)))) ** 2
    freqs = np.fft.fftfreq(len(t), 1e-3)
    bound_hz = 2 * 2 * np.pi * (0.8 * 0.05 + 4 * 0.01) / LAMBDA0
    assert np.sum(spectrum[np.abs(freqs) > 1.05 * bound_hz]) < 1e-4 * spectrum.sum()
    moving = np.abs(np.fft.fft((signal - signal.mean()) * np.hanning(len(t)))) ** 2
    assert abs(np.sum(freqs * moving) / moving.sum()) < 0.5
    assert np.sum(moving[np.abs(freqs) > 5]) > 0.1 * moving.sum()  # it does move: a micro-Doppler spread
    truth = expected_features(scene_from_mapping(mapping), [plan])["targets"][0]
    assert truth["expected_class"] == "none" and truth["kind"] == "branch"
    centre_wavelength_m = scene_from_mapping(mapping).radar.params.wavelength_m
    assert truth["doppler_extent_hz"][1] == pytest.approx(bound_hz * LAMBDA0 / centre_wavelength_m, rel=1e-12)


# ---- scenes ----

def test_two_targets_in_one_range_bin_both_arrive():
    """configs/realism/two_in_one_bin.yaml (cut to 0.2 s): drone and pigeon share bin 33; the IF is the sum of
    each target's own IF, and the bin's spectrum holds the drone's chopping line (180 Hz) and the bird's body
    line (+36 .. +54 Hz)."""
    data = load_scene_mapping(CONFIGS / "two_in_one_bin.yaml")
    data["radar"]["n_chirps"] = 8000
    data.pop("noise")
    scene = scene_from_mapping(data)
    plans = plan_targets(scene)
    radar = scene.radar.params
    both = noise_free_if(plans, 0, 8000, radar=radar).astype(np.float64)
    each = [noise_free_if([p], 0, 8000, radar=radar).astype(np.float64) for p in plans]
    np.testing.assert_allclose(both, each[0] + each[1], atol=1e-6 * np.abs(both).max())
    truth = expected_features(scene, plans)
    assert [t["range_bin"] for t in truth["targets"]] == [33, 33]
    window = np.hanning(radar.n_samples)
    slow = np.conj(np.fft.rfft(both[0] * window, axis=-1)[:, 33])
    spectrum = np.abs(np.fft.fft((slow - slow.mean()) * np.hanning(8000)))
    freqs = np.fft.fftfreq(8000, radar.chirp_period_s)
    noise_floor = np.median(spectrum)
    chopping = spectrum[np.abs(freqs - 180.0) <= 5].max()
    bird_line = spectrum[(freqs > 30) & (freqs < 60)].max()
    assert chopping > 100 * noise_floor and bird_line > 100 * noise_floor


def test_moving_snr_counts_what_mti_keeps(tmp_capture):
    """A hovering drone with a bright body: moving_snr_db = 0 sets the noise to the power of the echo minus its
    slow-time mean; /Truth records both SNRs, the whole echo's higher by the body's share."""
    target = rotor_target(rev=80.0, body_rcs_m2=0.05)
    mapping = scene_mapping(XBAND | {"n_chirps": 2000}, [target], noise={"moving_snr_db": 0.0})
    path, truth = tmp_capture(mapping)
    scene = scene_from_mapping(mapping)
    plans = plan_targets(scene)
    clean = noise_free_if(plans, 0, 2000, radar=scene.radar.params).astype(np.float64)[0]
    mti = clean - clean.mean(axis=0)
    sigma = truth["simulation"]["noise_sigma_v"]
    assert np.mean(mti**2) / sigma**2 == pytest.approx(1.0, rel=0.02)
    entry = truth["targets"][0]
    assert entry["moving_snr_db"] == pytest.approx(0.0, abs=1e-9)
    whole, moving = target_powers_v2(plans, scene.radar.params, 2000)[0]
    assert entry["snr_db"] == pytest.approx(10 * np.log10(whole / moving), rel=1e-9) and entry["snr_db"] > 3.0


@pytest.mark.parametrize("name", ["quad_unequal_tapered", "bird_flap_glide", "branch", "two_in_one_bin"])
def test_realism_configs_build(name):
    scene = scene_from_mapping(load_scene_mapping(CONFIGS / f"{name}.yaml"))
    assert scene.targets


def test_rotor_line_weights_predict_an_imbalanced_tapered_three_blade_rotor(tmp_capture):
    """N = 3, gains [1, 2, 1.5], tapered from a 2 cm root, phase 30 deg: every line (not only multiples of 3) equals
    :func:`mdpipe.physics.rotor.rotor_line_weights`, the oracle the feature extractor can use for N."""
    rev, length = 80.0, 0.105
    target = rotor_target(rev=rev, blade_length_m=length, root_m=0.02, blades=3)
    target["rotors"] |= {"blade_profile": "tapered", "tip_reflectivity": 0.5, "blade_gains": [1.0, 2.0, 1.5],
                         "phase_deg": 30.0}
    path, _ = tmp_capture(scene_mapping(XBAND | {"n_chirps": 8000}, [target]))
    m = np.arange(-60, 61)
    measured, params = line_spectrum(path, rev, m)
    oracle = rotor.rotor_line_weights(m, blade_gains=[1.0, 2.0, 1.5], blade_length_m=length, root_m=0.02,
                                      wavelength_m=LAMBDA0, profile="tapered", tip_reflectivity=0.5,
                                      phase0_rad=np.deg2rad(30.0))
    oracle = oracle * range_fft_response(m * rev, params, 30.0, 4)
    scale = np.vdot(oracle, measured) / np.vdot(oracle, oracle)
    np.testing.assert_allclose(measured, scale * oracle, atol=1e-3 * np.abs(scale * oracle).max())
    assert np.max(np.abs(measured[m % 3 != 0])) > 0.05 * np.max(np.abs(measured))
    equal = rotor.blade_gain_factor(m, [1.0, 1.0, 1.0])
    np.testing.assert_allclose(equal, np.where(m % 3 == 0, 3.0, 0.0), atol=1e-12)


def test_points_profile_named_or_implied_by_points_per_blade_is_eq1():
    named = rotor_target(rev=80.0)
    named["rotors"] |= {"blade_profile": "points", "points_per_blade": 4}
    implied = rotor_target(rev=80.0, points_per_blade=4)
    t = np.linspace(0, 0.0125, 501)
    a, b = plan_of(scene_mapping(XBAND, [named])), plan_of(scene_mapping(XBAND, [implied]))
    np.testing.assert_array_equal(echo_at(a, t), echo_at(b, t))
    assert a.target.rotors.profile == b.target.rotors.profile == "points"
    assert not np.allclose(echo_at(a, t), echo_at(plan_of(scene_mapping(XBAND, [rotor_target(rev=80.0)])), t))
