"""The line at 0 Hz that static-clutter removal leaves, and clutter it does not remove, are no micro-Doppler of a
body whose Doppler lies elsewhere (:func:`mdpipe.process.features.static_line`)."""

import numpy as np

from mdpipe.process import doppler, features

PRF_HZ = 4000.0
WAVELENGTH_M = 0.0306  # X band: +-900 Hz is +-13.8 m/s
NOISE_POWER = 1.0


def echo(doppler_hz, *, clutter=0.0, mean_removed=True, seed=0):
    """A body line of Doppler ``doppler_hz`` (per chirp), 60 dB over unit noise, a constant ``clutter``, less its
    mean (the static removal's mean chirp, which holds the body's own stay at 0 Hz)."""
    rng = np.random.default_rng(seed)
    phase = 2 * np.pi * np.cumsum(doppler_hz) / PRF_HZ
    noise = np.sqrt(NOISE_POWER / 2) * (rng.normal(size=len(phase)) + 1j * rng.normal(size=len(phase)))
    signal = 1000.0 * np.exp(1j * phase) + clutter + noise
    return signal - signal.mean() if mean_removed else signal


def flyby_hz(dwell_s=3.0):
    """A bird flying past: its Doppler sweeps from +900 to -900 Hz, through 0 Hz at 1.7 s."""
    t_s = np.arange(int(dwell_s * PRF_HZ)) / PRF_HZ
    return 900.0 * np.tanh((1.7 - t_s) / 0.3)


def half_width_hz(signal, demodulated):
    return features.doppler_band(signal, demodulated, prf_hz=PRF_HZ, wavelength_m=WAVELENGTH_M,
                                 noise_power=NOISE_POWER).half_width_hz


def test_a_flyby_leaves_no_mirrored_body_line():
    """The body dwells at 0 Hz as it passes; the mean removed takes that with it, and the line left at 0 Hz,
    demodulated by the body, sweeps -+900 Hz: without the line's removal the band of a body alone is 900 Hz
    wide each side (a pigeon read 12.4 m/s, a drone's spread). With it, the band is that of the same body with
    no mean removed (the body line's skirts, where its track is not exact)."""
    signal = echo(flyby_hz())
    body = features.body_motion(signal, prf_hz=PRF_HZ, wavelength_m=WAVELENGTH_M)
    assert np.max(np.abs(body.track_hz - flyby_hz())) < 20.0
    mirrored = doppler.demodulate(signal, body.track_hz, prf_hz=PRF_HZ)
    assert half_width_hz(signal, mirrored) > 800.0
    untouched = echo(flyby_hz(), mean_removed=False)
    alone = features.body_motion(untouched, prf_hz=PRF_HZ, wavelength_m=WAVELENGTH_M)
    assert half_width_hz(signal, body.demodulated) <= 1.1 * half_width_hz(untouched, alone.demodulated)


def test_clutter_beside_a_moving_body_is_removed():
    """Clutter that the mean did not remove (it changes along a track that crosses range bins: here from +30 to
    -30 over the dwell), 30 dB under a body at a steady 300 Hz: its line, at -300 Hz in the body-demodulated
    echo, loses over 99 % of its power."""
    n = int(2.0 * PRF_HZ)
    clutter = 30.0 * np.cos(np.pi * np.arange(n) / n)
    signal = echo(np.full(n, 300.0), clutter=clutter)
    body = features.body_motion(signal, prf_hz=PRF_HZ, wavelength_m=WAVELENGTH_M)
    cleaned = doppler.power_spectrum(body.demodulated, prf_hz=PRF_HZ)
    kept = doppler.power_spectrum(doppler.demodulate(signal, body.track_hz, prf_hz=PRF_HZ), prf_hz=PRF_HZ)
    at_clutter = np.abs(cleaned.f_hz + 300.0) < 5.0
    assert kept.power[at_clutter].sum() > 100 * cleaned.power[at_clutter].sum()


def test_the_line_of_a_hovering_body_is_the_body():
    """A body at 0 Hz throughout is the line at 0 Hz: nothing is taken for clutter."""
    signal = echo(np.zeros(8000)) + 50.0
    body_hz = np.zeros(8000)
    assert np.all(features.static_line(signal, body_hz, prf_hz=PRF_HZ) == 0)


def test_the_line_is_interpolated_where_the_body_crosses_it():
    """Where the body's Doppler lies within the smoothing's pass band over its window, the smoothed echo holds the
    body: the line there is the one either side (the clutter less the mean removed with it, which holds the
    body's stay at 0 Hz), to the smoothing's leak of the body beside it, ``(pi STATIC_CLEAR_NULLS)^-2`` of it."""
    body_hz = np.linspace(900.0, -900.0, 12000)
    signal = echo(body_hz, clutter=20.0)
    line = features.static_line(signal, body_hz, prf_hz=PRF_HZ)
    expected = -1000.0 * np.mean(np.exp(2j * np.pi * np.cumsum(body_hz) / PRF_HZ))
    assert abs(expected) > 10.0
    assert np.max(np.abs(line - expected)) < 1000.0 / (np.pi * features.STATIC_CLEAR_NULLS) ** 2
