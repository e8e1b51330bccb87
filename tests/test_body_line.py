"""A body line that does not stand 6 dB over the next line of its frames, but keeps to its track and moves as the
range track does, is the body's (:func:`mdpipe.process.features.body_motion`): a bird whose wings are about as
bright as its body."""

import numpy as np
import pytest

from mdpipe.process import features
from mdpipe.process.features import RangeTrack

PRF_HZ = 4000.0
WAVELENGTH_M = 0.0306   # X band
SPEED_MPS = 6.0         # approaching: the range falls 6 m/s, the Doppler +392 Hz
DWELL_S = 1.5


def bird(wing_amplitude, *, seed=0):
    """A body approaching at 6 m/s and one wing point ``wing_amplitude`` times as bright whose Doppler swings
    +-300 Hz about the body's at 8 Hz (it turns, and dwells in Doppler, twice a beat), 40 dB over the noise, less
    its mean."""
    t_s = np.arange(int(DWELL_S * PRF_HZ)) / PRF_HZ
    body_hz = 2 * SPEED_MPS / WAVELENGTH_M
    wing_phase = -300.0 / (2 * np.pi * 8.0) * np.cos(2 * np.pi * 8.0 * t_s)
    rng = np.random.default_rng(seed)
    signal = (np.exp(2j * np.pi * body_hz * t_s) + wing_amplitude * np.exp(2j * np.pi * (body_hz * t_s + wing_phase))
              + 0.01 * (rng.normal(size=len(t_s)) + 1j * rng.normal(size=len(t_s))))
    return signal - signal.mean()


def range_track(rate_mps):
    t_s = np.linspace(0.0, DWELL_S, 60)
    return RangeTrack(t_s=t_s, range_m=50.0 + rate_mps * t_s, bin_m=3.0)


def test_a_body_line_kept_to_its_track_and_followed_in_range_is_the_body():
    signal = bird(0.8)
    alone = features.body_motion(signal, prf_hz=PRF_HZ, wavelength_m=WAVELENGTH_M)
    assert alone.velocity.status == "no_body_line"  # under 6 dB over the wing's turns: not a line that stands out
    assert alone.track_hz is None
    body = features.body_motion(signal, prf_hz=PRF_HZ, wavelength_m=WAVELENGTH_M, track=range_track(-SPEED_MPS))
    assert body.velocity.status == "ok"
    assert body.velocity.value == pytest.approx(-SPEED_MPS, abs=0.05)
    assert np.median(body.track_hz) == pytest.approx(2 * SPEED_MPS / WAVELENGTH_M, abs=5.0)


@pytest.mark.parametrize("rate_mps", [0.0, SPEED_MPS])
def test_a_line_the_range_track_does_not_follow_is_no_body(rate_mps):
    """Still, or receding while the line says approaching: a steady line of another part (a rotor's comb line,
    its hub hovering) is not taken for the body."""
    body = features.body_motion(bird(0.8), prf_hz=PRF_HZ, wavelength_m=WAVELENGTH_M, track=range_track(rate_mps))
    assert body.velocity.status == "no_body_line"
    assert body.track_hz is None
    assert "the range track" in body.velocity.note


def test_wings_outshining_the_body_leave_no_body_line():
    """Wings 1.2 times as bright as the body win a third of the frames: no line kept to a track."""
    body = features.body_motion(bird(1.2), prf_hz=PRF_HZ, wavelength_m=WAVELENGTH_M, track=range_track(-SPEED_MPS))
    assert body.velocity.status == "no_body_line"
