"""Shared physics: forward/inverse pairs, blade models, the bird's rotation-built wing."""

import math
from fractions import Fraction

import numpy as np
import pytest

from mdpipe.physics import bird, radar, rotor

C = radar.SPEED_OF_LIGHT_MPS


@pytest.mark.parametrize("range_m", [0.5, 3.8, 11.0, 1000.0])
def test_beat_frequency_round_trip(range_m):
    slope = 40e6 / 51.2e-6
    f_b = radar.beat_frequency_hz(range_m, slope_hz_per_s=slope)
    assert f_b == pytest.approx(2 * slope * range_m / C, rel=1e-15)
    assert radar.range_from_beat_frequency_m(f_b, slope_hz_per_s=slope) == pytest.approx(range_m, rel=1e-15)


def test_doppler_sign_and_round_trip():
    lam = C / 76.02e9
    approaching = radar.doppler_hz(-2.0, wavelength_m=lam)
    assert approaching == pytest.approx(4.0 / lam) and approaching > 0
    assert radar.range_rate_from_doppler_mps(approaching, wavelength_m=lam) == pytest.approx(-2.0)


def test_two_way_phase_exact_at_one_kilometre():
    """4 pi f R / c is ~3.2e6 rad at 1 km and 76 GHz; the wrapped phase keeps float64 precision."""
    f0, ranges = 76e9, [1000.0, 1000.0001, 999.987654321]
    for r in ranges:
        cycles = Fraction(2) * Fraction(f0) * Fraction(r) / Fraction(C)
        frac = cycles - round(cycles)
        exact = 2 * math.pi * float(frac)
        assert abs(radar.two_way_phase_rad(r, frequency_hz=f0) - exact) < 1e-8
        naive32 = np.float32(4 * np.pi * f0 / C) * np.float32(r)
        assert abs(np.angle(np.exp(1j * (float(naive32) - exact)))) > 1e-3  # what float32 would lose


def test_eq5_and_eq6_pairs_fimi_numbers():
    """FIMI X8 SE: 2 blades at 80 rev/s, r = 10.5 cm. Eq. 5: 160 Hz; Eq. 6 at 9.8 GHz: 4 (2 pi 80) 0.105 / 0.0305911 = 6901 Hz."""
    lam = C / 9.8e9
    assert rotor.chopping_frequency_hz(80.0, n_blades=2) == 160.0
    assert rotor.rotation_rate_from_chopping_hz(160.0, n_blades=2) == 80.0
    bw = rotor.doppler_bandwidth_hz(80.0, blade_length_m=0.105, wavelength_m=lam)
    assert bw == pytest.approx(4 * 2 * np.pi * 80 * 0.105 / lam) and bw == pytest.approx(6901, abs=1)
    assert rotor.blade_length_from_bandwidth_m(bw, rotation_rate_hz=80.0, wavelength_m=lam) == pytest.approx(0.105)
    at60 = rotor.doppler_bandwidth_hz(70.0, blade_length_m=0.13, wavelength_m=lam, elevation_deg=60.0)
    assert at60 == pytest.approx(3738, abs=1)  # the paper's Table IV gives 6.75 kHz for config 4
    assert rotor.blade_length_from_bandwidth_m(at60, rotation_rate_hz=70.0, wavelength_m=lam,
                                               elevation_deg=60.0) == pytest.approx(0.13)


@pytest.mark.parametrize("n_blades, flashes", [(2, 2), (3, 6), (4, 4), (5, 10)])
def test_flash_counts_even_and_odd(n_blades, flashes):
    assert rotor.flashes_per_revolution(n_blades) == flashes
    assert rotor.flash_period_s(80.0, n_blades=n_blades) == pytest.approx(1 / (flashes * 80.0))


@pytest.mark.parametrize("n_blades", [2, 3, 4, 5])
def test_closed_form_blade_flashes_at_predicted_times(n_blades):
    """|echo| peaks when a blade is broadside (theta = pi/2 + n pi): N flashes a turn for even N, 2N for odd."""
    lam, rate, length = C / 76e9, 80.0, 0.105
    t = np.linspace(0, 1 / rate, 400001)[:-1]
    mag = np.abs(rotor.rotor_echo(t, rotation_rate_hz=rate, n_blades=n_blades, blade_length_m=length,
                                  wavelength_m=lam))
    local_max = (mag > 0.5 * mag.max()) & (mag >= np.roll(mag, 1)) & (mag >= np.roll(mag, -1))
    k, n = np.meshgrid(np.arange(n_blades), np.arange(2))
    expected = np.unique(np.round(((np.pi / 2 + n * np.pi - 2 * np.pi * k / n_blades) / (2 * np.pi * rate))
                                  % (1 / rate), 12))
    assert len(expected) == rotor.flashes_per_revolution(n_blades)
    np.testing.assert_allclose(np.sort(t[local_max]), expected, atol=2 * (t[1] - t[0]))
    # at a flash the broadside blade(s) add their full span; blade k at |cos(theta)| = |sin(2 pi k / N)| adds at
    # most the sinc's envelope, span / (pi 2 span |cos| / lambda) = lambda / (2 pi |cos|)
    broadside = 2 if n_blades % 2 == 0 else 1
    cos_others = np.abs(np.sin(2 * np.pi * np.arange(1, n_blades) / n_blades))
    sidelobes = np.sum(lam / (2 * np.pi * cos_others[cos_others > 1e-9]))
    assert abs(mag.max() - broadside * length) <= sidelobes + 1e-12


def test_point_blades_converge_to_closed_form():
    """Midpoint rule: |error| <= span (a h)^2 / 24 with a = 4 pi / lambda, h = span / Q; converges as 1/Q^2."""
    lam, span = C / 76e9, 0.095
    t = np.linspace(0, 1 / 80, 4001)
    kwargs = dict(rotation_rate_hz=80.0, n_blades=2, blade_length_m=0.105, root_m=0.01, wavelength_m=lam,
                  elevation_deg=20.0)
    closed = rotor.rotor_echo(t, **kwargs)
    errors = []
    for q in (64, 256, 1024, 4096):
        err = np.max(np.abs(rotor.rotor_echo(t, points_per_blade=q, **kwargs) - closed))
        bound = 2 * span * (4 * np.pi / lam * span / q) ** 2 / 24  # two blades
        assert err <= bound
        errors.append(err)
    assert errors[-1] / errors[-2] == pytest.approx(1 / 16, rel=0.05)


def test_bessel_oracle_suppresses_non_multiples_of_n():
    w = rotor.bessel_line_weights(np.arange(-10, 11), radius_m=0.05, wavelength_m=0.03, n_blades=3)
    assert np.all(w[np.arange(-10, 11) % 3 != 0] == 0)
    assert np.any(np.abs(w[np.arange(-10, 11) % 3 == 0]) > 0.1)


def test_rotor_parameter_errors():
    with pytest.raises(ValueError, match=r"root_m=0.2 must lie in \[0, blade_length_m=0.1\)"):
        rotor.rotor_echo([0.0], rotation_rate_hz=1, n_blades=2, blade_length_m=0.1, root_m=0.2, wavelength_m=0.01)
    with pytest.raises(ValueError, match="points_per_blade=0 must be an integer >= 1"):
        rotor.rotor_echo([0.0], rotation_rate_hz=1, n_blades=2, blade_length_m=0.1, wavelength_m=0.01,
                         points_per_blade=0)


# ---- bird: the paper's Eqs. 10-15 written literally (degrees inside the trig, as printed) ----

def paper_joints(psi1, psi2, phi2, l1, l2):
    """Eqs. 10-15 with angles in radians; tan() where the paper has it."""
    y1 = l1 * np.cos(psi1)
    z1 = y1 * np.tan(psi1)
    y2 = l1 * np.cos(psi1) + l2 * np.cos(phi2) * np.cos(psi1 - psi2)
    d = phi2 / np.cos(psi1 - psi2)
    x2 = -(y2 - y1) * np.tan(d)
    z2 = z1 + (y2 - y1) * np.tan(psi1 - psi2)
    return np.stack([np.zeros_like(y1), y1, z1], -1), np.stack([x2, y2, z2], -1)


def test_rotation_built_wing_equals_paper_where_tan_is_finite():
    t = np.linspace(0, 2, 2001)
    psi1, psi2, phi2 = bird.flap_angles_rad(t, wingbeat_hz=1.0, a1_deg=40, a2_deg=40, psi10_deg=15, psi20_deg=20,
                                            c2_deg=20, phi20_deg=0)
    p1, p2 = bird.wing_joints_m(psi1, psi2, phi2, upper_arm_m=0.625, forearm_m=0.625)
    q1, q2 = paper_joints(psi1, psi2, phi2, 0.625, 0.625)
    np.testing.assert_allclose(p1, q1, atol=1e-12)           # Eqs. 10-12
    np.testing.assert_allclose(p2[:, 1:], q2[:, 1:], atol=1e-12)  # Eqs. 14-15
    # Eq. 13 is exact when psi1 = psi2 and agrees to third order in phi2 otherwise
    lift = psi1 - psi2
    assert np.max(np.abs(p2[:, 0] - q2[:, 0])) <= 0.625 * (np.max(np.abs(phi2)) ** 3) * (1 / np.cos(lift.max()) ** 2)
    r1, r2 = bird.wing_joints_m(psi1, psi1, phi2, upper_arm_m=0.625, forearm_m=0.625)
    s1, s2 = paper_joints(psi1, psi1, phi2, 0.625, 0.625)
    np.testing.assert_allclose(r2, s2, atol=1e-12)


def test_rotation_built_wing_finite_rigid_and_continuous_at_vertical_segments():
    """Where Eqs. 12, 13, 15 take tan(90 deg) the rotation form stays finite, rigid and continuous."""
    psi1 = np.deg2rad(np.array([90.0, -90.0, 90.0, 45.0]))
    psi2 = np.deg2rad(np.array([0.0, 0.0, 180.0, -45.0]))  # upper arm, then forearm, vertical
    phi2 = np.deg2rad(np.array([30.0, -10.0, 20.0, 15.0]))
    p1, p2 = bird.wing_joints_m(psi1, psi2, phi2, upper_arm_m=0.5, forearm_m=0.4)
    assert np.all(np.isfinite(p1)) and np.all(np.isfinite(p2))
    np.testing.assert_allclose(np.linalg.norm(p1, axis=-1), 0.5, rtol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(p2 - p1, axis=-1), 0.4, rtol=1e-14)
    np.testing.assert_allclose(p1[0], [0.0, 0.0, 0.5], atol=1e-15)
    eps = np.deg2rad(1e-6)
    q1, q2 = bird.wing_joints_m(psi1 - eps, psi2, phi2, upper_arm_m=0.5, forearm_m=0.4)
    np.testing.assert_allclose(q2, p2, atol=1e-7)


def test_a2_is_its_own_parameter():
    psi1, psi2, _ = bird.flap_angles_rad(np.array([0.0]), wingbeat_hz=1, a1_deg=40, a2_deg=10, psi10_deg=0,
                                         psi20_deg=0, c2_deg=0, phi20_deg=0)
    assert np.rad2deg(psi1[0]) == pytest.approx(40) and np.rad2deg(psi2[0]) == pytest.approx(10)


def test_tilt_error_of_blade_length():
    """r from Eq. 6 read at beta for a disc at beta + tau is off by cos(beta + tau) / cos(beta) - 1 (~ tan(beta) tau):
    5 deg of tilt costs 0.38 % edge-on, 3.6 % at 20 deg, 8.5 % at 43 deg (the tilt away from edge-on, the larger)."""
    assert rotor.tilt_error(0.0, (-5.0, 5.0)) == pytest.approx(1 - np.cos(np.deg2rad(5.0)))
    assert rotor.tilt_error(20.0, (-5.0, 5.0)) == pytest.approx(1 - np.cos(np.deg2rad(25.0)) / np.cos(np.deg2rad(20.0)))
    assert rotor.tilt_error(43.0, -5.0) == pytest.approx(np.cos(np.deg2rad(38.0)) / np.cos(np.deg2rad(43.0)) - 1)
    assert rotor.tilt_error(43.0, (-5.0, 5.0)) == pytest.approx(0.0852, abs=5e-4)
    assert rotor.tilt_error(43.0, (-0.1, 0.1)) == pytest.approx(np.tan(np.deg2rad(43.0)) * np.deg2rad(0.1), rel=0.01)
