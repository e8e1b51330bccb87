"""The blade flashes' Doppler edges (tip Doppler, Eq. 6): how many Doppler bins they need, and one flash per frame."""

import numpy as np
import pytest

from mdpipe.physics import rotor
from mdpipe.process import doppler, spectral

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


@pytest.mark.parametrize("bins, wide", [(3, 0.04), (4, 0.03)])
def test_edges_read_wide_where_the_tips_span_few_bins(bins, wide):
    """At 3-4 bins a side the blurred rectangle never reaches its plateau: the level read is low and the edges wide
    (+6.3 and +4.0 %), which is why r needs ``MIN_EDGE_BINS`` (8)."""
    assert tip_error(rotor_echo(), bins) > wide


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
