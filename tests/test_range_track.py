"""The range track as the Doppler straightens it (:meth:`mdpipe.process.features.RangeTrack.straightened`) and the
alias of the body velocity it picks (:func:`mdpipe.process.features.dealias_velocity`)."""

import numpy as np
import pytest

from mdpipe.physics.radar import doppler_hz
from mdpipe.process.features import STRAIGHT_BINS, RangeTrack, dealias_velocity

WAVELENGTH_M = 0.0125   # K band
BIN_M = 1.5
T_S = 193e-6            # the sampled ramp: a Doppler f reads f T_s bins nearer


def passing(t_s, *, miss_m=11.5, speed_mps=11.7, closest_s=2.9):
    """Range and range rate of a point flying straight past at ``miss_m``, nearest at ``closest_s``."""
    along = speed_mps * (t_s - closest_s)
    range_m = np.hypot(miss_m, along)
    return range_m, speed_mps * along / range_m


def test_a_curved_track_less_its_coupling_and_bend_moves_at_the_mean_range_rate():
    """A goose passing 11.5 m from a K-band radar in 3.5 s: its range rate runs from -11.1 to +6.1 m/s, a curved track
    whose least-squares slope (-7.3 m/s) is no mean range rate (-6.4, the secant), 0.92 m/s off where the bins bound
    it to +-0.43; its Doppler, falling, reads the track up to 0.51 m nearer (a slope of -7.1 read). Straightened by the
    Doppler (one span off, 25.8 m/s: its shape is all that is used), the track lies on a line at the mean range rate,
    within 1e-3 bin, and picks the alias."""
    t_s = np.linspace(0.0, 3.5, 256)
    true_m, rate_mps = passing(t_s)
    f_hz = doppler_hz(rate_mps, wavelength_m=WAVELENGTH_M)
    observed = RangeTrack(t_s, true_m - f_hz * T_S * BIN_M, BIN_M, coupling_m_per_hz=T_S * BIN_M)
    mean_mps = (true_m[-1] - true_m[0]) / 3.5
    assert observed.range_rate_mps()[0] == pytest.approx(-7.1, abs=0.05)
    assert np.polyfit(t_s, true_m, 1)[0] - mean_mps < -2 * BIN_M / 3.5  # the curve alone fails the bins' bound
    span_hz = 2 * 25.8 / WAVELENGTH_M
    straight = observed.straightened(t_s, f_hz + span_hz, wavelength_m=WAVELENGTH_M)
    assert straight.bend_bins() < 1e-3
    assert straight.range_rate_mps()[0] == pytest.approx(np.mean(rate_mps), abs=0.01)
    velocity = dealias_velocity(float(np.mean(rate_mps)) + 25.8, span_mps=25.8, track=straight)
    assert velocity.status == "ok" and velocity.value == pytest.approx(mean_mps, abs=0.02)


def test_a_track_that_bends_off_the_doppler_gives_no_velocity():
    """The goose's range track lost half-way (it stays at 34 m from 1.5 s on while the Doppler says the goose flew
    on past the radar): straightened by the Doppler, which bends it by 5 bins, it still lies bins off a line. Range and
    Doppler follow different things: no alias is taken, whichever the track's rate would have picked."""
    t_s = np.linspace(0.0, 3.5, 256)
    true_m, rate_mps = passing(t_s)
    lost = RangeTrack(t_s, np.where(t_s < 1.5, true_m, np.interp(1.5, t_s, true_m)), BIN_M)
    straight = lost.straightened(t_s, doppler_hz(rate_mps, wavelength_m=WAVELENGTH_M), wavelength_m=WAVELENGTH_M)
    assert straight.doppler_bend_bins > 1.0 and straight.bend_bins() > STRAIGHT_BINS
    velocity = dealias_velocity(float(np.mean(rate_mps)), span_mps=25.8, track=straight)
    assert velocity.value is None and velocity.status == "velocity_ambiguous"
    assert "does not follow the Doppler" in velocity.note


def test_a_track_the_doppler_hardly_bends_keeps_its_own_scatter():
    """A hovering drone's range track scattering 0.3 bin rms about its place (the tracker on a weak echo) while its
    Doppler holds: the Doppler bends it by under a bin, the scatter is the track's own, and the rate read within the
    bins' bound takes the alias as before."""
    t_s = np.linspace(0.0, 3.5, 256)
    rng = np.random.default_rng(1)
    track = RangeTrack(t_s, 20.0 + 0.3 * BIN_M * rng.standard_normal(len(t_s)), BIN_M)
    straight = track.straightened(t_s, np.full(len(t_s), 2.0), wavelength_m=WAVELENGTH_M)
    assert straight.doppler_bend_bins < 1.0 and straight.bend_bins() > STRAIGHT_BINS
    velocity = dealias_velocity(-0.0125, span_mps=25.8, track=straight)
    assert velocity.status == "ok" and velocity.value == pytest.approx(-0.0125)
