"""Features of one target's slow-time echo, each with a reason when it cannot be measured.

Conventions: Doppler in Hz with the paper's sign (approaching positive); velocities in m/s,
positive receding; every inversion uses :mod:`mdpipe.physics`, the functions the simulator uses.
"""

from dataclasses import dataclass, field

import numpy as np

from mdpipe.physics import rotor
from mdpipe.physics.radar import range_rate_from_doppler_mps
from mdpipe.process import doppler, spectral
from mdpipe.process.flashes import flash_period
from mdpipe.process.periodicity import find_period
from mdpipe.process.wingbeat import MAX_WINGBEAT_HZ, MIN_WINGBEAT_HZ, wingbeat

BODY_LINE_DB = 6.0           # a body line stands this far above the next line of its frame
BODY_FRAME_S = 0.032
MIN_REV_PER_S, MAX_REV_PER_S = 10.0, 500.0
MAX_ELEVATION_DEG = 80.0     # beyond it Eq. 6 divides by cos(beta) < 0.17: r is not estimable
FLASHES_PER_WINDOW = 1.5     # flash main lobes the edge window must hold: Gamma >= 24 for N = 2 (config 4: 26.7)
MIN_PERIODICITY = 0.2        # wingbeat autocorrelation prominence needed
MIN_ROTOR_PERIODICITY = 0.6  # a rotor's echo repeats almost exactly (measured 0.93-0.95; a gull's best: 0.40)
HIGHPASS_SHARE = 0.25        # body removal for unaliased echoes: cut below this share of the band's half-width
ALIAS_CHECK_CHIRPS = 64      # window of the spectrogram that tells whether the brightest frames fill the span


FEATURE_KEYS = ("snr_db", "doppler_bw_hz", "doppler_bw_mps", "doppler_low_hz", "doppler_high_hz",
                "doppler_bw_spectrogram_hz", "chopping_freq_hz", "rotation_rate_hz", "rotation_period_s",
                "flash_period_s", "blade_length_m", "tip_doppler_hz", "body_doppler_hz", "body_velocity_mps",
                "wingbeat_freq_hz", "wingbeat_period_s", "micro_doppler_halfwidth_mps", "aliased",
                "stft_window_s", "stft_hop_s")


@dataclass
class TargetAnalysis:
    """Everything measured on one target: the feature row and the spectra the figures show."""

    row: dict
    spectrum: doppler.PowerSpectrum
    spectrogram: doppler.Spectrogram
    paper_extent_hz: tuple = None
    flash_edges_hz: tuple = None
    notes: list = field(default_factory=list)


def body_line(signal, *, prf_hz):
    """Body Doppler at every chirp when a body line stands out, and its median prominence (dB).

    Per 32 ms frame the strongest line must stand ``BODY_LINE_DB`` above the strongest line more
    than two bins away; otherwise (rotating parts only, or phase-locked rotors whose interference
    skews the spectrum) there is no body line and the track is None.
    """
    frame_s = min(BODY_FRAME_S, len(signal) / prf_hz)
    spec = doppler.spectrogram(signal, prf_hz=prf_hz, window_s=frame_s, hop_s=frame_s / 4)
    power = spec.power
    peak = np.argmax(power, axis=0)
    masked = power.copy()
    for offset in range(-2, 3):
        masked[np.clip(peak + offset, 0, len(spec.f_hz) - 1), np.arange(power.shape[1])] = 0.0
    ratio_db = 10 * np.log10(power.max(axis=0) / np.maximum(masked.max(axis=0), np.finfo(float).tiny))
    prominence = float(np.median(ratio_db))
    if prominence < BODY_LINE_DB:
        return None, prominence
    return doppler.peak_track_hz(spec, n_chirps=len(signal), prf_hz=prf_hz), prominence


def highpass(signal, *, prf_hz, cutoff_hz):
    """Remove everything within +-cutoff_hz of 0 Hz (FFT mask): the demodulated body and its wander."""
    spectrum = np.fft.fft(signal)
    spectrum[np.abs(np.fft.fftfreq(len(signal), 1.0 / prf_hz)) < cutoff_hz] = 0.0
    return np.fft.ifft(spectrum)


def difference(signal):
    """First difference ``x[m] - x[m-1]``: a high-pass of response ``|2 sin(pi f / PRF)|``.

    After demodulation the body sits near 0 Hz, with whatever slow wander the track left; the
    difference suppresses it by ``(2 pi f_wander / PRF)^2`` in power while an aliased flash, broadband
    against the PRF, passes; no cutoff has to be read from a band that aliasing has hidden.
    :func:`mdpipe.process.spectral.flash_edges` undoes the response.
    """
    return np.diff(signal, prepend=signal[:1])


def display_window_s(row, params):
    """Spectrogram window and hop: given, or from the physics of what was found."""
    if params.stft_window_s is not None:
        window = params.stft_window_s
    elif row["chopping_freq_hz"] is not None:
        window = 0.25 / row["chopping_freq_hz"]  # resolves the flashes
    elif row["wingbeat_freq_hz"] is not None:
        window = min(0.064, 0.2 / row["wingbeat_freq_hz"])  # ~15 Hz resolution, 5 frames a wingbeat
    else:
        window = 0.032
    hop = params.stft_hop_s if params.stft_hop_s is not None else window / 4
    return window, hop


def display_adjustments(params, shown, *, prf_hz, dwell_s):
    """A note for each spectrogram setting the user gave that ``shown`` (:class:`doppler.Spectrogram`) could not
    take as asked: beyond the rounding to whole chirps, a window outside 8 chirps to half the dwell, a hop
    under one chirp (none is clamped silently)."""
    notes = []
    for name, asked, used in (("window", params.stft_window_s, shown.window_s), ("hop", params.stft_hop_s, shown.hop_s)):
        if asked is not None and abs(used - asked) > 0.5 / prf_hz:
            notes.append(f"spectrogram {name} {asked:g} s asked, {used:.4g} s used (the window spans 8 chirps to "
                         f"half the dwell of {dwell_s:.4g} s, the hop at least one chirp of {1 / prf_hz:.4g} s)")
    return notes


def _speed_mps(doppler_hz_, wavelength_m):
    return float(-range_rate_from_doppler_mps(doppler_hz_, wavelength_m=wavelength_m))


def _mark_aliased(row, notes, reason, *, prf_hz, wavelength_m):
    """Withhold what aliasing makes unmeasurable, and say why."""
    row["doppler_bw_hz"] = row["doppler_bw_mps"] = row["doppler_low_hz"] = row["doppler_high_hz"] = None
    row["micro_doppler_halfwidth_mps"] = _speed_mps(prf_hz / 2, wavelength_m)
    notes.append(f"Doppler bandwidth and blade length not estimable: aliased ({reason})")


def _body_motion(s, *, prf_hz, wavelength_m, row, notes):
    """Body Doppler and velocity when a body line exists; returns the echo demodulated by it (or as it is)."""
    track, prominence = body_line(s, prf_hz=prf_hz)
    if track is None:
        notes.append(f"body velocity not estimable: no body line stands out of the micro-Doppler "
                     f"({prominence:.1f} dB < {BODY_LINE_DB:.0f} dB above the next line)")
        return s
    row["body_doppler_hz"] = float(np.mean(track))
    row["body_velocity_mps"] = float(range_rate_from_doppler_mps(row["body_doppler_hz"], wavelength_m=wavelength_m))
    return doppler.demodulate(s, track, prf_hz=prf_hz)


def _doppler_band(s, demodulated, *, prf_hz, wavelength_m, noise_power, params, row, notes):
    """Occupied band, aliasing, and the paper's bandwidth. Returns (spectrum, extent, aliased, half-width)."""
    plain = doppler.power_spectrum(s, prf_hz=prf_hz)
    compensated = doppler.power_spectrum(demodulated, prf_hz=prf_hz)
    band = spectral.occupied_band(compensated, doppler.noise_level_per_bin(noise_power, len(s)),
                                  smooth_hz=max(prf_hz / 200, 4 * compensated.resolution_hz))
    extent = spectral.paper_extent(plain, threshold_db=params.threshold_db)
    half_width_hz = max(abs(band.low_hz), abs(band.high_hz), 0.0)
    if np.isfinite(half_width_hz):
        row["micro_doppler_halfwidth_mps"] = _speed_mps(half_width_hz, wavelength_m)
    if extent is None:
        notes.append(f"Doppler bandwidth not estimable: nothing {params.threshold_db:g} dB above the spectrum's mean")
    else:
        row["doppler_low_hz"], row["doppler_high_hz"] = extent
        row["doppler_bw_hz"] = extent[1] - extent[0]
        row["doppler_bw_mps"] = float(row["doppler_bw_hz"] * wavelength_m / 2)
    reason = band.reason if band.aliased else None
    if reason is None:
        strobe = spectral.flash_edges(difference(demodulated), prf_hz=prf_hz, window_s=ALIAS_CHECK_CHIRPS / prf_hz,
                                      noise_power=noise_power, differenced=True)
        if strobe.fills_span:
            reason = (f"the brightest frames fill the span 1/Tp = {prf_hz:.0f} Hz in {strobe.n_filled} of "
                      f"{strobe.n_frames}")
    if reason is not None:
        _mark_aliased(row, notes, reason, prf_hz=prf_hz, wavelength_m=wavelength_m)
        half_width_hz = prf_hz / 2
    return plain, extent, reason is not None, half_width_hz


def _rotation(demodulated, *, aliased, half_width_hz, prf_hz, noise_power, n_blades, dwell_s, notes):
    """Rotation rate (rev/s) from the blade flashes, or None with the reason in ``notes``.

    A flash is about as long as the inverse of its Doppler width, so flashes are shorter than a
    chirp interval exactly when the micro-Doppler aliases. Unaliased (well-sampled flashes): the
    body-free echo repeats every 1/(N f_rot) for even and odd N. Aliased (stroboscopic flashes):
    flash timing on the first difference of the echo.
    """
    max_period = 1.0 / (rotor.flashes_per_revolution(n_blades) * MIN_REV_PER_S)
    if aliased:
        found = flash_period(difference(demodulated), prf_hz=prf_hz,
                             min_period_s=1.0 / (rotor.flashes_per_revolution(n_blades) * MAX_REV_PER_S),
                             max_period_s=max_period, noise_power=2 * noise_power)  # a difference doubles noise
        if found is not None and found.ambiguous:
            notes.append(f"rotation not estimable: the flash times fit {found.period_s * 1e3:.3g} ms and, by their "
                         f"pairs, {found.period_s * 1e3 / found.ambiguous:.3g} ms (flashes shorter than a chirp are "
                         f"sampled stroboscopically; a longer dwell or a higher PRF tells them apart)")
            return None
        rate = None if found is None else rotor.rotation_rate_from_flash_period_hz(found.period_s, n_blades=n_blades)
    else:
        micro = highpass(demodulated, prf_hz=prf_hz, cutoff_hz=HIGHPASS_SHARE * half_width_hz)
        found = find_period(micro, sample_rate_hz=prf_hz, min_period_s=1.0 / (n_blades * MAX_REV_PER_S),
                            max_period_s=1.0 / (n_blades * MIN_REV_PER_S))
        if found is not None and found.strength < MIN_ROTOR_PERIODICITY:
            found = None
        rate = None if found is None else rotor.rotation_rate_from_chopping_hz(1.0 / found.period_s, n_blades=n_blades)
    if rate is None:
        notes.append(f"rotation not estimable: dwell {dwell_s:.3g} s is shorter than two flash periods of the slowest "
                     f"rotor searched ({2 * max_period:.3g} s)" if dwell_s < 2 * max_period
                     else "no periodic blade flashes")
        return None
    return float(rate)


def _blade_length(demodulated, *, rate_hz, prf_hz, wavelength_m, noise_power, params, row, notes):
    """Tip Doppler from the flash edges, and r by inverting Eq. 6. Returns the edges (or None).

    The edges are those of a flash's rectangular spectrum only when the window holds the whole
    flash. A broadside blade's sinc lasts ``2 / f_tip`` (main lobe); the window is
    ``w / (N f_rot)``; their ratio is ``w Gamma / (2 N)`` with ``Gamma = f_tip / f_rot``. Below
    ``FLASHES_PER_WINDOW`` main lobes r is not reported.
    """
    edges = spectral.flash_edges(demodulated, prf_hz=prf_hz, window_s=params.edge_window_periods / row["chopping_freq_hz"],
                                 noise_power=noise_power, hop_fraction=params.edge_hop_fraction)
    if edges.low_hz is None:
        notes.append("blade length not estimable: no flash frame with both Doppler edges inside the span")
        return None
    bandwidth = edges.high_hz - edges.low_hz
    row["doppler_bw_spectrogram_hz"] = bandwidth
    row["tip_doppler_hz"] = bandwidth / 2
    gamma = bandwidth / 2 / rate_hz
    min_gamma = FLASHES_PER_WINDOW * 2 * params.n_blades / params.edge_window_periods
    if gamma < min_gamma:
        notes.append(f"blade length not estimable: the tips span {gamma:.1f} rotation harmonics (< {min_gamma:.0f}); "
                     "a flash that long does not fit the analysis window and its Doppler edges blur")
    elif abs(params.elevation_deg) > MAX_ELEVATION_DEG:
        notes.append(f"blade length not estimable: elevation {params.elevation_deg:g} deg (Eq. 6 divides by "
                     f"cos(beta) = {np.cos(np.deg2rad(params.elevation_deg)):.2f})")
    else:
        row["blade_length_m"] = float(rotor.blade_length_from_bandwidth_m(
            bandwidth, rotation_rate_hz=rate_hz, wavelength_m=wavelength_m, elevation_deg=params.elevation_deg))
    return edges.low_hz, edges.high_hz


def _wingbeat(demodulated, *, prf_hz, noise_power, dwell_s, row, notes):
    beat = wingbeat(demodulated, prf_hz=prf_hz, noise_power=noise_power)
    if beat is not None and beat.strength >= MIN_PERIODICITY and beat.repeats >= 2:
        row["wingbeat_period_s"] = beat.period_s
        row["wingbeat_freq_hz"] = 1.0 / beat.period_s
    else:
        notes.append(f"no wingbeat between {max(MIN_WINGBEAT_HZ, 2.0 / dwell_s):.2g} and {MAX_WINGBEAT_HZ:g} Hz "
                     f"(a dwell of {dwell_s:.3g} s holds two wingbeats only above {2.0 / dwell_s:.2g} Hz)")


def analyse_target(signal, *, prf_hz, wavelength_m, noise_power, params):
    """Measure every feature of one target's complex slow-time ``signal`` (channels combined).

    Parameters
    ----------
    signal : ndarray (n_chirps,) complex
    prf_hz, wavelength_m : float
    noise_power : float
        Noise power per chirp of ``signal`` (V^2).
    params : ProcessParams
    """
    notes = []
    dwell_s = len(signal) / prf_hz
    s = np.asarray(signal, dtype=np.complex128)
    s = s - s.mean()  # static clutter in this bin
    moving = float(np.mean(np.abs(s) ** 2))
    snr = (moving - noise_power) / noise_power if noise_power > 0 else np.inf
    row = dict.fromkeys(FEATURE_KEYS)
    row["snr_db"] = float(10 * np.log10(snr)) if snr > 0 else float("-inf")
    demodulated = _body_motion(s, prf_hz=prf_hz, wavelength_m=wavelength_m, row=row, notes=notes)
    plain, extent, aliased, half_width_hz = _doppler_band(
        s, demodulated, prf_hz=prf_hz, wavelength_m=wavelength_m, noise_power=noise_power, params=params,
        row=row, notes=notes)
    rate = _rotation(demodulated, aliased=aliased, half_width_hz=half_width_hz, prf_hz=prf_hz,
                     noise_power=noise_power, n_blades=params.n_blades, dwell_s=dwell_s, notes=notes)
    edges = None
    if rate is not None:
        row["rotation_rate_hz"] = rate
        row["rotation_period_s"] = 1.0 / rate
        row["flash_period_s"] = float(rotor.flash_period_s(rate, n_blades=params.n_blades))
        row["chopping_freq_hz"] = float(rotor.chopping_frequency_hz(rate, n_blades=params.n_blades))
        if not aliased:
            edges = _blade_length(demodulated, rate_hz=rate, prf_hz=prf_hz, wavelength_m=wavelength_m,
                                  noise_power=noise_power, params=params, row=row, notes=notes)
    else:  # blade flashes exclude a bird
        _wingbeat(demodulated, prf_hz=prf_hz, noise_power=noise_power, dwell_s=dwell_s, row=row, notes=notes)
    row["aliased"] = bool(aliased)
    window, hop = display_window_s(row, params)
    shown = doppler.spectrogram(s, prf_hz=prf_hz, window_s=window, hop_s=hop)
    row["stft_window_s"], row["stft_hop_s"] = shown.window_s, shown.hop_s
    notes.extend(display_adjustments(params, shown, prf_hz=prf_hz, dwell_s=dwell_s))
    return TargetAnalysis(row=row, spectrum=plain, spectrogram=shown, paper_extent_hz=extent,
                          flash_edges_hz=edges, notes=notes)
