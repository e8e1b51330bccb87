"""The blade flashes' Doppler edges (tip Doppler, Eq. 6): how many Doppler bins they need, and one flash per frame."""

import numpy as np
import pytest

from mdpipe.params import ProcessParams
from mdpipe.physics import rotor
from mdpipe.process import doppler, features, spectral
from mdpipe.process.validity import Measured

WAVELENGTH_M, BETA_DEG, PRF_HZ, RATE_HZ, BLADE_M = 0.0306, 8.0, 60000.0, 60.0, 0.15
T_S = np.arange(30000) / PRF_HZ


def rotor_echo(phase_rad=0.3, rate_hz=RATE_HZ):
    """One 2-blade rotor of uniform 15 cm blades (root 1 cm), X band: tip Doppler 3.66 kHz, Gamma = 61."""
    theta = rotor.blade_angles_rad(T_S, rotation_rate_hz=rate_hz, n_blades=2, phase0_rad=phase_rad)
    return rotor.blade_echoes(theta, blade_length_m=BLADE_M, wavelength_m=WAVELENGTH_M, elevation_deg=BETA_DEG,
                              root_m=0.01).sum(axis=-1)


TIP_HZ = float(rotor.tip_doppler_hz(RATE_HZ, blade_length_m=BLADE_M, wavelength_m=WAVELENGTH_M,
                                    elevation_deg=BETA_DEG))


def tip_error(echo, bins):
    """Relative error of the flash edges' half distance against the tip Doppler, in frames where the tips span
    ``bins`` Doppler bins a side (no noise)."""
    edges = spectral.flash_edges(echo, prf_hz=PRF_HZ, window_s=bins / TIP_HZ,
                                 noise_power=1e-12 * np.mean(np.abs(echo) ** 2))
    return (edges.high_hz - edges.low_hz) / 2 / TIP_HZ - 1


@pytest.mark.parametrize("bins", [8, 10, 12])
def test_edges_on_the_tip_doppler_where_the_tips_span_eight_bins(bins):
    """The half-amplitude edge of a broadside blade's rectangular spectrum lies on the tip Doppler where the frame's
    Hann main lobe (+-2 bins) blurs a small part of it: measured -0.25, -0.56, -0.81 % at 8, 10, 12 bins."""
    assert abs(tip_error(rotor_echo(), bins)) < 0.01


@pytest.mark.parametrize("bins, off", [(3, 0.04), (4, 0.03)])
def test_edges_off_where_the_tips_span_few_bins(bins, off):
    """At 3-4 bins a side the blurred rectangle never reaches its plateau: the level read is low and the edges wide
    (+6.3 and +4.0 %), which is why r needs ``MIN_EDGE_BINS`` (8)."""
    assert abs(tip_error(rotor_echo(), bins)) > off


def flash_frame(echo, bins=10.0):
    """The spectrogram column (noise-free power) of the strongest frame of ``echo`` in frames where the tips span
    ``bins`` bins a side, zero-padded as the edges are read, and its edges."""
    spec = doppler.spectrogram(echo, prf_hz=PRF_HZ, window_s=bins / TIP_HZ, hop_s=bins / TIP_HZ / 8,
                               pad=spectral.EDGE_PAD)
    column = spec.power[:, int(np.argmax(spec.power.sum(axis=0)))]
    return column, spec.f_hz


def test_one_flash_in_a_frame_has_a_smooth_plateau():
    column, f_hz = flash_frame(rotor_echo())
    assert spectral.plateau_ripple(column, f_hz, TIP_HZ) < 0.05
    assert spectral.plateau_ripple(column, f_hz, -TIP_HZ) < 0.05


def test_two_flashes_in_a_frame_beat():
    """A second rotor at the same rate flashing 0.6 ms (0.22 of the 2.7 ms frame) later at half the amplitude: the two
    flashes' spectra beat in fringes 1.7 kHz apart, and the plateau ripples past ``MAX_RIPPLE`` (0.20-0.23, either
    order). Fringes wider than the plateau's inner part are not seen so: 0.4 ms apart, 2.5 kHz, 0.13-0.14."""
    second = 0.5 * rotor_echo(phase_rad=0.3 - 2 * np.pi * RATE_HZ * 0.6e-3)
    column, f_hz = flash_frame(rotor_echo() + second)
    assert spectral.plateau_ripple(column, f_hz, TIP_HZ) > spectral.MAX_RIPPLE
    assert spectral.plateau_ripple(column, f_hz, -TIP_HZ) > spectral.MAX_RIPPLE


def blade_length_of(echo, *, rate_hz, tip_hz, noise_power):
    """``features.blade_length`` of a 2-blade rotor's echo, its rate known (beta 8 deg given)."""
    return features.blade_length(echo, rate=Measured(rate_hz), chopping_hz=2 * rate_hz, aliased=False,
                                 half_width_hz=tip_hz, prf_hz=PRF_HZ, wavelength_m=WAVELENGTH_M,
                                 noise_power=noise_power, params=ProcessParams(elevation_deg=BETA_DEG), n_blades=2)


def tapered_echo(blade_m, snr_db=25.0, tip_reflectivity=0.3):
    """One 2-blade rotor of tapered blades (tips ``tip_reflectivity`` of the root), 60 rev/s, with noise ``snr_db``
    under the echo; (echo, noise power)."""
    theta = rotor.blade_angles_rad(T_S, rotation_rate_hz=RATE_HZ, n_blades=2, phase0_rad=0.3)
    echo = rotor.blade_echoes(theta, blade_length_m=blade_m, wavelength_m=WAVELENGTH_M, elevation_deg=BETA_DEG,
                              root_m=0.01, profile="tapered", tip_reflectivity=tip_reflectivity).sum(axis=-1)
    noise_power = np.mean(np.abs(echo) ** 2) / 10 ** (snr_db / 10)
    rng = np.random.default_rng(5)
    noise = np.sqrt(noise_power / 2) * (rng.standard_normal(len(echo)) + 1j * rng.standard_normal(len(echo)))
    return echo + noise, noise_power


@pytest.mark.parametrize("gamma", [18.0, 20.0])
def test_a_quarter_turn_bounds_the_frame(gamma):
    """Tapered blades at Gamma 18-20: their tips span 8 bins a side only in frames over a quarter turn long, where
    the tips' Doppler falls to cos(45 deg) and below at the frame's ends (read so, -5 to -8 %). r is withheld."""
    blade_m = gamma * WAVELENGTH_M / (4 * np.pi * np.cos(np.deg2rad(BETA_DEG)))
    echo, noise_power = tapered_echo(blade_m)
    _, length, _ = blade_length_of(echo, rate_hz=RATE_HZ, tip_hz=gamma * RATE_HZ, noise_power=noise_power)
    assert length.value is None and length.status == "few_harmonics"


def test_tapered_blades_read_in_a_frame_lengthened_to_ten_bins():
    """Tapered blades at Gamma 41: a quarter chopping period spans 5.1 bins of their tips (read -12 % there); the
    frame lengthened to 10 bins reads r within 1 %."""
    blade_m = 41.0 * WAVELENGTH_M / (4 * np.pi * np.cos(np.deg2rad(BETA_DEG)))
    echo, noise_power = tapered_echo(blade_m)
    _, length, _ = blade_length_of(echo, rate_hz=RATE_HZ, tip_hz=41.0 * RATE_HZ, noise_power=noise_power)
    assert length.status == "ok" and length.value == pytest.approx(blade_m, rel=0.01)


@pytest.mark.parametrize("tip_reflectivity", [2.0, 3.0])
def test_blades_brighter_at_their_tips(tip_reflectivity):
    """Tips 2-3 times as bright as the root: the flash's plateau rises towards the edges, and half the plateau's
    median amplitude lies outside the tips (+2.7 and +3.9 % read so at Gamma 61). Half the amplitude the plateau's
    trend reaches at the edge is the tip's: r within 1 %."""
    echo, noise_power = tapered_echo(BLADE_M, tip_reflectivity=tip_reflectivity)
    _, length, _ = blade_length_of(echo, rate_hz=RATE_HZ, tip_hz=TIP_HZ, noise_power=noise_power)
    assert length.status == "ok" and length.value == pytest.approx(BLADE_M, rel=0.01)


def points_echo(*, rates_hz, phases_rad, blade_m, wavelength_m, points, snr_db=15.0):
    """2-blade rotors of ``points`` equal point scatterers a blade (the paper's Eq. 1, root 1 cm) at ``rates_hz``, with
    noise ``snr_db`` under the echo; (echo, noise power)."""
    echo = 0
    for rate_hz, phase_rad in zip(rates_hz, phases_rad):
        theta = rotor.blade_angles_rad(T_S, rotation_rate_hz=rate_hz, n_blades=2, phase0_rad=phase_rad)
        echo = echo + rotor.blade_echoes(theta, blade_length_m=blade_m, wavelength_m=wavelength_m,
                                         elevation_deg=BETA_DEG, root_m=0.01, profile="points",
                                         points_per_blade=points).sum(axis=-1)
    noise_power = np.mean(np.abs(echo) ** 2) / 10 ** (snr_db / 10)
    rng = np.random.default_rng(3)
    return echo + np.sqrt(noise_power / 2) * (rng.standard_normal(len(echo)) + 1j * rng.standard_normal(len(echo))), \
        noise_power


def test_grating_flashes_of_point_blades_are_not_read_as_the_tips():
    """16 points on a 30 cm blade at X band lie 18.8 mm apart, over lambda / 2 (15.3 mm): besides broadside, each blade
    flashes in grating lobes at cos(theta) = lambda / (2 d) = 0.82, whose Doppler reaches about 0.53 of the tips'.
    Those flashes come twice as often and outshine the broadside ones; the median of every flash's edges read the tip
    Doppler -47 % (r was withheld only because the micro-Doppler band reached past it). The widest edges are the
    broadside ones: r within 1 %."""
    echo, noise_power = points_echo(rates_hz=(RATE_HZ,), phases_rad=(0.3,), blade_m=0.3, wavelength_m=WAVELENGTH_M,
                                    points=16)
    tip_hz = float(rotor.tip_doppler_hz(RATE_HZ, blade_length_m=0.3, wavelength_m=WAVELENGTH_M, elevation_deg=BETA_DEG))
    _, length, _ = blade_length_of(echo, rate_hz=RATE_HZ, tip_hz=tip_hz, noise_power=noise_power)
    assert length.status == "ok" and length.value == pytest.approx(0.3, rel=0.01)


def test_broadside_flashes_of_rotors_apart_are_found_among_beating_frames():
    """Four rotors of 16-point 14 cm blades at K band (points 0.7 lambda apart, grating flashes to 0.7 of the tips'
    Doppler) at rates 59.1-61.2 rev/s: their broadside flashes mostly beat with the others' grating flashes, which
    stand alone and smooth. The widest edges, found among all frames, pick the smooth broadside ones: the tip Doppler
    of the mean rate within 2 % (the median of the smooth frames' edges read -36 %)."""
    rates_hz = (60.0, 61.2, 59.1, 60.7)
    echo, noise_power = points_echo(rates_hz=rates_hz, phases_rad=(0.3, 1.1, 2.0, 2.9), blade_m=0.14,
                                    wavelength_m=0.0125, points=16)
    tip_hz = float(rotor.tip_doppler_hz(np.mean(rates_hz), blade_length_m=0.14, wavelength_m=0.0125,
                                        elevation_deg=BETA_DEG))
    edges = spectral.flash_edges(echo, prf_hz=PRF_HZ, window_s=10 / tip_hz, noise_power=noise_power)
    assert (edges.high_hz - edges.low_hz) / 2 == pytest.approx(tip_hz, rel=0.02)


def test_broadside_keeps_the_smooth_edges_near_the_widest():
    """Three smooth broadside edges near 1 kHz, six smooth grating ones at 0.53 kHz and one beating frame at 1.05 kHz:
    the broadside ones stand."""
    edges = [(1000.0, True), (990.0, True), (1010.0, True), (1050.0, False)] + [(530.0, True)] * 6
    assert sorted(spectral.broadside(edges)) == [990.0, 1000.0, 1010.0]


def test_frames_nowhere_over_the_noise_read_no_edges():
    """Noise 60 dB under the noise level given: after the noise's expectation is taken out every frame is empty,
    and the flash frames give no plateau to read edges on (no edges, no error)."""
    rng = np.random.default_rng(0)
    noise = rng.standard_normal(4000) + 1j * rng.standard_normal(4000)
    edges = spectral.flash_edges(noise, prf_hz=10000.0, window_s=0.004, noise_power=1e6)
    assert edges.low_hz is None and edges.high_hz is None and edges.n_frames == 0
