"""What each drawn target lets a measurement know, and how a feature row measured it.

Estimability is decided from the physics of the scene (one function per feature, each rule in its
docstring), never from what the pipeline did. A row's value is

* REPORTED when it is not null;
* CONFIDENT when reported and its ``<feature>_status`` is ``ok`` (a row without a status column
  states no caveat, so every reported value is confident);
* CONFIDENTLY WRONG when confident and more than ``TOLERANCE`` off the truth (verdict ``wrong``), or
  confident where the truth says not estimable (verdict ``unwarranted``).

Verdicts: ``right`` and ``wrong`` (confident, estimable), ``unwarranted`` (confident, not estimable),
``withheld`` (reported with a caveat), ``missed`` (estimable, not reported), ``n/a`` (not estimable,
not claimed). Coverage = confident values / estimable cases.
"""

import dataclasses
from dataclasses import dataclass

import numpy as np

from mdpipe.evaluate import range_share
from mdpipe.physics import rotor
from mdpipe.process.doppler import power_spectrum
from mdpipe.simulate.targets import module_of, target_echo
from mdpipe.simulate.targets.common import carrier

FEATURES = ("chopping_freq_hz", "rotation_rate_hz", "blade_length_m", "wingbeat_freq_hz", "body_velocity_mps")
TOLERANCE = 0.10             # a confident value more than 10 % off is wrong
VELOCITY_FLOOR_MPS = 1.0     # body velocity error is relative to max(|v|, 1 m/s): 0.1 m/s near hover
LINE_SNR_DB = 13.0           # a spectral line is detectable: Pfa 1e-5 per bin needs 10.6 dB, + ~2.5 dB for Pd 0.9
MIN_ROTATIONS = 3            # rotation: the dwell holds 3 turns of the slowest rotor
MIN_CHOP_ORDERS = 3          # rotation: the tips' band spans 3 chopping harmonics a side (a comb's least; face-on: 0)
MAX_BLADE_ELEVATION_DEG = 80.0
BLADE_TILT_TOLERANCE = 0.03  # blade length: the rotors' tilts move cos(beta) by at most this share
MIN_TIP_HARMONICS = 24       # blade length: the band +-f_tip spans 24 rotation harmonics
MIN_WINGBEATS = 2            # wingbeat: two beats in a row while flapping
STATIC_SHARE = 1e-3          # body velocity: a body whose echo the dwell's mean removal keeps less of is at rest
POWER_SAMPLES = 4096


@dataclass(frozen=True)
class Physics:
    """What the physics of one drawn target says, in the units its names carry.

    ``micro_line_snr_db`` is the SNR of one spectral line of the moving parts (blades, wings) after the
    range FFT (gain ``n_samples / 3``: a real IF's positive bin through a Hann window), coherent RX
    combining (``n_channels``) and the dwell (``n_chirps``): for rotors, the blades' power shared among the
    lines that fill their Doppler extent (see :func:`line_count`); for birds, the share of the wings' power in
    their strongest wingbeat line (:func:`wing_line_share`); scaled by ``micro_bin_share``, the share of
    their power the range FFT puts in the body's range bin, where the processing reads them (blade tips whose
    Doppler shifts their beat by bins, or flashes shorter than the ramp, spread over the range bins:
    :mod:`mdpipe.evaluate.range_share`); ``imbalance_line_db``, the strongest line
    that unequal blades add at a turn-rate order between the chopping lines, against those
    (:func:`imbalance_line_db`; -inf for equal blades). ``body_line_snr_db`` is the body
    line's SNR in the frames a track follows it with: a line sweeping B Hz over the dwell T stays in one
    bin of a frame sqrt(T / B) long (B T >= 1), whose SNR is the dwell's over sqrt(B T) (over the whole
    dwell its power spreads over B T bins); of the body's power only ``body_kept_share`` counts, what the
    removal of the dwell's mean (static clutter) keeps (:func:`kept_share`).
    """

    kind: str
    expected_class: str
    dwell_s: float
    prf_hz: float
    micro_line_snr_db: float = float("-inf")
    micro_bin_share: float = 1.0
    body_line_snr_db: float = float("-inf")
    rotor_rates_hz: tuple = ()
    rotor_elevations_deg: tuple = ()
    n_blades: int = 0
    blade_length_m: float = float("nan")
    elevation_deg: float = 0.0
    blades_given: bool = False
    elevation_given: bool = False
    imbalance_line_db: float = float("-inf")
    tip_doppler_hz: float = 0.0
    body_doppler_max_hz: float = 0.0
    body_kept_share: float = 1.0
    wingbeat_hz: float = float("nan")
    flap_run_s: float = 0.0
    has_body: bool = False
    body_velocity_mps: float = float("nan")
    velocity_span_mps: float = float("inf")
    range_bin_m: float = float("inf")

    @property
    def detectable(self):
        """The echo that tells the class stands ``LINE_SNR_DB`` above the noise: a drone's blade or a bird's
        wing lines (a body line alone does not tell a drone from a bird); any line of anything else."""
        if self.expected_class != "none":
            return self.micro_line_snr_db >= LINE_SNR_DB
        return max(self.micro_line_snr_db, self.body_line_snr_db) >= LINE_SNR_DB

    @property
    def chopping_freq_hz(self):
        """Mean chopping frequency ``N |f_rot|``, the truth of ``chopping_freq_hz`` (Hz)."""
        return self.n_blades * self.rotation_rate_hz if self.rotor_rates_hz else float("nan")

    @property
    def rotation_rate_hz(self):
        """Mean rotor rate, the truth of ``rotation_rate_hz`` (rev/s)."""
        return float(np.mean(self.rotor_rates_hz)) if self.rotor_rates_hz else float("nan")


def chopping_estimable(p):
    """Chopping frequency ``N f_rot``: as the rotation rate (:func:`rotation_estimable`), whatever the blade
    count. Returns ``(estimable, reason)``."""
    ok, reason = rotation_estimable(p)
    return (True, "") if reason == "blades_unknown" else (ok, reason)


def rotation_estimable(p):
    """Rotation rate: a drone whose blade flashes carry the rate unambiguously.

    All of: the blades' spectral lines stand ``LINE_SNR_DB`` above the noise (``micro_line_snr_db``);
    the dwell holds ``MIN_ROTATIONS`` turns of the slowest rotor; the tips' band ``+-f_tip`` (``cos beta``
    in it: near face-on the blades move across the line of sight) holds ``MIN_CHOP_ORDERS`` chopping
    harmonics a side, the least a comb is read from (2 blades of 12 cm at 80 rev/s: 1.3 at X band and
    87 deg, 8 at 94 GHz and 88 deg); the chopping frequency ``N f_rot`` of the fastest rotor is below
    PRF / 2 (else the line that gives the rate aliases); and the blade count is knowable: given to the
    processing, or told by the echo (unequal blades add lines at orders of ``f_rot``, the rate itself, which
    must stand ``LINE_SNR_DB`` out: 17.7 dB under the chopping lines for 2 blades 1.3x apart). Equal blades of
    an odd N flash twice per blade passage, one side of the Doppler span at a time: the echo tells that N is
    odd and the chopping frequency N f_rot, not whether N is 3 or 5, so not f_rot.
    Returns ``(estimable, reason)``, reason ``""`` when estimable.
    """
    if p.kind != "multirotor":
        return False, "not_a_drone"
    if p.micro_line_snr_db < LINE_SNR_DB:
        return False, "below_noise"
    if p.dwell_s * min(p.rotor_rates_hz) < MIN_ROTATIONS:
        return False, "dwell_short"
    if p.tip_doppler_hz < MIN_CHOP_ORDERS * p.chopping_freq_hz:
        return False, "few_lines"
    if rotor.chopping_frequency_hz(max(p.rotor_rates_hz), n_blades=p.n_blades) >= p.prf_hz / 2:
        return False, "chopping_aliased"
    if not (p.blades_given or p.micro_line_snr_db + p.imbalance_line_db >= LINE_SNR_DB):
        return False, "blades_unknown"
    return True, ""


def blade_length_estimable(p):
    """Blade length (Eq. 6 inverted): the tip Doppler is seen, resolved and its projection known.

    All of: rotation estimable; the tips' band (body Doppler plus ``f_tip``) inside +-PRF/2 (not
    aliased); ``|beta| <= MAX_BLADE_ELEVATION_DEG``; the band ``2 f_tip`` spans ``MIN_TIP_HARMONICS``
    rotation harmonics (else its edge is a handful of lines); beta given to the processing (Eq. 6 gives
    ``r cos beta``, not r: without beta, r is an assumption); and the rotors' tilts move ``cos beta`` by at
    most ``BLADE_TILT_TOLERANCE`` (the processing is given the drone's beta, not each disc's).
    """
    ok, reason = rotation_estimable(p)
    if not ok:
        return False, reason
    if p.body_doppler_max_hz + p.tip_doppler_hz >= p.prf_hz / 2:
        return False, "aliased"
    if abs(p.elevation_deg) > MAX_BLADE_ELEVATION_DEG:
        return False, "elevation"
    if 2 * p.tip_doppler_hz / max(p.rotor_rates_hz) < MIN_TIP_HARMONICS:
        return False, "few_harmonics"
    if not p.elevation_given:
        return False, "elevation_unknown"
    tilts_deg = np.array(p.rotor_elevations_deg or (p.elevation_deg,)) - p.elevation_deg
    if rotor.tilt_error(p.elevation_deg, tilts_deg) > BLADE_TILT_TOLERANCE:
        return False, "tilt"
    return True, ""


def wingbeat_estimable(p):
    """Wingbeat: a bird whose wing lines are detectable and that beats ``MIN_WINGBEATS`` times in a row.

    All of: the wings' strongest line off the body's (the lines are spaced by the wingbeat) stands
    ``LINE_SNR_DB`` above the noise; the
    longest stretch of flapping inside the dwell (``flap_run_s``: the whole dwell, or one flap burst
    of a flap-glide bird) holds ``MIN_WINGBEATS`` beats.
    """
    if p.kind != "bird":
        return False, "not_a_bird"
    if p.micro_line_snr_db < LINE_SNR_DB:
        return False, "below_noise"
    if p.flap_run_s * p.wingbeat_hz < MIN_WINGBEATS:
        return False, "dwell_short"
    return True, ""


def body_velocity_estimable(p):
    """Body velocity (mean range rate): an unambiguous, detectable body Doppler line.

    All of: a body scatterer exists (a drone's or bird's body RCS > 0, or a moving point); it moves: the
    processing's removal of the dwell's mean keeps ``STATIC_SHARE`` of its echo (``body_kept_share``; a
    body at rest, a drone hovering without sway, is one more static scatterer of its range bin: removed
    with the clutter, and nothing tells the two apart); its line stands ``LINE_SNR_DB`` above the noise in
    the frames that hold its sweep to a bin (``body_line_snr_db``); its Doppler stays within +-PRF/2, or
    the range track resolves the alias (beyond PRF/2 the Doppler gives the velocity only modulo the span
    ``lambda PRF / 2``; one range bin over the dwell below a quarter span tells which alias).
    """
    if not p.has_body:
        return False, "no_body"
    if p.body_kept_share < STATIC_SHARE:
        return False, "static"
    if p.body_line_snr_db < LINE_SNR_DB:
        return False, "below_noise"
    if p.body_doppler_max_hz >= p.prf_hz / 2 and p.range_bin_m / p.dwell_s >= p.velocity_span_mps / 4:
        return False, "aliased"
    return True, ""


ESTIMABILITY = {"chopping_freq_hz": chopping_estimable, "rotation_rate_hz": rotation_estimable,
                "blade_length_m": blade_length_estimable, "wingbeat_freq_hz": wingbeat_estimable,
                "body_velocity_mps": body_velocity_estimable}


def truth_value(p, feature):
    """The true value of ``feature`` for target ``p`` (NaN where it has none)."""
    return {"chopping_freq_hz": p.chopping_freq_hz, "rotation_rate_hz": p.rotation_rate_hz,
            "blade_length_m": p.blade_length_m, "wingbeat_freq_hz": p.wingbeat_hz,
            "body_velocity_mps": p.body_velocity_mps}[feature]


def relative_error(feature, truth, value):
    """``|value - truth| / |truth|``; for body velocity relative to ``max(|truth|, VELOCITY_FLOOR_MPS)``."""
    scale = max(abs(truth), VELOCITY_FLOOR_MPS) if feature == "body_velocity_mps" else abs(truth)
    return abs(value - truth) / scale


def score_value(feature, *, truth, estimable, value, status):
    """Verdict of one feature value.

    Parameters
    ----------
    feature : str
    truth : float
        NaN when the target has no such quantity.
    estimable : bool
    value : float or None
        The row's value; None (or NaN) when not reported.
    status : str or None
        The row's ``<feature>_status``; None when the row has no status column.

    Returns
    -------
    dict with ``confident`` (bool), ``error`` (relative, NaN unless both truth and a confident value
    exist) and ``verdict``.
    """
    reported = value is not None and np.isfinite(value)
    confident = bool(reported and (status is None or status == "ok"))
    error = relative_error(feature, truth, value) if confident and np.isfinite(truth) else float("nan")
    if confident and not estimable:
        verdict = "unwarranted"
    elif confident:
        verdict = "wrong" if error > TOLERANCE else "right"
    elif reported:
        verdict = "withheld"
    else:
        verdict = "missed" if estimable else "n/a"
    return {"confident": confident, "error": error, "verdict": verdict}


COVERED = ("right", "wrong")  # the verdicts coverage counts: confident values on estimable cases
CONFIDENTLY_WRONG = ("wrong", "unwarranted")


def score_row(p, row):
    """Score feature row ``row`` (a dict, or None when the target was not detected) against ``p``.

    Returns a flat dict: ``expected_class``, ``measured_class``, ``class_ok``, ``detectable``, the row's
    ``n_blades``, ``n_blades_source`` and ``notes`` (prefixed ``row_``) and for each feature
    ``<f>_truth``, ``<f>_value``, ``<f>_status``, ``<f>_estimable``, ``<f>_why``, ``<f>_error``,
    ``<f>_verdict``.
    """
    row = row or {}
    measured = row.get("class") or "none"
    out = {"expected_class": p.expected_class, "measured_class": measured, "class_ok": measured == p.expected_class,
           "detectable": p.detectable, "row_n_blades": row.get("n_blades"),
           "row_n_blades_source": row.get("n_blades_source"), "row_notes": row.get("notes")}
    for feature in FEATURES:
        estimable, why = ESTIMABILITY[feature](p)
        truth = truth_value(p, feature)
        value = row.get(feature)
        value = None if value is None else float(value)
        status = row.get(f"{feature}_status")
        scored = score_value(feature, truth=truth, estimable=estimable, value=value, status=status)
        out.update({f"{feature}_truth": truth, f"{feature}_value": value, f"{feature}_status": status,
                    f"{feature}_estimable": estimable, f"{feature}_why": why,
                    f"{feature}_error": scored["error"], f"{feature}_verdict": scored["verdict"]})
    return out


def body_rcs_m2(target):
    """RCS of the scatterers that move with the target's body (m^2): a drone's or bird's body and body
    scatterers, a point's (or branch's) own RCS."""
    if target.kind in ("multirotor", "bird"):
        scatterers = getattr(target, "body_scatterers", None) or ()
        return target.body_rcs_m2 + sum(s.rcs_m2 for s in scatterers)
    return float(getattr(target, "rcs_m2", 0.0))


def _without_body(target):
    fields = {f.name for f in dataclasses.fields(target)}
    changes = {k: v for k, v in (("body_rcs_m2", 0.0), ("body_scatterers", ())) if k in fields}
    return dataclasses.replace(target, **changes)


def echo_power_v2(target, *, f0_hz, dwell_s, seed=0, index=0):
    """Mean IF power of ``target`` over the dwell (V^2 per real sample, ``|s|^2 / 2``), at random instants
    (a fixed seed; regular instants could strobe with the blade flashes). ``seed``, ``index``: the scene's
    seed and the target's place, which fix its random draws (rate wander, rough wings, leaves)."""
    t_s = np.sort(np.random.default_rng(0).uniform(0.0, dwell_s, POWER_SAMPLES))
    realization = module_of(target).realize(target, seed=seed, index=index, duration_s=dwell_s)
    return 0.5 * float(np.mean(np.abs(target_echo(target, realization, t_s, f0_hz=f0_hz).signal) ** 2))


def wing_line_share(wings, *, f0_hz, chirp_period_s, n_chirps, seed=0, index=0):
    """The share of a bird's wing echo (``wings``: the bird without its body) that its strongest wingbeat line holds
    in the dwell spectrum (:func:`strongest_line_share`): the echo at the capture's chirps, demodulated by the body's
    range (the processing demodulates the body line to 0 Hz).

    The wings do not share their power evenly among the lines that fill their Doppler extent: the inner wing moves
    slowly and the strokes dwell near their turns. On the default sweep's 83 birds the strongest line stands
    1.1-18.4 dB (median 8.1 dB) above the even share of its extent (4 times the wing tip speed over the wavelength,
    over the wingbeat)."""
    t_s = np.arange(n_chirps) * chirp_period_s
    realization = module_of(wings).realize(wings, seed=seed, index=index, duration_s=n_chirps * chirp_period_s)
    echo = target_echo(wings, realization, t_s, f0_hz=f0_hz)
    return strongest_line_share(echo.signal / carrier(echo.range_m, f0_hz), chirp_period_s=chirp_period_s,
                                spacing_hz=wings.wingbeat_hz)


def strongest_line_share(signal, *, chirp_period_s, spacing_hz):
    """The share of ``signal``'s mean power (one sample a chirp) in the strongest bin of its Hann-windowed dwell
    spectrum (a tone of amplitude a: a^2) at least half ``spacing_hz`` from 0 Hz, where the lines of a pattern
    repeating at ``spacing_hz`` lie (the line at 0 Hz, the pattern's mean, tells no repeat). 0 for no power."""
    signal = np.asarray(signal, dtype=np.complex128)
    mean_power = float(np.mean(np.abs(signal) ** 2))
    if mean_power <= 0:
        return 0.0
    spectrum = power_spectrum(signal, prf_hz=1.0 / chirp_period_s)
    return float(spectrum.power[np.abs(spectrum.f_hz) >= spacing_hz / 2].max() / mean_power)


def kept_share(t_s, range_m, *, wavelength_m):
    """The share of a body's echo power that removing its mean over the dwell keeps: ``1 - |<exp(j phi)>|^2``,
    ``phi = 4 pi r / lambda`` along the range track (samples ``t_s``, ``range_m``), integrated exactly over
    each linear piece (no aliasing of the phase between samples). 0 for a body at rest, ~1 once it moves a
    wavelength."""
    t_s, phase = np.asarray(t_s, dtype=float), 4 * np.pi * np.asarray(range_m, dtype=float) / wavelength_m
    if len(t_s) < 2 or t_s[-1] <= t_s[0]:
        return 0.0
    step = np.diff(phase)
    small = np.abs(step) < 1e-9
    piece = np.where(small, 1.0, np.expm1(1j * step) / np.where(small, 1.0, 1j * step))
    mean = np.sum(np.exp(1j * phase[:-1]) * piece * np.diff(t_s)) / (t_s[-1] - t_s[0])
    return float(max(0.0, 1.0 - abs(mean) ** 2))


def line_count(extent_hz, spacing_hz, *, prf_hz):
    """Lines of spacing ``spacing_hz`` in a Doppler extent (folded into the PRF when wider), at least 1."""
    return max(1.0, min(extent_hz, prf_hz) / spacing_hz)


def physics_of(index, expected, *, scene, noise_sigma_v, process):
    """:class:`Physics` of the scene's target ``index``.

    Parameters
    ----------
    index : int
        The target's index in ``scene.targets`` (its seed index).
    expected : dict
        Its entry of the capture's ``/Truth`` ``expected.targets`` (body track, rotor rates, blade imbalance).
    scene : Scene
    noise_sigma_v : float
        Noise standard deviation per IF sample (V), from ``/Truth`` ``simulation``.
    process : dict
        The :class:`mdpipe.params.ProcessParams` keywords given (``n_blades``, ``elevation_deg``).
    """
    target = scene.targets[index]
    radar = scene.radar.params
    n_chirps = scene.radar.n_chirps
    dwell_s = radar.duration_s(n_chirps)
    wavelength_m, prf_hz = radar.wavelength_m, radar.prf_hz
    kind = target.kind
    base = dict(kind=kind, expected_class=target.expected_class,
                dwell_s=dwell_s, prf_hz=prf_hz, velocity_span_mps=wavelength_m * prf_hz / 2,
                range_bin_m=radar.range_bin_m)
    if kind == "static":
        return Physics(**base)
    noise_v2 = noise_sigma_v ** 2 if noise_sigma_v > 0 else np.finfo(float).tiny
    gain = radar.n_samples / 3.0 * radar.n_channels * n_chirps
    micro, share = 0.0, 1.0
    if kind in ("multirotor", "bird"):
        bodiless = _without_body(target)
        micro = echo_power_v2(bodiless, f0_hz=radar.f_start_hz, dwell_s=dwell_s, seed=scene.seed, index=index)
        share = range_share.in_bin_share(bodiless, radar=radar, seed=scene.seed, index=index, n_chirps=n_chirps)
    base.update(micro_bin_share=share)
    body_rcs = body_rcs_m2(target)
    body_power = 0.5 * body_rcs * float(np.mean(np.asarray(expected["track"]["range_m"]) ** -4.0))
    kept = kept_share(expected["track"]["t_s"], expected["track"]["range_m"], wavelength_m=wavelength_m)
    body_doppler = expected["body_doppler_hz"]
    sweep_hz = body_doppler["max"] - body_doppler["min"]
    base.update(body_doppler_max_hz=max(abs(body_doppler["max"]), abs(body_doppler["min"])),
                has_body=body_rcs > 0, body_velocity_mps=float(expected["range_rate_mps"]["mean"]),
                body_kept_share=kept,
                body_line_snr_db=_db(kept * body_power / noise_v2 * gain
                                     / np.sqrt(max(1.0, sweep_hz * dwell_s))))
    if kind == "multirotor":
        rotors = target.rotors
        rates = tuple(expected["rotor_rates_hz"])
        # each rotor's disc seen at the drone's elevation plus its tilt (near face-on the tilt decides)
        tip_hz = float(np.max(rotor.tip_doppler_hz(np.array(rates), blade_length_m=rotors.blade_length_m,
                                                   wavelength_m=wavelength_m,
                                                   elevation_deg=np.array(expected["rotor_elevations_deg"]))))
        distinct = len(np.unique(np.round(np.array(rates) * dwell_s)))  # rotors resolved in the dwell spectrum
        lines = distinct * line_count(2 * tip_hz + sweep_hz, rotors.blades * np.mean(rates), prf_hz=prf_hz)
        return Physics(**base, micro_line_snr_db=_db(share * micro / noise_v2 * gain / lines), rotor_rates_hz=rates,
                       rotor_elevations_deg=tuple(expected["rotor_elevations_deg"]),
                       n_blades=rotors.blades, blade_length_m=rotors.blade_length_m,
                       elevation_deg=target.elevation_deg, blades_given=process.get("n_blades") is not None,
                       elevation_given="elevation_deg" in process,
                       imbalance_line_db=imbalance_line_db(expected["blade_gains"]), tip_doppler_hz=tip_hz)
    if kind == "bird":
        line = wing_line_share(bodiless, f0_hz=radar.f_start_hz, chirp_period_s=radar.chirp_period_s,
                               n_chirps=n_chirps, seed=scene.seed, index=index)
        flap_run_s = dwell_s if target.flap_glide is None else min(dwell_s, target.flap_glide.flap_s)
        return Physics(**base, micro_line_snr_db=_db(share * micro / noise_v2 * gain * line),
                       wingbeat_hz=target.wingbeat_hz, flap_run_s=flap_run_s)
    return Physics(**base)


def imbalance_line_db(gains):
    """The strongest line unequal blades (amplitude ``gains``, one per blade) add between the chopping lines,
    in dB against the chopping lines; -inf for equal blades.

    A rotor's echo is the sum of its blades' echoes, blade i delayed by i / N of a turn: its line at order m of
    the turn rate carries ``sum_i g_i exp(-2 pi j m i / N)``, ``sum_i g_i`` at the chopping lines (m a multiple
    of N). Two blades: ``((g1 - g2) / (g1 + g2))^2``.
    """
    g = np.asarray(gains, dtype=np.float64)
    n = len(g)
    if n < 2 or np.ptp(g) == 0:
        return float("-inf")
    orders = np.arange(1, n)[:, None]
    lines = np.abs(np.exp(-2j * np.pi * orders * np.arange(n)[None, :] / n) @ g) ** 2
    return float(10 * np.log10(lines.max() / np.sum(g) ** 2))


def _db(ratio):
    return float(10 * np.log10(ratio)) if ratio > 0 else float("-inf")


def match_rows(rows, *, range_min_m, range_max_m, range_mean_m, tolerance_m):
    """The row of the target whose track spans ``[range_min_m, range_max_m]``, and the other detections.

    A row matches when its range lies within the track widened by ``tolerance_m``; of several, the
    nearest to ``range_mean_m``. Rows without a range (nothing detected) are neither.
    """
    detected = [r for r in rows if r.get("range_m") is not None]
    near = [r for r in detected if range_min_m - tolerance_m <= r["range_m"] <= range_max_m + tolerance_m]
    match = min(near, key=lambda r: abs(r["range_m"] - range_mean_m)) if near else None
    return match, [r for r in detected if r is not match]
