"""Features of one target's slow-time echo, each a value with its validity (:mod:`mdpipe.process.validity`).

Conventions: Doppler in Hz with the paper's sign (approaching positive); velocities in m/s,
positive receding; every inversion uses :mod:`mdpipe.physics`, the functions the simulator uses.
Each measurement is one function returning :class:`~mdpipe.process.validity.Measured` values;
:func:`analyse_target` puts them in the row.
"""

import functools
import math
from dataclasses import dataclass, field, replace

import numpy as np

from mdpipe.physics import rotor
from mdpipe.physics.radar import range_rate_from_doppler_mps
from mdpipe.process import combs, doppler, mains, spectral
from mdpipe.process.classify import (DRONE_SPREAD_MPS, MIN_FLIGHT_DISTANCE_M, MIN_FLIGHT_SPEED_MPS,
                                     MIN_FLYING_WING_SPREAD_MPS, MIN_WING_SPREAD_MPS, ROTOR_EVIDENCE)
from mdpipe.process.filters import least_squares_line, moving_average, running_median, triangular_average
from mdpipe.process.flashes import (MAX_POWER_PERIOD_S, RAMP_MIN_PERIOD_CHIRPS, RAMP_SETTLE_SHARE, PowerPeriod,
                                    chirp_grid_drift, flank_flash_period, flank_line_hz, flash_period, on_chirp_grid,
                                    period_of_power, power_period, ramp_readable, ramp_floor, ramp_repeat,
                                    ramp_repeats_whole, ramp_train, sides_alternate, sides_flash_apart,
                                    whole_ratio_apart)
from mdpipe.process.periodicity import autocorrelation, best_near, find_period
from mdpipe.process.ranging import MAIN_LOBE_BINS
from mdpipe.process.validity import OK, Measured, withheld
from mdpipe.process.wingbeat import (MAX_WINGBEAT_HZ, MIN_WINGBEAT_HZ, STROKE_FRAME_S, Octave, ShortBursts,
                                     dwell_frames, flap_glide_share, overruns_span, readable_reach_hz, stroke_swing,
                                     weak_reach_hz, wing_reach_hz, wingbeat)

BODY_LINE_DB = 6.0           # a body line stands this far above the next line of its frame ...
BODY_KEPT_LINE_DB = 3.0      # ... or this far, where it is the strongest line on the body track in ...
BODY_KEPT_SHARE = 0.75       # ... this share of the frames (a bird's wings stand within 6 dB of its body as they turn)
BODY_KEPT_TRACK_BINS = 0.25  # ... and the range track moves as it says to this share of a range bin over the dwell
BODY_FRAME_S = 0.032
BODY_STEADY_SHARE = 0.5      # frames whose strongest line lies on the smoothed body track
MAX_UNRANGED_SPEED_MPS = 50.0  # without a range track (CW), the one alias of the body Doppler under this speed
MAX_SPEED_MPS = 25.0         # birds and small drones fly slower: a faster alias of the body Doppler is not taken
BODY_TRACK_FRAMES = 9        # running median of the body track (rotor lines win single frames)
BODY_RATE_MEDIAN_S = 0.2     # ... and, for the mean range rate, over this time: a rotor line winning up to 0.1 s
BODY_SPREAD_PERCENTILES = (90, 10)  # the body track's spread read between these (a rotor line wins a frame or two)
STROKE_SWING = 0.15          # wings' reach swinging this share of its greatest over the dwell: a stroke (rotors' hold)
WINGBEAT_SPREAD_SHARE = 0.01  # a wingbeat's standard error (its repeats' scatter about k T) at most this share of T:
                              # the 3 % a wingbeat is held to at three standard errors
STRAIGHT_BINS = 0.25         # a track the Doppler bent a bin or more lies this close (rms) to a line, straightened
STATIC_LINE_S = 0.25         # the line at 0 Hz (clutter, and what its removal leaves) followed over this time ...
STATIC_CLEAR_NULLS = 4.0     # ... where the body line lies this many of its smoothing's first nulls from 0 Hz
MAX_ELEVATION_DEG = 80.0     # beyond it Eq. 6 divides by cos(beta) < 0.17: r is not estimable
EDGE_BINS = 10.0             # the flash edges' frame lengthened, up to a flash period, until the tips span this many
                             # Doppler bins a side ...
MIN_EDGE_BINS = 8.0          # ... and r read only where they span this many (at 3-4 bins one uniform 2-blade rotor's
                             # edges read 4-6 % wide, 3-blade rotors' 9-17 % at 4-5 bins)
MAX_EDGE_TURN = 0.25         # ... in frames of a quarter turn at most: the tips' Doppler falls to cos(45 deg) at their
                             # ends (one 2-blade rotor read -1.2 to -2.6 % in 3/8 or 1/2 turn, tapered ones -5 to -8 %
                             # at Gamma 18-20, against -0.3 to -1.4 % in a quarter)
MIN_ROTOR_PERIODICITY = 0.6  # a rotor's echo repeats almost exactly (measured 0.93-0.95; a gull's best: 0.40)
HIGHPASS_SHARE = 0.25        # body removal for unaliased echoes: cut below this share of the band's half-width
EDGE_NOTCH_SHARE = 0.05      # body removal before the flash edges (which lie at the band's ends)
MIN_EDGE_FRAMES = 5          # flash edges read on each side, at least (their scatter is measured from them) ...
EDGE_SPREAD_SHARE = 0.015    # ... and the standard error of their medians' distance at most this share of it
ROTOR_TILT_DEG = 5.0         # a rotor disc may tilt this far from the drone's elevation (attitude, hover to cruise)
TILT_TOLERANCE = 0.03        # blade length ok only where that tilt moves cos(beta) by at most this share
ALIAS_CHECK_CHIRPS = 64      # window of the spectrogram that tells whether the brightest frames fill the span
TAGGED_REPEAT = 0.8          # a rotor with one blade differing still repeats this well each 1/N turn (0.89-0.98)
DRIFTING_REPEAT = 0.6        # rotors at one rate repeat their echo each turn as one rotor does (0.86-0.99 of the
                             # signal's power); under this share they drift through each other's phases
HANN_LOBE_BINS = MAIN_LOBE_BINS["hann"]  # a line reaches this many bins either side of it (a Hann window's main lobe)
ONCE_FOLDED_MULTIPLES = 3    # a comb at k f folded once fills every order of the comb at f for k up to this
AGREEMENT = 0.02             # comb and time-domain chopping frequencies agree within 2 %
WIDE_BAND_SHARE = 0.75       # an unaliased band over this share of the span decorrelates within a chirp
MAX_RAMP_DIVISOR = 6         # a power period not whole within the ramp: its halves to sixths are tried there
POWER_COMB_TOLERANCE = 0.1   # an unaliased comb and its echo's power rate are a whole ratio apart within 10 %: rotors
                             # apart in rate (chopping at 123-134 Hz, the power repeated with the fastest, 133.1 Hz,
                             # the comb was their median, 125.2 Hz)
MIN_ROTOR_TIP_MPS = 20.0     # multirotor blade tips move at 20 m/s or more (classify.py; the fastest: rotor.py) ...
HIDDEN_ELEVATION_DEG = 60.0  # ... and, the elevation not given, are taken as seen within this of edge-on
MIN_BLADE_M = 0.005          # a blade this short, at the elevation given (its disc tilted ROTOR_TILT_DEG towards
                             # face-on), reaches the least r cos(beta) of any rotor: a comb narrower is not one
MIN_WIDE_ORDERS = 8          # a comb found beyond the band measured holds this many orders a side at least
BANDWIDTH_SEGMENT_S = 0.25   # the paper's rule on segments of this length (its value depends on the dwell)
EDGE_BAND_EXCESS = 1.25      # the whole dwell's band beyond the flash edges by more than this is not the lines' Bessel
                             # tails and the rotors' spread of rates (<= 1.2; in the sweep 1.28-1.71 where tips folded)
ASSUMED_EVEN_BLADES, ASSUMED_ODD_BLADES = 2, 3

# Each measured quantity and the columns derived from it, which share its status.
FEATURE_GROUPS = {
    "snr_db": (),
    "micro_doppler_halfwidth_mps": (),
    "doppler_bw_hz": ("doppler_bw_mps", "doppler_low_hz", "doppler_high_hz"),
    "chopping_freq_hz": (),
    "rotation_rate_hz": ("rotation_period_s", "flash_period_s", "rotor_rates_hz"),
    "doppler_bw_spectrogram_hz": ("tip_doppler_hz",),
    "blade_length_m": (),
    "body_velocity_mps": ("body_doppler_hz",),
    "wingbeat_freq_hz": ("wingbeat_period_s",),
    "flapping_share": (),
    "wing_stroke_swing": (),
}
VALUE_KEYS = tuple(key for primary, derived in FEATURE_GROUPS.items() for key in (primary, *derived))
STATUS_KEYS = tuple(f"{key}_status" for key in VALUE_KEYS)
FEATURE_KEYS = VALUE_KEYS + ("aliased", "n_rotors", "n_blades", "n_blades_source", "stft_window_s", "stft_hop_s",
                             "mains_hum_hz") + STATUS_KEYS
WITHHELD_KEPT = ("snr_db", "snr_db_status", "mains_hum_hz")  # a withheld echo's own strength and hum: measured


def read_as(row):
    """What ``row``'s echo alone was read as, for the note of a row withheld (:func:`withheld_row`): its class and the
    class's reason (the first of its notes)."""
    return f"its echo read as {row['class']} ({row['notes'].split('; ')[0].removeprefix('class: ')})"


def withheld_row(row, *, status, note, capture_notes=()):
    """``row`` read as an echo that a receiver impairment may have made: class ``none``, every feature but its SNR
    withheld with ``status``, a blade count given by the user kept, its notes ``note`` and ``capture_notes``."""
    withheld = [key for key in FEATURE_KEYS if key not in WITHHELD_KEPT]
    return {**row, **dict.fromkeys(key for key in withheld if key not in STATUS_KEYS),
            **dict.fromkeys((key for key in STATUS_KEYS if key in withheld), status),
            "n_blades": row["n_blades"] if row["n_blades_source"] == "given" else None,
            "n_blades_source": "given" if row["n_blades_source"] == "given" else None,
            "class": "none", "notes": "; ".join([note, *capture_notes])}


@dataclass
class TargetAnalysis:
    """Everything measured on one target: the feature row and the spectra the figures show."""

    row: dict
    spectrum: doppler.PowerSpectrum
    spectrogram: doppler.Spectrogram
    paper_extent_hz: tuple = None
    flash_edges_hz: tuple = None
    notes: list = field(default_factory=list)


@dataclass(frozen=True)
class BodyMotion:
    """The body's Doppler track (None without a body line), its velocity, and the echo demodulated by it."""

    track_hz: object
    velocity: Measured
    demodulated: np.ndarray


@dataclass(frozen=True)
class RangeTrack:
    """The target's range over the dwell, per tracking chunk: ``range_m`` at ``t_s``, bins of ``bin_m``."""

    t_s: np.ndarray
    range_m: np.ndarray
    bin_m: float
    coupling_m_per_hz: float = 0.0
    doppler_bend_bins: float = 0.0  # how far (peak to peak) the Doppler said the track bends, straightened

    def straightened(self, t_s, doppler_hz, *, wavelength_m):
        """The track as the Doppler says a body moving at its mean range rate would have gone, to test aliases on.

        Two things bend a track that the Doppler ``doppler_hz`` (+ approaching, at ``t_s``; right up to a whole number
        of spans) tells. The range-Doppler coupling: an up-chirp's beat holds the Doppler ``f`` with the range, and a
        scatterer reads ``f T_s`` bins nearer (``coupling_m_per_hz`` = ``T_s`` times the bin); a Doppler falling 7.2
        kHz/s at 94 GHz (``T_s`` 0.31 ms, bins of 1.5 m) tilts the track by 3.4 m/s. And the range rate's own change:
        the least-squares slope of a curved track is no mean range rate (a goose passing 11 m over a K-band radar in
        3.5 s). The coupling is taken out, and the path the Doppler's range rate integrates to less its mean rate:
        what is left moves at the mean range rate, up to the whole spans the Doppler does not tell, and the bins'
        uncertainty.
        """
        f_hz = np.interp(self.t_s, t_s, doppler_hz)
        rate = range_rate_from_doppler_mps(f_hz, wavelength_m=wavelength_m)
        steps = np.diff(self.t_s) * (rate[1:] + rate[:-1]) / 2
        bend = np.concatenate([[0.0], np.cumsum(steps)]) - np.mean(rate) * (self.t_s - self.t_s[0])
        return RangeTrack(self.t_s, self.range_m + f_hz * self.coupling_m_per_hz - bend, self.bin_m,
                          self.coupling_m_per_hz, doppler_bend_bins=float(np.ptp(bend)) / self.bin_m)

    def range_rate_mps(self):
        """Least-squares range rate and its bound: a bin's uncertainty over the track's span."""
        span_s = float(self.t_s[-1] - self.t_s[0]) if len(self.t_s) > 1 else 0.0
        if span_s <= 0:
            return 0.0, np.inf
        return float(np.polyfit(self.t_s, self.range_m, 1)[0]), self.bin_m / span_s

    def bend_bins(self):
        """The rms distance (bins) of the track from its least-squares line (0 for fewer than three points)."""
        if len(self.t_s) < 3:
            return 0.0
        line = least_squares_line(self.t_s, self.range_m)
        return float(np.sqrt(np.mean((self.range_m - line) ** 2)) / self.bin_m)


def dealias_velocity(doppler_mps, *, span_mps, track, ranged=True):
    """The body velocity among ``doppler_mps + k span_mps`` that the range track supports, or why none.

    The ``track`` is the range track as the Doppler straightens it (:meth:`RangeTrack.straightened`): where the
    Doppler bent it by a bin or more and it still lies ``STRAIGHT_BINS`` rms off a line, range and Doppler follow
    different things (a target lost by the range track, a Doppler track on noise), and nothing is reported (a point
    passing 5 m under an X-band radar at 12 m/s, its range track lost: 0.76 rms; bodies followed through bends of
    4-8 m, 0.017-0.055 rms). Where the Doppler bends it less, the track's own scatter stays (a swaying branch's and
    a hovering drone's, 0.26-0.37 bin rms at the sweep's SNRs) and the bins bound the rate as before.

    The Doppler gives the range rate only modulo the unambiguous span ``lambda PRF / 2``; the range
    track (bins of c / 2B over the dwell) gives it coarsely but without ambiguity. When the track's
    uncertainty is below a quarter span the alias nearest the track's rate is the velocity (if it lies
    within twice that uncertainty of it: else the two disagree and nothing is reported); otherwise
    the Doppler stands only when every other alias the track allows is faster than ``MAX_SPEED_MPS``.

    Without a track (``None``): a target held in one range bin (the Doppler stands), or, not ``ranged``, an echo
    without range (a CW recording), where the Doppler stands only when every other alias is faster than
    ``MAX_UNRANGED_SPEED_MPS`` (twice the speed the track's test allows: no track bounds it; a target receding at 30
    m/s sampled at 8 kHz at 24 GHz read -19.97 m/s under 25 m/s), and is given as ``assumed_speed`` where that holds
    for ``MAX_SPEED_MPS`` only.
    """
    if track is None and ranged:
        return Measured(doppler_mps)
    if track is None:
        aliases = doppler_mps + span_mps * np.arange(-3, 4)
        for ceiling_mps, status in ((MAX_UNRANGED_SPEED_MPS, OK), (MAX_SPEED_MPS, "assumed_speed")):
            if np.count_nonzero(np.abs(aliases) <= ceiling_mps) == 1 and abs(doppler_mps) <= ceiling_mps:
                note = "" if status == OK else (f"body velocity assumes a speed under {MAX_SPEED_MPS:g} m/s: the "
                                                f"Doppler gives it modulo {span_mps:.3g} m/s and no range tells which")
                return Measured(doppler_mps, status, note)
        return withheld("velocity_ambiguous", f"body velocity not estimable: the Doppler gives it modulo "
                        f"{span_mps:.3g} m/s and, without range, only a speed under {MAX_SPEED_MPS:g} m/s could tell "
                        "which; more than one alias is")
    if track.doppler_bend_bins >= 1.0 and (bend := track.bend_bins()) > STRAIGHT_BINS:
        return withheld("velocity_ambiguous", f"body velocity not estimable: the range track does not follow the "
                        f"Doppler (straightened by it, it lies {bend:.2g} bins rms off a line)")
    rate, bound = track.range_rate_mps()
    if bound < span_mps / 4:
        k = round((rate - doppler_mps) / span_mps)
        if abs(doppler_mps + k * span_mps - rate) > 2 * bound:  # no alias agrees with the track
            return withheld("velocity_ambiguous", f"body velocity not estimable: no alias of the Doppler's "
                            f"{doppler_mps:.3g} m/s (modulo {span_mps:.3g} m/s) agrees with the range track's "
                            f"{rate:.2g} +- {bound:.2g} m/s")
        note = "" if k == 0 else (f"body velocity unfolded by {k:+d} x {span_mps:.3g} m/s: the range track moves at "
                                  f"{rate:.2g} +- {bound:.2g} m/s")
        return Measured(doppler_mps + k * span_mps, OK, note)
    aliases = doppler_mps + span_mps * np.arange(-3, 4)
    possible = aliases[(np.abs(aliases - rate) <= bound) & (np.abs(aliases) <= MAX_SPEED_MPS)]
    if len(possible) == 1 and possible[0] == doppler_mps:
        return Measured(doppler_mps)
    return withheld("velocity_ambiguous", f"body velocity not estimable: the Doppler gives it modulo {span_mps:.3g} m/s "
                    f"and the range track ({rate:.2g} +- {bound:.2g} m/s) does not tell which")


def body_motion(signal, *, prf_hz, wavelength_m, track=None, ranged=True):
    """Body Doppler and velocity from the strongest line of each 32 ms frame, when a body line exists.

    Per frame the strongest line must stand ``BODY_LINE_DB`` above the strongest line more than two
    bins away (median over frames); otherwise (rotating parts only, or phase-locked rotors whose
    interference skews the spectrum) there is no body line, unless it stands ``BODY_KEPT_LINE_DB``, is the
    strongest line on the body track in ``BODY_KEPT_SHARE`` of the frames, and the range ``track`` moves as its
    Doppler says (:func:`_range_follows`): a bird's wings, as bright as its body, stand within 6 dB of it where
    they turn (birds of an independent simulator, 94 GHz to X band, their body lines 3-6 dB over the wings' and
    on their track in 75-100 % of the frames, read none; their range rates are now read within 0.1 m/s), while a
    rotor's comb line, as steady, stays where the hub is (a hovering quadrotor's line at 10.9 m/s, its range
    track still). The track is the running median of the
    frame peaks over ``BODY_TRACK_FRAMES`` frames, so a frame where a rotor line outshines the body
    does not move it; if fewer than ``BODY_STEADY_SHARE`` of the frames peak on the track, the body
    is not steady enough to demodulate. The velocity is the mean range rate over the dwell: the mean of the
    frame peaks' running median over ``BODY_RATE_MEDIAN_S`` (a rotor line 1.7 m/s off that won 6 frames running took
    the 9-frame track, and its mean read -0.46 m/s for -0.26; a body's monotone track passes such a median
    unchanged, a sway's turns are clipped symmetrically), the frame peaks taken on one branch first
    (:func:`one_branch_hz`), unfolded with the range ``track`` where the Doppler alone is ambiguous
    (:func:`dealias_velocity`) as the Doppler straightens it (:meth:`RangeTrack.straightened`). The echo is
    demodulated along the 9-frame track (which follows a body's turns closer: demodulated along the 0.2 s one, a
    sparrow of the sweep read as a drone), less its line at 0 Hz (:func:`static_line`).
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
    peaks = one_branch_hz(doppler.frame_peaks_hz(spec, prf_hz=prf_hz), prf_hz=prf_hz, frames=BODY_TRACK_FRAMES)

    def peaks_median(frames):  # the peaks' running median over an odd number of frames, at most the dwell's
        return running_median(peaks, min(frames, len(peaks)) | 1)

    frame_track = peaks_median(BODY_TRACK_FRAMES)
    bin_hz = spec.f_hz[1] - spec.f_hz[0]
    on_track = float(np.mean(np.abs(doppler.fold_hz(spec.f_hz[peak] - frame_track, prf_hz=prf_hz)) <= 2 * bin_hz))
    kept = prominence < BODY_LINE_DB  # a line that does not stand out, kept to a track the range track follows
    if kept and not (prominence >= BODY_KEPT_LINE_DB and on_track >= BODY_KEPT_SHARE and track is not None):
        return BodyMotion(None, withheld("no_body_line", f"body velocity not estimable: no body line stands out of "
                                         f"the micro-Doppler ({prominence:.1f} dB < {BODY_LINE_DB:.0f} dB above the "
                                         f"next line; {BODY_KEPT_LINE_DB:.0f} dB for a line on its track in "
                                         f"{BODY_KEPT_SHARE:.0%} of the frames that the range track follows: on it in "
                                         f"{on_track:.0%})"), signal)
    if on_track < BODY_STEADY_SHARE:
        return BodyMotion(None, withheld("body_unsteady", f"body velocity not estimable: the strongest line lies on "
                                         f"the body track in only {on_track:.0%} of the frames"), signal)
    times_s = np.arange(len(signal)) / prf_hz
    doppler_track = np.interp(times_s, spec.t_s, frame_track)
    track = None if track is None else track.straightened(spec.t_s, frame_track, wavelength_m=wavelength_m)
    rate_track = peaks_median(int(round(BODY_RATE_MEDIAN_S / spec.hop_s)))
    velocity = float(range_rate_from_doppler_mps(float(np.mean(np.interp(times_s, spec.t_s, rate_track))),
                                                 wavelength_m=wavelength_m))
    unfolded = dealias_velocity(velocity, span_mps=wavelength_m * prf_hz / 2, track=track, ranged=ranged)
    if kept and not _range_follows(unfolded.value, track):
        rate = track.range_rate_mps()[0]
        return BodyMotion(None, withheld("no_body_line", f"body velocity not estimable: no body line stands out of "
                                         f"the micro-Doppler ({prominence:.1f} dB < {BODY_LINE_DB:.0f} dB above the "
                                         f"next line; the line kept to a track says {velocity:.3g} m/s, the range "
                                         f"track {rate:.3g} m/s, bins of {track.bin_m:.3g} m)"), signal)
    return BodyMotion(doppler_track, unfolded, doppler.demodulate(
        signal - static_line(signal, doppler_track, prf_hz=prf_hz), doppler_track, prf_hz=prf_hz))


def one_branch_hz(peaks_hz, *, prf_hz, frames):
    """Frame peaks ``peaks_hz`` (each folded into the span) on one continuous branch: each the alias of itself
    nearest the running median over ``frames`` frames, itself unwrapped (steps of ``prf_hz`` taken out).

    A body whose Doppler crosses the span's edge during the dwell (a swift at 94 GHz and a PRF of 2.6 kHz: its
    range rate sweeping -4.8 to +8 m/s across a span of 4.1 m/s) folds to the other edge there; the folded track's
    mean is no mean range rate (the swift read 6.04 m/s for 1.96), its running median no track, and a track
    interpolated across the jump sweeps the whole span. An outlier frame (a rotor line outshining the body) keeps
    its alias nearest the track: unwrapped itself, two outliers a span apart would step the rest of the track
    by a span.
    """
    track = np.unwrap(running_median(peaks_hz, min(frames, len(peaks_hz)) | 1), period=prf_hz)
    return track + doppler.fold_hz(peaks_hz - track, prf_hz=prf_hz)


def _range_follows(velocity_mps, track):
    """Whether the range ``track`` (a :class:`RangeTrack`) moves at ``velocity_mps`` (None: no) to within
    ``BODY_KEPT_TRACK_BINS`` of a range bin over its span: its fractional bins follow a body to a few per cent
    of a bin (a flying bird's range rate read within 0.15 m/s from bins of 7.5 m over 1.8 s)."""
    if velocity_mps is None:
        return False
    rate, bound = track.range_rate_mps()
    return bool(np.isfinite(bound)) and abs(velocity_mps - rate) <= BODY_KEPT_TRACK_BINS * bound


def static_line(signal, track_hz, *, prf_hz):
    """The line at 0 Hz that the body-demodulated echo would carry as a copy of the body track, mirrored.

    Static clutter is removed as the mean chirp of each range column, but that mean also holds what the
    target puts at 0 Hz: a body whose Doppler crosses 0 Hz (a bird flying past) dwells there, and its mean,
    subtracted from every chirp, leaves a line at 0 Hz (-44 dB of a body sweeping +-900 Hz in 3 s: a pigeon's
    4.6 m/s of wings read 12.4 m/s). Clutter the mean does not hold (it changes along a track that crosses
    range bins) leaves one too. Demodulated by the body, such a line sweeps over the micro-Doppler band.
    It is followed as the echo smoothed over ``STATIC_LINE_S`` (triangular, first null ``2 / STATIC_LINE_S``)
    where the body line lies ``STATIC_CLEAR_NULLS`` such nulls from 0 Hz or more throughout the smoothing's
    window (there the smoothing leaks under 1 % of the body: it holds the line), interpolated across the
    times the body passes 0 Hz, and 0 where the body never leaves it (a hovering drone's body is that line).
    """
    size = max(1, int(round(STATIC_LINE_S * prf_hz / 2)))
    away = np.abs(doppler.fold_hz(track_hz, prf_hz=prf_hz)) >= STATIC_CLEAR_NULLS * 2.0 / STATIC_LINE_S
    clear = moving_average(away.astype(float), 2 * size - 1, mode="inside") > 1 - 1e-9  # away over the whole window
    if not clear.any():
        return np.zeros_like(signal)
    line = triangular_average(np.asarray(signal, dtype=np.complex128), size)
    if clear.all():
        return line
    index = np.arange(len(signal))
    inside = np.interp(index, index[clear], line.real[clear]) + 1j * np.interp(index, index[clear], line.imag[clear])
    return np.where(clear, line, inside)


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


@dataclass(frozen=True)
class DopplerBand:
    """The dwell spectrum (for the figures), the micro-Doppler half-width about its centre (with the single lines
    beyond the dense band; ``dense_half_width_hz`` without them), aliasing and why."""

    spectrum: doppler.PowerSpectrum
    half_width_hz: float
    aliased: bool
    halfwidth: Measured
    dense_half_width_hz: float = 0.0


def _disc_seen_deg(elevation_deg, *, towards_face_on):
    """The elevation (deg, 0 edge-on to 90 face-on) a rotor disc is seen at, the drone seen at ``elevation_deg``
    and its disc tilted ``ROTOR_TILT_DEG`` towards face-on (its tips' radial speed the least) or edge-on (the most)."""
    turned = abs(elevation_deg) + (ROTOR_TILT_DEG if towards_face_on else -ROTOR_TILT_DEG)
    return float(np.clip(turned, 0.0, 90.0))


def hidden_aliasing_note(*, prf_hz, wavelength_m, elevation_deg):
    """Why a band that does not reach the span's ends may yet alias where the noise is read from the echo itself (a CW
    recording, :mod:`mdpipe.process.cw`): a rotor's tips (``MIN_ROTOR_TIP_MPS``, seen at the elevation given, tilted
    ``ROTOR_TILT_DEG`` towards face-on, else at ``HIDDEN_ELEVATION_DEG``) pass the span's radial speed
    ``lambda PRF / 4``, so that they fold over it, and a floor they fill evenly reads as noise. None where the span
    holds them."""
    seen_deg = HIDDEN_ELEVATION_DEG if elevation_deg is None else _disc_seen_deg(elevation_deg, towards_face_on=True)
    least_mps = MIN_ROTOR_TIP_MPS * np.cos(np.deg2rad(seen_deg))
    span_mps = wavelength_m * prf_hz / 4
    if span_mps >= least_mps:
        return None
    return (f"the span reaches +-{span_mps:.2g} m/s, under the {least_mps:.2g} m/s a rotor's tips reach, and the "
            "noise, read from the echo (no range bins), may be their folded floor")


def _undersampled(turn, why):
    """A :class:`Rotation` read from an echo without range whose span cannot hold a rotor's tips (``why``:
    :func:`hidden_aliasing_note`): its values kept, their status (``ok``, or a caveat such as ``assumed_blades``,
    which the note keeps) made ``undersampled``. On the scenes of ``make offmodel`` recorded by a CW radar at the
    scenes' PRFs (``make offmodel-cw``), such rates were more than 2 % off (at half or three times the truth and the
    like) in 5 of 33 recorded through a filter and 4 of 45 sampled without one (flashes shorter than a sample, caught
    only where samples fall; folded lines that coincide; a receiver's filter cutting the tips off), where those with
    the tips inside the span were all right."""
    def caveat(measured, what):
        if measured.value is None:
            return measured
        note = (f"{what} not stood behind: {why}; from such an echo it may be a fraction or a multiple of the true one "
                "(record at over twice the tips' Doppler)")
        return Measured(measured.value, "undersampled", "; ".join(n for n in (measured.note, note) if n))
    return replace(turn, chopping=caveat(turn.chopping, "chopping frequency"), rate=caveat(turn.rate, "rotation rate"))


def _folded_unseen(turn, *, aliased, tips_seen, prf_hz, wavelength_m, elevation_deg, dwell_s):
    """``turn`` (a :class:`Rotation`), its chopping frequency kept as ``ambiguous_period`` (it or a whole multiple; the
    blade count as it was; the rate withheld) where it was read in a band that shows no aliasing, no flash showed both
    the tips' Doppler edges inside the span (``tips_seen``: the blade length's reading, :func:`blade_length`, got
    them), the span (``lambda PRF / 4``) holds no tips of the fastest rotor (``rotor.MAX_ROTOR_TIP_MPS``, seen at the
    elevation given, its disc tilted ``ROTOR_TILT_DEG`` towards edge-on; else edge-on), and the PRF lies within the
    Hann main lobe of a whole multiple M of it with k = 2 or 3 prime to M (``ONCE_FOLDED_MULTIPLES``,
    :func:`_fold_multiples`; k times it no faster than ``combs.MAX_CHOP_HZ``).
    Tips folded once, too faint to light the dwell's band out to the span's ends, then put k times that chopping's
    lines on the orders of a comb at it that k's own lines miss: the echo shows the same comb, and the same period,
    for either. A comb at 4 times or more fills them only folded twice or more, by tips that light the span's ends
    (where M was a multiple of 6, three right readings at X and 77 GHz lay within the lobe of k = 5, and none wrong).
    Three X-band drones at PRFs of 2.2-4.4 kHz (spans of 17-34 m/s), N = 2 given or not, were read at half their
    chopping, `ok`, the PRF 0.11-0.28 bin from 35, 45 and 45 times the comb (a fourth, 2.9 bins from 17 times it, is
    not told); three right readings lay within the lobe too (0.9-1.7 bins: a 94 GHz hexarotor, an X-band quadrotor, a
    77 GHz one seen from 81 deg). Two X-band quadrotors of 3-blade rotors at PRFs of 1.8 and 1.7 kHz were read at a
    third, the PRF 1.2 and 1.6 bins from 26 times the comb (k = 2 shares M's factor; k = 3 does not); the second is
    told, the first not (its flash edges read inside the span, at 0.90 of its half, blurred over 3.6 Doppler bins a
    side); a K-band 3-blade one read right lay 1.9 bins from 26 times its comb. Of `make offmodel`'s scenes, three
    right readings at K and X band (PRFs of 9.4-20.9 kHz) lay within the lobe with their flash edges read inside the
    span, their blade lengths given: tips seen inside the span do not fold. (Tried, not kept: flash edges out to 0.75
    of the half-span or beyond taken for the span's ends, not tips. Two wrong readings had them at 0.90-0.91, but
    those three right ones and three right low-PRF readings, at 0.93-0.96, had them there too.)"""
    chopping_hz = turn.chopping.value
    if aliased or tips_seen or chopping_hz is None:
        return turn
    seen_deg = 0.0 if elevation_deg is None else _disc_seen_deg(elevation_deg, towards_face_on=False)
    fastest_mps = rotor.MAX_ROTOR_TIP_MPS * np.cos(np.deg2rad(seen_deg))
    span_mps = wavelength_m * prf_hz / 4
    multiples = [k for k in _fold_multiples(chopping_hz, prf_hz=prf_hz, dwell_s=dwell_s, up_to=ONCE_FOLDED_MULTIPLES)
                 if k * chopping_hz <= combs.MAX_CHOP_HZ]
    if span_mps >= fastest_mps or not multiples:
        return turn
    others = " or ".join(f"{k * chopping_hz:.4g}" for k in multiples)
    note = (f"chopping frequency {chopping_hz:.4g} Hz, or {others} Hz, and rotation not estimable: the span reaches "
            f"+-{span_mps:.3g} m/s, under the {fastest_mps:.3g} m/s a rotor's tips may, and the PRF lies within "
            f"{HANN_LOBE_BINS:g} bins of {round(prf_hz / chopping_hz)} times it: tips folded once, unseen, would put "
            f"the lines of a chopping {' or '.join(str(k) for k in multiples)} times faster on the orders of the "
            f"{chopping_hz:.4g} Hz comb that its own lines miss (another PRF tells which)")
    return replace(turn, chopping=Measured(chopping_hz, "ambiguous_period", note),
                   rate=withheld("ambiguous_period", note), rotor_rates_hz=())


def _flashes_between(turn, ramp, *, prf_hz):
    """``turn`` (a :class:`Rotation`), read again where the echo resolved within the ramp (``ramp()``, a
    :class:`~mdpipe.process.flashes.RampTrain`, or None: not read) shows flashes k times as often as its chopping
    allows: equal blades flash once per chopping period P (an even N) or twice (an odd N), so the parts repeating whole
    (:func:`_settled_in_ramp`) at P / k, k up to ``MAX_RAMP_DIVISOR`` and P / k ``flashes.RAMP_MIN_PERIOD_CHIRPS`` or
    longer, with k a multiple of the flashes per chopping period and at least twice it (the count given or measured;
    k of 3 or more where it may be odd), standing over the floor the parts' slow swings may lift every lag to
    (:func:`~mdpipe.process.flashes.ramp_floor`), and, over that floor, at every multiple of P / k with
    ``RAMP_SETTLE_SHARE`` of their repeat at P: an offset d between two trains repeats at d and P - d only (a
    hexarotor's parts repeated at P / 4 with 0.87 of it, at P / 2 with 0.33), and point blades' grating flashes
    within one blade's likewise (a quadrotor of 8-point blades read right at 157.6 Hz: at P / 4 with 1.26 of it, at
    P / 2 with 0.59).

    Flashes shorter than a chirp, sampled every 1 / PRF, are caught whole at some passages only; their flash times
    and folded comb repeat where the sampling comes round again, after k passages, while the ramp's parts show every
    passage that falls within a ramp. Quadrotors of 2 blades at 1.7-4 kHz PRFs, rotors up to 4.4 % apart, were read
    `ok` at a third, a fourth or a fifth of their chopping from flash times or a comb (an unaliased one too: tips seen
    from 85 deg folded unseen), the parts whole at their flash period.

    With the blade count given or measured the chopping is taken at k / (flashes per chopping period) times the
    reading, the rates with it. It is kept as ``ambiguous_period`` (its value; the rate withheld) where the count is
    assumed (its parity says whether the flash rate is the chopping or twice it), and where k is twice the flashes
    per chopping period: rotors at one rate half a flash period apart repeat so too, two of them locked being the
    likeliest, and one rate in a comb does not rule it out (a 94 GHz quadrotor at 223 Hz and a K-band 3-blade one at
    218 Hz, read at half, were so)."""
    chopping_hz = turn.chopping.value
    if chopping_hz is None or turn.chopping.status not in (OK, "assumed_blades") or ramp is None or ramp() is None:
        return turn
    known = turn.n_blades is not None and turn.n_blades_source in ("given", "measured")
    per_chop = rotor.flashes_per_revolution(turn.n_blades) // turn.n_blades if known else 1
    period_chirps = prf_hz / chopping_hz
    divisors = [k for k in range(2 * per_chop if known else 3, MAX_RAMP_DIVISOR + 1, per_chop)
                if period_chirps / k >= RAMP_MIN_PERIOD_CHIRPS]
    settled = _settled_in_ramp(ramp, period_chirps, divisors, prf_hz=prf_hz)
    if settled is None:
        return turn
    k = int(round(period_chirps / settled))
    floor = ramp_floor(ramp(), period_chirps)
    reference = ramp_repeat(ramp(), period_chirps) - floor
    if not (reference > 0 and ramp_repeats_whole(ramp(), settled, shortest_chirps=prf_hz / combs.MAX_CHOP_HZ,
                                                 over_floor=True)):
        return turn  # on the floor the parts' slow swings lift
    if any(not ramp_repeat(ramp(), j * settled) - floor >= RAMP_SETTLE_SHARE * reference for j in range(2, k)):
        return turn  # not at every multiple: an offset between rotors' trains or flashes within a blade's
    found = (f"the echo resolved within the ramp repeats whole every {settled:.3g} chirps, {k} times per period of "
             f"the chopping read: flashes shorter than a chirp caught at some passages only")
    if not known or k == 2 * per_chop:
        if not known:
            times = f"{k} times it (an even blade count) or {k / 2:g} times (an odd one)"
            why = ("the blade count's parity, which tells whether their rate is the chopping or twice it, is not "
                   "known (give --blades)")
        else:
            times, why = "twice it", "or rotors at one rate half a flash period apart"
        note = f"chopping frequency {chopping_hz:.4g} Hz or {times}, and rotation not estimable: {found}, {why}"
        return replace(turn, chopping=Measured(chopping_hz, "ambiguous_period", note),
                       rate=withheld("ambiguous_period", note), rotor_rates_hz=())
    factor = k / per_chop
    odd = "; an odd count flashes twice per chopping period" if per_chop == 2 else ""
    note = (f"{found}; the chopping is {factor:g} times the {chopping_hz:.4g} Hz read ({turn.n_blades} blades "
            f"{turn.n_blades_source}{odd})")
    chopping_hz *= factor
    rate_hz = float(rotor.rotation_rate_from_chopping_hz(chopping_hz, n_blades=turn.n_blades))
    return replace(turn, chopping=Measured(chopping_hz, OK, note), rate=Measured(rate_hz, OK, note),
                   rotor_rates_hz=tuple(factor * r for r in turn.rotor_rates_hz))


def _flashes_in_flanks(turn, flanks, *, prf_hz, mains_hz=(), own_power=None, body_hz=None, body_spread_hz=0.0):
    """``turn`` (no flashes found in the target's own bin), or blade flashes found in its range flanks (``flanks()``,
    :func:`mdpipe.process.flashes.flank_flash_period`): the chopping and rate withheld as ``ambiguous_period``, a
    drone's flashes seen, the period they recur at a whole multiple of the chopping period; where the flanks repeat
    at no period alike, a line both flanks' powers share tells them (:func:`_line_in_flanks`). The wings are not read
    then: flashes on both flanks at once, recurring faster than 40 Hz, are no wings' echo. Read only about a body
    line (the caller asks): a detection without one may itself be one side's flashes, whose "flanks" hold the other
    side's and the hub (low-PRF seed 555, scene 84: such an image read so was taken for the hub between its images,
    and the drone's row moved 5.7 m off it). Nor where the flanks repeat with the grid (``mains_hz``,
    :func:`mdpipe.process.mains.repeats_with_grid`): a supply's ripple on the gain swells every static echo in them
    alike (`make bench-impairments`: a K-band sparrow beside clutter read a drone whose flanks recurred every 20 ms
    under a 1 % ripple, its own echo too faint for the hum to be found there), nor where what every range bin holds
    in common (``flanks().common``) recurs a whole number of times as often or as seldom: another radar's bursts,
    too few to count the capture crossed, or a ripple at a frequency not searched, light both flanks alike (a W-band
    sparrow under bursts every 9.7 chirps, 0-7 of them counted, read a drone). A drone whose flashes light every bin
    recurs there too: it keeps the reading of its own bin.

    At a low PRF and a long ramp a blade's flash lands metres off its drone, and the drone's own bin keeps its body
    line and little else (the low-PRF sweep at seed 556: 22 of the 140 drones whose tips land 4-32 bins off and whose
    lines a measurement can see read ``none`` or ``bird`` for no flashes; a K-band quadrotor's flashes spread 21 dB
    over the noise across +-8 m of range, its own bin's body line 15 dB over them)."""
    read = flanks()
    period_s = flank_flash_period(read.power, prf_hz=prf_hz, min_period_s=1.0 / combs.MAX_CHOP_HZ)
    if period_s is None:
        return _line_in_flanks(turn, read, prf_hz=prf_hz, mains_hz=mains_hz, own_power=own_power, body_hz=body_hz,
                               body_spread_hz=body_spread_hz)
    if mains.repeats_with_grid(period_s, mains_hz):
        return turn
    common = None if read.common is None else period_of_power(np.asarray(read.common, dtype=np.float64),
                                                               prf_hz=prf_hz, min_period_s=1.0 / combs.MAX_CHOP_HZ)
    if common is not None and whole_ratio_apart(period_s, common.period_s):
        return turn
    note = (f"rotation not estimable: blade flashes recur every {period_s * 1e3:.3g} ms in the range bins either "
            "side of the target, where a long ramp moves its blades' flashes (their Doppler times the ramp), none in "
            "its own; flashes shorter than a chirp recur where the chirps catch them alike again, and one blade "
            f"differing repeats once a turn: the chopping is a whole multiple of {1 / period_s:.4g} Hz, which one the "
            "flanks do not tell")
    return Rotation.withheld("ambiguous_period", note)


def _line_in_flanks(turn, read, *, prf_hz, mains_hz=(), own_power=None, body_hz=None, body_spread_hz=0.0):
    """``turn``, or the chopping and rate withheld as ``ambiguous_period`` where a line that both range flanks' powers
    share (``read``: a :class:`~mdpipe.process.ranging.Flanks`) tells blade flashes
    (:func:`mdpipe.process.flashes.flank_line_hz`: rotors at rates apart, their trains interleaved), over the fastest
    wingbeat's harmonics (``1 / flashes.MAX_POWER_PERIOD_S``) and up to ``combs.MAX_CHOP_HZ``: not lit in every range
    bin, nor carried from the target's own power ``own_power`` (per chirp) by the range window's sidelobes
    (``read.leak_db``), nor on the beats of its body's Doppler ``body_hz`` (spread over ``body_spread_hz``), nor on
    the grid's harmonics (``mains_hz``)."""
    line_hz = flank_line_hz(read.power, prf_hz=prf_hz, min_hz=1.0 / MAX_POWER_PERIOD_S, max_hz=combs.MAX_CHOP_HZ,
                            common=read.common, own=own_power, leak_db=read.leak_db, body_hz=body_hz,
                            body_spread_hz=body_spread_hz, mains_hz=mains_hz)
    if line_hz is None:
        return turn
    note = (f"rotation not estimable: the power of the range bins either side of the target, where a long ramp "
            f"moves its blades' flashes (their Doppler times the ramp), shares a line at {line_hz:.4g} Hz, though "
            "the two repeat at no period alike (rotors at rates apart interleave their flashes): flashes recur at a "
            "chopping frequency whose multiple, folded by the PRF, lies there; which one the flanks do not tell")
    return Rotation.withheld("ambiguous_period", note)


def _views_without_hum(flash_views, hum, *, prf_hz):
    """The target's :class:`~mdpipe.process.ranging.FlashViews` (``flash_views()``) with ``hum``'s lines taken out of
    each column, as out of the echo."""
    views = flash_views()
    return replace(views, parts=mains.without_hum(views.parts, hum, prf_hz=prf_hz),
                   sides=mains.without_hum(views.sides, hum, prf_hz=prf_hz))


def _on_hum(turn, hum, *, body_hz, prf_hz):
    """``turn`` (a :class:`Rotation`), withheld (``mains.STATUS``) where its chopping comb, lines at ``body_hz`` plus
    its multiples, fell on the notches that took the mains ``hum`` out (:meth:`mains.Hum.covers`): a rotor held
    still at a multiple of the grid's rate gives the lines hum gives, and the lines that told it went with the
    hum."""
    chop_hz = turn.chopping.value
    if chop_hz is None or not hum.covers(body_hz, chop_hz, prf_hz=prf_hz):
        return turn
    return Rotation.withheld(mains.STATUS, f"rotation not estimable: the lines of the chopping frequency read, "
                             f"{chop_hz:.1f} Hz, fell on the harmonics of the mains hum at {hum.f0_hz:.2f} Hz taken "
                             "out of the echo (a rotor held at a multiple of the grid's rate shares them; "
                             "--mains-hz none keeps them)")


def _undersampled_wings(measured, why):
    """A wing reading (wingbeat, flapping share, stroke) of an echo without range whose span cannot hold a rotor's tips
    (``why``: :func:`hidden_aliasing_note`), its status made ``undersampled``: all such a span shows of a drone is its
    blades' inner parts, which beat at the rotors' rate differences as wings do (three 94 GHz multirotors recorded
    through a filter at 8.8-11.8 kHz read as birds beating 11.7-17.9 Hz, ``make offmodel-cw``)."""
    if measured.value is None:
        return measured
    note = (f"wings not told from rotors: {why}, and a drone's inner blades, all such a span shows of them, beat as "
            "wings do")
    return Measured(measured.value, "undersampled", "; ".join(n for n in (measured.note, note) if n))


def doppler_band(signal, demodulated, *, prf_hz, wavelength_m, noise_power, hidden_aliasing=None):
    """Occupied micro-Doppler band of the body-demodulated echo and whether it aliases.

    The half-width is taken about the band's centre, so a bird's own flight speed does not count when
    no body line was found to demodulate. Aliased (the half-width then only a lower bound, ``PRF / 2``):
    the band fills the span or reaches both ends, or the brightest 64-chirp frames fill it, or, the noise read
    from the echo, ``hidden_aliasing`` says why the band may alias unseen (:func:`hidden_aliasing_note`).
    """
    plain = doppler.power_spectrum(signal, prf_hz=prf_hz)
    compensated = doppler.power_spectrum(demodulated, prf_hz=prf_hz)
    band = spectral.occupied_band(compensated, doppler.noise_level_per_bin(noise_power, len(signal)),
                                  smooth_hz=max(prf_hz / 200, 4 * compensated.resolution_hz))
    reason = band.reason if band.aliased else None
    if reason is None:
        strobe = spectral.flash_edges(difference(demodulated), prf_hz=prf_hz, window_s=ALIAS_CHECK_CHIRPS / prf_hz,
                                      noise_power=noise_power, differenced=True)
        if strobe.fills_span:
            reason = (f"the brightest frames fill the span 1/Tp = {prf_hz:.0f} Hz in {strobe.n_filled} of "
                      f"{strobe.n_frames}")
        elif hidden_aliasing is not None:  # the band shows no aliasing: its half-width is not known
            return DopplerBand(plain, prf_hz / 2, True, withheld("undersampled", f"micro-Doppler half-width not "
                                                                 f"known: {hidden_aliasing}"), prf_hz / 2)
    if reason is not None:
        return DopplerBand(plain, prf_hz / 2, True,
                           Measured(_speed_mps(prf_hz / 2, wavelength_m), "aliased",
                                    f"micro-Doppler half-width at least the span's: aliased ({reason})"), prf_hz / 2)
    if not np.isfinite(band.low_hz):
        return DopplerBand(plain, 0.0, False, withheld("no_signal", "no micro-Doppler band 10 dB above the noise"))
    half_width_hz = (band.high_hz - band.low_hz) / 2
    dense_hz = (band.dense_high_hz - band.dense_low_hz) / 2 if np.isfinite(band.dense_low_hz) else 0.0
    return DopplerBand(plain, half_width_hz, False, Measured(_speed_mps(half_width_hz, wavelength_m)), dense_hz)


def paper_bandwidth(demodulated, *, prf_hz, threshold_db, body_doppler_hz, aliased):
    """The paper's bandwidth rule on ``BANDWIDTH_SEGMENT_S`` segments; returns (Measured, (low_hz, high_hz)).

    The rule (spectrum above its mean by ``threshold_db``) applied to a whole dwell depends on the
    dwell: the mean falls as lines sharpen (a 10 s dwell of a drone gave 1-2 Hz where 1.5 s pieces gave
    1.8 kHz). On fixed-length segments of the body-demodulated echo it is one defined measurement;
    the median of the segments' edges is reported, shifted back by the body Doppler. Withheld when
    only the body line crosses the threshold.
    """
    if aliased:
        return withheld("aliased", "Doppler bandwidth not estimable: aliased"), None
    n = int(round(BANDWIDTH_SEGMENT_S * prf_hz))
    if len(demodulated) < n:
        return withheld("dwell_short", f"Doppler bandwidth not estimable: the paper's rule is applied to "
                        f"{BANDWIDTH_SEGMENT_S:g} s segments, longer than the dwell"), None
    extents = [spectral.paper_extent(doppler.power_spectrum(demodulated[start:start + n], prf_hz=prf_hz),
                                     threshold_db=threshold_db)
               for start in range(0, len(demodulated) - n + 1, n // 2)]
    extents = [e for e in extents if e is not None]
    if not extents:
        return withheld("below_threshold", f"Doppler bandwidth not estimable: nothing {threshold_db:g} dB above "
                        "the spectrum's mean"), None
    low, high = np.median(extents, axis=0)
    if high - low <= 4 * prf_hz / n:  # the body line's Hann main lobe
        return withheld("body_only", f"Doppler bandwidth not estimable: only the body line stands {threshold_db:g} dB "
                        "above the spectrum's mean"), None
    return Measured(float(high - low)), (float(low + body_doppler_hz), float(high + body_doppler_hz))


@dataclass(frozen=True)
class Rotation:
    """Chopping frequency, rotation rate (with the blade count it rests on) and the rotors resolved."""

    chopping: Measured
    rate: Measured
    rotor_rates_hz: tuple = ()
    n_blades: int = None
    n_blades_source: str = None

    @classmethod
    def withheld(cls, status, note):
        """Chopping and rate both withheld with ``status`` and ``note``."""
        return cls(withheld(status, note), withheld(status, note))


def _time_domain_chopping_hz(demodulated, *, aliased, half_width_hz, prf_hz, noise_power, min_hz, ramp=None):
    """Chopping (unaliased: the echo's period) or flash rate (aliased: flash timing) in Hz, None, or an ambiguity.

    Returns (frequency_hz or None, note, rates_hz): a note names an ambiguity the flash times could not settle,
    unless the echo resolved within the ramp (``ramp()``, a :class:`~mdpipe.process.flashes.RampTrain`, or None)
    repeats whole at one of the two periods (:func:`~mdpipe.process.flashes.ramp_repeats_whole`); ``rates_hz`` then
    holds the two flash rates it leaves (else empty).
    """
    if aliased:
        found = flash_period(difference(demodulated), prf_hz=prf_hz, min_period_s=1.0 / combs.MAX_CHOP_HZ,
                             max_period_s=1.0 / min_hz, noise_power=2 * noise_power)  # a difference doubles noise
        if found is None:
            return None, None, ()
        settled = found.ambiguous and _settled_in_ramp(ramp, found.period_s * prf_hz,
                                                       (1, found.ambiguous), prf_hz=prf_hz)
        if settled:
            return prf_hz / settled, None, ()
        if found.ambiguous:
            return None, (f"the flash times fit {found.period_s * 1e3:.3g} ms and, by their pairs, "
                          f"{found.period_s * 1e3 / found.ambiguous:.3g} ms (flashes shorter than a chirp are sampled "
                          "stroboscopically; a longer dwell or a higher PRF tells them apart)"), (
                1.0 / found.period_s, found.ambiguous / found.period_s)
        return 1.0 / found.period_s, None, ()
    micro = highpass(demodulated, prf_hz=prf_hz, cutoff_hz=HIGHPASS_SHARE * half_width_hz)
    found = find_period(micro, sample_rate_hz=prf_hz, min_period_s=1.0 / combs.MAX_CHOP_HZ,
                        max_period_s=1.0 / min_hz)
    if found is None or found.strength < MIN_ROTOR_PERIODICITY:
        return None, None, ()
    return 1.0 / found.period_s, None, ()


def demodulated_parts(parts, track_hz, *, prf_hz):
    """Each column of ``parts`` (slow time in ramp parts, or at range sides) demodulated by the body's Doppler
    track (None: as is)."""
    return parts if track_hz is None else doppler.demodulate(parts, track_hz, prf_hz=prf_hz)


def _settled_in_ramp(ramp, period_chirps, divisors, *, prf_hz):
    """The first of ``period_chirps / k`` (k in ``divisors``) at which the echo resolved within the ramp
    (``ramp()``, or None: none) repeats whole, in chirps, else None. One the ramp cannot tell does not stop the
    search (flashes every 25 chirps, whole ramps repeating at 75: 37.5 cannot be told, 25 is whole). A period / k
    is tried only where it repeats with ``flashes.RAMP_SETTLE_SHARE`` of the period's repeat: a partial repeat
    within a period (grating flashes of point blades a third of it apart, 0.63 of it) is not one."""
    if ramp is None or ramp() is None:
        return None
    shortest = prf_hz / combs.MAX_CHOP_HZ
    reference = ramp_repeat(ramp(), period_chirps)
    for divisor in divisors:
        candidate = period_chirps / divisor
        if candidate < shortest or (divisor > 1 and not ramp_repeat(ramp(), candidate)
                                    >= RAMP_SETTLE_SHARE * reference):
            continue  # flashes resolved within the ramp repeat alike at their period and its multiples
        if ramp_repeats_whole(ramp(), candidate, shortest_chirps=shortest):
            return candidate
    return None


def resolved_in_ramp(found, ramp, *, prf_hz):
    """The echo's power period ``found`` (a :class:`~mdpipe.process.flashes.PowerPeriod` or None), settled by
    the echo resolved within the ramp (``ramp``: a cached callable giving its
    :class:`~mdpipe.process.flashes.RampTrain`, or None).

    Read from whole ramps, flashes shorter than a chirp may repeat whole only at a multiple of their period, and a
    period that repeats whole there may yet hold a weak shorter one (:class:`~mdpipe.process.flashes.PowerPeriod`).
    Resolved within the ramp: the period, or else the first of its halves to sixths, that repeats whole there is
    taken as whole (:func:`~mdpipe.process.flashes.ramp_repeats_whole`); one found not whole there, a shorter
    repeat seen, is not; where the ramp cannot tell, ``found`` stands.
    """
    if found is None or ramp is None or ramp() is None:
        return found
    period = found.period_s * prf_hz
    verdict = ramp_repeats_whole(ramp(), period, shortest_chirps=prf_hz / combs.MAX_CHOP_HZ)
    if verdict is None:
        return found
    if verdict:
        return PowerPeriod(found.period_s, True)
    settled = _settled_in_ramp(ramp, period, range(2, MAX_RAMP_DIVISOR + 1), prf_hz=prf_hz)
    return PowerPeriod(settled / prf_hz, True) if settled else PowerPeriod(found.period_s, False)


def _power_flashes(found, *, n_blades, alternate=lambda period_s: False):
    """Rotation from blade flashes that show only in the echo's power (too weak for flash times or line combs):
    ``found``, the power's :class:`~mdpipe.process.flashes.PowerPeriod` or None (then None).

    The power of N equal blades repeats once per chopping period for an even N. For an odd N it repeats twice
    or once (the approaching and the receding blade flash alike, or, off the range bin's centre, not), and with
    one blade differing once a turn. So the power's period is the chopping period for an even N given and a
    power that repeats whole (:class:`~mdpipe.process.flashes.PowerPeriod`: one blade differing shows a repeat
    at the chopping period within the turn's), and half of it where, N odd or not given, its flashes alternate
    between the target's range sides (``alternate(period_s)``, :func:`~mdpipe.process.flashes.sides_alternate`:
    an odd N's approaching and receding blades by turns; the rate then under N = 3 assumed where N is not given);
    otherwise rotation is withheld as ``ambiguous_period``.
    """
    if found is None:
        return None
    if found.whole and n_blades is not None and n_blades % 2 == 0:
        chopping_hz = 1.0 / found.period_s
        rate_hz = float(rotor.rotation_rate_from_chopping_hz(chopping_hz, n_blades=n_blades))
        return Rotation(Measured(chopping_hz), Measured(rate_hz), (), n_blades, "given")  # no rotor resolved
    if found.whole and (n_blades is None or n_blades % 2) and alternate(found.period_s):
        chopping_hz = 0.5 / found.period_s
        blades = n_blades or ASSUMED_ODD_BLADES
        rate_hz = float(rotor.rotation_rate_from_chopping_hz(chopping_hz, n_blades=blades))
        if n_blades is not None:
            return Rotation(Measured(chopping_hz), Measured(rate_hz), (), n_blades, "given")
        rate = Measured(rate_hz, "assumed_blades", f"rotation rate assumes N = {blades} blades (the flashes "
                        "alternate range sides: an odd count, 3 or 5 alike; give --blades)")
        return Rotation(Measured(chopping_hz), rate, (), blades, "assumed")
    if not found.whole:
        why = "it repeats in part at other lags: flashes of rotors a phase apart, or a multiple of the flash period"
    elif n_blades is None:
        why = "it is the chopping period for an even blade count (give --blades)"
    else:
        why = "an odd blade count's power repeats once or twice per chopping period"
    note = (f"rotation not estimable: the echo's power repeats every {found.period_s * 1e3:.3g} ms like blade "
            f"flashes, too weak for the flash times or line combs that tell the chopping frequency; {why}")
    return Rotation.withheld("ambiguous_period", note)


def _folded_comb_by_power(found, comb_hz, *, n_blades):
    """The chopping frequencies of a folded comb (spacings ``comb_hz``) that the echo's power period confirms for
    the blade count ``n_blades`` (given or measured), else None (:func:`_folded_comb_at_rate`). Only a power that
    repeats whole (``found``, a :class:`~mdpipe.process.flashes.PowerPeriod` or None) is read.
    """
    if found is None or not found.whole:
        return None
    return _folded_comb_at_rate(1.0 / found.period_s, comb_hz, n_blades=n_blades)


def _folded_comb_by_flash_times(rates_hz, comb_hz, *, n_blades, power, prf_hz, dwell_s):
    """The chopping frequencies of a folded comb (spacings ``comb_hz``) that the two flash rates an unsettled
    flash-time ambiguity leaves (``rates_hz``) confirm for the blade count ``n_blades`` (given or measured), where
    every rate that confirms it gives the same (:func:`_folded_comb_at_rate`); else None.

    The comb and the flash times are read apart (lines in the dwell's spectrum, flashes in time), so a comb that a
    flash rate confirms for the N known is the rotors' (four 3-blade rotors at 94 GHz, N measured: their combs at the
    turn rates, every third line standing out on each, and flash times at 5.8 ms or, by their pairs, 1.93 ms: twice
    the chopping). Not where the echo's power (``power``, a :class:`~mdpipe.process.flashes.PowerPeriod` or None)
    repeats whole: it did not confirm the comb (:func:`_folded_comb_by_power`), and it outweighs flash times; nor
    where the comb's spacing or the rate lies on the PRF's grid (:func:`_on_span_grid`): both may then be one
    stroboscopic repeat (two rotors at 90 rev/s, 2 blades, sampled at PRF / 75.7 folded a comb to PRF / 227, and
    their flash times to it or 6x it; the power repeated whole at 3x it, the chopping)."""
    if (power is not None and power.whole) or _on_span_grid(float(np.median(comb_hz)), prf_hz=prf_hz, dwell_s=dwell_s):
        return None
    off_grid = [rate_hz for rate_hz in rates_hz if not _on_span_grid(rate_hz, prf_hz=prf_hz, dwell_s=dwell_s)]
    confirmed = [c for c in (_folded_comb_at_rate(rate_hz, comb_hz, n_blades=n_blades) for rate_hz in off_grid)
                 if c is not None]
    if not confirmed:
        return None
    return confirmed[0] if all(np.allclose(c, confirmed[0]) for c in confirmed) else None


def _folded_comb_at_rate(rate_hz, comb_hz, *, n_blades):
    """The chopping frequencies of a folded comb (spacings ``comb_hz``) that blade flashes at ``rate_hz`` confirm for
    the blade count ``n_blades`` (given or measured), else None.

    The power of N blades repeats 1 (even N) or 1-2 (odd N) times per chopping period; the comb is the
    chopping frequency or, one blade differing, the turn rate. With N, the flashes' rate over the comb's
    tells which: 1 or 2 (odd N) times it, the chopping; N or 2N (odd N) times, the turn rate.
    """
    if n_blades is None:
        return None
    ratio = rate_hz / float(np.median(comb_hz))
    per_chop = rotor.flashes_per_revolution(n_blades) // n_blades
    for factor, chopping_hz in ((1, comb_hz), (per_chop, comb_hz), (n_blades, comb_hz * n_blades),
                                (per_chop * n_blades, comb_hz * n_blades)):
        if _agrees(ratio, factor):
            return chopping_hz
    return None


def _agrees(ratio, factor=1.0):
    """Whether ``ratio`` is ``factor`` within ``AGREEMENT``."""
    return abs(ratio / factor - 1) <= AGREEMENT


def _whole_ratio(ratio):
    """The whole number k (2..6) with ratio ~ k or 1/k, else 0."""
    for k in range(2, 7):
        if _agrees(ratio, k) or _agrees(ratio * k):
            return k
    return 0


ODD_FLASH_SAMPLING = (3, 5)  # an odd N's flash times caught at one passage in m, m these (2/m of its chopping) ...
ODD_FLASH_TOLERANCE = 0.05   # ... within 5 %: rotors up to 5 % apart in rate blend the comb and the flash times
                             # differently (157 Hz and 107.7 Hz, 2.7 % off two thirds)


def _odd_flashes_sampled(ratio, *, odd, comb_hz, timed_hz):
    """Rotation withheld as ``ambiguous_period`` where an aliased echo's flash times (``timed_hz``) are ``2 / m`` times
    its folded comb (``comb_hz``, ``ratio`` the first over the second; m in ``ODD_FLASH_SAMPLING``, within
    ``ODD_FLASH_TOLERANCE``) and the blade count is odd (``odd()``: given, measured, or the flashes alternating range
    sides; asked only for such a ratio); else None.

    An odd N flashes twice per chopping period, and flashes shorter than a chirp, caught at one passage in m only,
    time at 2 / m of the chopping: the comb is the chopping. Or the flash times are whole, the chopping half their
    rate, and the comb lies at m times it (folded lines coinciding). Both were seen on quadrotors of 3-blade rotors at
    53 rev/s: at an X-band PRF of 3.3 kHz, their tips folded, combed at 157 Hz (159 true) and timed at 107.7 Hz (two
    thirds), read 53.8 Hz from the flash times; at 77 GHz and 17.4 kHz timed at 319 Hz (twice the chopping, right)
    and combed at 798 Hz (five times). The dwell does not tell which. Even counts are left to the flash times: equal
    blades flash once per chopping period, caught at one passage in m at 1 / m of it, never 2 / m; a comb lining the
    turn rate (one blade differing, half the chopping) would give 2 / 3 too, but six 2-blade rotors of the default
    sweep timed at 93.7 Hz on a folded comb at 140.7 Hz were right from the flash times."""
    if ratio >= 1:
        return None
    m = next((m for m in ODD_FLASH_SAMPLING if abs(ratio * m / 2 - 1) <= ODD_FLASH_TOLERANCE), None)
    if m is None or not odd():
        return None
    note = (f"rotation not estimable: the line comb says {comb_hz:.4g} Hz and the flash times {timed_hz:.4g} Hz, 2/{m} "
            f"of it: an odd blade count's flashes (twice per chopping period) caught at one passage in {m}, or a "
            f"chopping of {timed_hz / 2:.4g} Hz whose folded lines coincide on a comb {m} times it; the dwell does "
            "not tell which")
    return Rotation.withheld("ambiguous_period", note)


def _chopping_from_flash_rate(flash_rate_hz, *, n_blades, alternating):
    """The chopping frequency (one-element array) from an aliased echo's flash rate: 2N flashes a turn for an
    odd N (given, or, none given, flashes ``alternating`` range sides), N for an even one (or none given and
    nothing telling: the caller marks it assumed)."""
    odd = n_blades % 2 == 1 if n_blades is not None else alternating
    return np.array([flash_rate_hz / 2 if odd else flash_rate_hz])


PHASED_ROTORS = 4  # rotors at one rate, phases apart, flash this many times per chopping period (a quadrotor)


def rotation(demodulated, *, aliased, half_width_hz, prf_hz, noise_power, n_blades, dwell_s, halfwidth_mps,
             dense_half_width_hz, body_found=True, elevation_deg=None, ramp=None, sides=None):
    """Rotation of the rotors from their line combs and from the echo's period (or flash times when aliased).

    * The combs (:mod:`mdpipe.process.combs`) give each resolvable rotor's chopping frequency ``N f_i``.
    * The time domain gives the echo's period (well-sampled flashes) or the flash period (aliased:
      flashes shorter than a chirp, seen stroboscopically).
    When both are found they must agree within ``AGREEMENT`` (the time domain then refines a single
    rotor's value: it averages over the whole dwell); a whole-number ratio is an ambiguity and
    nothing is reported, unless the comb is unfolded, every k-th of its lines stands out and the echo's rate is
    k times its spacing: the chopping is then the echo's rate, the rate the comb's under N = k assumed (the
    least count: one blade differing), or the comb is folded at a whole fraction of flash times at which the power
    repeats whole (rotors whose lines between the comb's cancel flash a whole number of times per comb period, but
    their power does not repeat whole at the flashes), or at three times flash times at which the power resolved
    within the ramp repeats whole, the gaps between ramps too short to hide the passages between theirs (N not
    given odd: :func:`_no_passages_hidden`): the flash times stand; or the comb is unfolded, the echo's period at no
    whole ratio to it, and the power repeats whole at it (:func:`_comb_agrees_with_power`): the comb stands. Flash
    times twice a folded comb are an odd N (flashing twice per chopping period) or an even N with one blade differing
    (the comb lines the turn rate): the blade count, given or measured, tells which, or every second line of the
    comb standing out (a turn of 2 blades, one differing; not where the chopping comb folded once falls on the comb's
    odd orders, :func:`_folds_onto_odd_orders`); without them nothing is reported. Flash times alternating
    range sides (an odd N) at 2k times a folded comb whose every k-th line stands out measure N = k (the comb the turn
    rate, one blade differing). A folded comb without
    flash times is taken where, N given or measured, the power repeating whole (:func:`_folded_comb_by_power`) or
    one of the two rates a flash-time ambiguity leaves (:func:`_folded_comb_by_flash_times`) confirms it. A
    chopping frequency that rests on an assumed blade parity carries ``assumed_blades``. A comb narrower in Doppler
    than any blade turning that fast could make at the elevation given (:func:`least_tip_speed_mps`) is not a rotor.
    A comb whose every k-th line stands out, read neither as a turn (blade count given or measured, see
    :func:`_comb_blades`: among others, rotors drifting apart on a comb that stands for them) nor by the echo's rate,
    is a turn of k blades (one differing, the chopping k times the spacing) or rotors at one rate cancelling the lines
    between (the chopping the spacing): withheld as ``ambiguous_period`` (four 4-blade rotors 78-82 rev/s apart,
    unresolved in 0.1 s, read 78 Hz for 321).
    An aliased comb spacing or flash rate that is the PRF over a whole number, which the power's period does not
    settle, is withheld as ``ambiguous_period`` (:func:`_span_ambiguity`: its multiples fold onto it).
    Blade count ``n_blades`` given, or (None) measured from the echo where it tells (imbalance lines), else
    assumed (odd where the flashes alternate sides of the span); those tests read the lines within
    ``dense_half_width_hz`` (the band's dense part): the single lines beyond it, searched for combs, carry the
    rotors' mutual beats as much as a blade pattern (read there, N came out 3 and 5 for 2-blade rotors).
    With N given, no comb is searched beyond N times the fastest rotor rate
    (:func:`mdpipe.process.combs.max_chop_hz`): six rotors' smeared lines seen 0.12 s read a 3-line comb at 1623 Hz
    for 173, with 2 blades 812 rev/s. Without a body line (``body_found`` False) the comb is first centred on the
    Doppler it lies about (:func:`mdpipe.process.combs.comb_offset_hz`). An unfolded comb with lines as strong
    between its own is read at the echo's fundamental where the power flashes at it (:func:`_comb_multiple`); one
    slower than any rotor chops (a wingbeat's lines) is withheld as ``no_flashes``, the wingbeat left to be read. An
    unfolded comb whose power repeats at no whole ratio to it is read at the one chopping frequency both allow for
    the blade count (:func:`_chopping_by_power`), else withheld (:func:`_comb_against_power`). The echo's period
    alone, in a band that fills most of the span, is withheld (:func:`_period_made_whole`). Where no comb holds
    within an unaliased band,
    one of single lines each under the band's threshold is searched over the span (:func:`_comb_beyond_band`); the
    flashes' Doppler sides (blade parity, a power in time, not a line pattern) are then read out to its extent.
    A chopping frequency the dwell holds fewer than ``2 PHASED_ROTORS`` periods of is withheld as ``ambiguous_period``
    (blade flashes found, their period untold: a drone still): a
    quadrotor's four rotors at one rate, phases apart, flash four times per chopping period, and a dwell that does not
    hold that period twice cannot tell (the Phantom 4 of paper config 7 seen 8 ms: its rotors' flashes 1.46 ms apart
    read as a comb at 683 Hz for 140, `ok`).
    """
    slowest_hz = max(combs.MIN_CHOP_HZ, 2.0 / dwell_s)  # two chopping periods in the dwell
    if slowest_hz >= combs.MAX_CHOP_HZ / 2:
        note = f"rotation not estimable: dwell {dwell_s:.3g} s is too short for two chopping periods of any rotor"
        return Rotation.withheld("dwell_short", note)
    band_hz = prf_hz / 2 if aliased else half_width_hz
    count_band_hz = band_hz if aliased else min(dense_half_width_hz, band_hz)
    sides_band_hz = count_band_hz  # where the flashes' Doppler sides are read (blade parity)
    micro = demodulated - np.mean(demodulated)  # the body, demodulated to 0 Hz; combs score lines from f_chop up
    if not body_found and not aliased:  # rotating parts alone: their comb lies about the body's Doppler
        offset_hz = combs.comb_offset_hz(micro, prf_hz=prf_hz, noise_power=noise_power, half_width_hz=band_hz)
        if offset_hz is not None:
            micro = micro * np.exp(-2j * np.pi * offset_hz * np.arange(len(micro)) / prf_hz)
    lines = combs.line_spectrum(micro, prf_hz=prf_hz, noise_power=noise_power)  # shared by the comb and N tests
    # the echo's power period, read only where a path needs it (an FFT of the dwell: 24 ms for 35k chirps)
    power = functools.cache(lambda: resolved_in_ramp(power_period(difference(demodulated), prf_hz=prf_hz,
                                                                  min_period_s=1.0 / combs.MAX_CHOP_HZ),
                                                     ramp, prf_hz=prf_hz))
    # flashes every period_s alternating between the target's range sides: an odd N's (read only where asked)
    alternate = functools.cache(lambda period_s: sides is not None and sides_alternate(sides(), period_s * prf_hz))
    fastest_hz = combs.max_chop_hz(n_blades)  # a comb wider than a given count's chopping at the top rate is not it
    comb = combs.find_combs(micro, prf_hz=prf_hz, noise_power=noise_power, half_width_hz=band_hz, min_hz=slowest_hz,
                            max_hz=fastest_hz, lines=lines)
    if comb is not None and not aliased and (multiple := _comb_multiple(lines, float(comb[0]), band_hz=band_hz,
                                                                        dwell_s=dwell_s)):
        if comb[0] / multiple < combs.MIN_CHOP_HZ:
            note = (f"rotation not estimable: the line comb at {comb[0]:.4g} Hz holds lines as strong between its own, "
                    f"the harmonics of a repeat at {comb[0] / multiple:.3g} Hz, slower than any rotor chops (a "
                    "wingbeat's)")
            return Rotation.withheld("no_flashes", note)
        if _power_at_fundamental(power(), float(comb[0]) / multiple, multiple):
            comb = tuple(spacing / multiple for spacing in comb)  # the echo's fundamental
    if aliased and comb is not None and (held := _span_ambiguity("folded line comb", float(comb[0]), prf_hz=prf_hz,
                                                                   dwell_s=dwell_s, power=power)):
        return held
    if comb is None and not aliased:
        comb, extent_hz = _comb_beyond_band(micro, lines, band_hz=band_hz, prf_hz=prf_hz, noise_power=noise_power,
                                            min_hz=slowest_hz, max_hz=fastest_hz)
        if comb is not None:
            sides_band_hz = extent_hz
            if halfwidth_mps is not None and band_hz > 0:  # its reach, for the blade reach test
                halfwidth_mps *= max(1.0, extent_hz / band_hz)
    timed_hz, ambiguity, ambiguous_rates_hz = _time_domain_chopping_hz(
        demodulated, aliased=aliased, half_width_hz=half_width_hz, prf_hz=prf_hz, noise_power=noise_power,
        min_hz=slowest_hz, ramp=ramp)
    if ambiguity is not None and comb is None:
        note = f"rotation not estimable: {ambiguity}"
        return Rotation.withheld("ambiguous_period", note)
    chopping_hz, measured_n, pattern, least_n, flashes_only, alternating = None, None, None, None, False, False
    comb_note = ""  # how a comb stood against the echo's period, for the rate's note (ok or assumed)

    def by_flash_times():
        """(withheld Rotation or None, chopping frequency, flashes alternating range sides) from the aliased
        echo's flash times alone (:func:`_span_ambiguity`, :func:`_chopping_from_flash_rate`)."""
        held = _span_ambiguity("flash times", timed_hz, prf_hz=prf_hz, dwell_s=dwell_s, power=power)
        if held:
            return held, None, False
        if n_blades is not None and n_blades % 2 and sides is not None and sides_flash_apart(sides(),
                                                                                           prf_hz / timed_hz):
            return _flash_times_of_each_side(timed_hz, n_blades=n_blades), None, False
        odd_shown = n_blades is None and alternate(1.0 / timed_hz)
        return None, _chopping_from_flash_rate(timed_hz, n_blades=n_blades, alternating=odd_shown), odd_shown

    if comb is not None:
        chopping_hz, measured_n, pattern = _comb_blades(micro, lines, np.array(comb), aliased=aliased, prf_hz=prf_hz,
                                                        band_hz=count_band_hz, n_blades=n_blades, power=power,
                                                        noise_power=noise_power, on_body=body_found)
    if chopping_hz is not None and timed_hz is not None:
        centre = float(np.median(chopping_hz))
        ratio = timed_hz / centre
        if aliased and _agrees(ratio, 2):
            # the flash times twice the comb: an odd N flashes twice per chopping period (the comb is the
            # chopping), or the comb is the turn rate of an even N with one blade differing (the flash times are)
            known = n_blades if n_blades is not None else measured_n
            if known is None and alternate(1.0 / timed_hz):  # the flashes alternate range sides: an odd N
                known, alternating = ASSUMED_ODD_BLADES, True
            if known is None and pattern == 2 and not _folds_onto_odd_orders(float(chopping_hz[0]), prf_hz=prf_hz,
                                                                             dwell_s=dwell_s):
                # every second line of the comb stands out: the turn of 2 blades, one differing, which flash together
                # twice a turn (the flash times); an odd N's equal blades line their chopping comb without that step
                known = measured_n = 2
            if known is None:
                note = (f"rotation not estimable: the flash times say {timed_hz:.4g} Hz and the line comb {centre:.4g} "
                        "Hz: an odd blade count flashes twice per chopping period, an even one with a blade differing "
                        "lines its turn rate; the blade count tells which (give --blades)")
                return Rotation.withheld("ambiguous_period", note)
            if known % 2:
                timed_hz, ratio = timed_hz / 2, ratio / 2
            else:
                chopping_hz, ratio = np.array([timed_hz]), 1.0
        if _agrees(ratio):
            odd_shown = ASSUMED_ODD_BLADES if alternating else None  # flashes alternating range sides
            if aliased and (held := _flashes_missed(power(), timed_hz, n_blades=next(
                    (n for n in (n_blades, measured_n, odd_shown) if n is not None), None))):
                return held
            if len(chopping_hz) == 1:
                chopping_hz = np.array([timed_hz])
        elif measured_n and _agrees(ratio * measured_n):
            # one blade differs: the echo repeats once a turn, the comb is its N-fold chopping
            if len(chopping_hz) == 1:
                chopping_hz = np.array([timed_hz * measured_n])
        elif (not aliased and n_blades is None and measured_n is None and ratio > 1 and (k := _whole_ratio(ratio))
              and pattern == k):
            # every k-th line of the (strongest) comb stands out and the echo repeats k times per comb period: the
            # echo's rate is the chopping; the comb a turn of k blades, one differing, or of 2k or 3k whose lines
            # between stay under the noise (a 6-blade rotor's comb lay at 3 f_rot): k is the least count
            chopping_hz, least_n = chopping_hz * k, k
        elif aliased and (not _whole_ratio(ratio) or (ratio > 1 and _whole_multiple(power(), timed_hz) == 1)
                          or (ratio < 1 and not (n_blades or 0) % 2 and _whole_multiple(power(), timed_hz) == 1
                              and _no_passages_hidden(ramp, timed_hz, _whole_ratio(ratio), prf_hz=prf_hz))):
            # folded combs coincide by chance; flash times do not (nor those the power repeats whole at: a comb at
            # a whole fraction of them, its lines between cancelling, is no rotor's whose power repeats so; nor, a
            # comb at three times them, those the power resolved within the ramp repeats whole at, where the ramp's
            # test reads any passage seen between theirs; not for an odd N given, which halves flash times that an
            # odd N off the range bin's centre leaves at its chopping)
            known = n_blades if n_blades is not None else measured_n
            odd = (lambda: alternate(1.0 / timed_hz)) if known is None else (lambda: known % 2 == 1)
            if held := _odd_flashes_sampled(ratio, odd=odd, comb_hz=centre, timed_hz=timed_hz):
                return held
            held, chopping_hz, alternating = by_flash_times()
            if held:
                return held
            flashes_only = True
            odd_turn = n_blades is None and alternating and pattern and pattern % 2
            if odd_turn and _agrees(float(chopping_hz[0]) / centre, pattern):
                # flashes by turns on the range sides, an odd N's (2N a turn), at twice a chopping that is
                # ``pattern`` times a comb whose every pattern-th line stands out: the comb lines the turn (one blade
                # differing) of N = pattern blades (four K-band 3-blade rotors 6 % apart, one blade 1.34 times the
                # others: a comb at 100.4 Hz, flash times at 601 Hz; N had been assumed)
                measured_n = pattern
        elif not aliased and _comb_agrees_with_power(power(), chopping_hz, period_ratio=ratio,
                                                     count_from_comb=measured_n is not None):
            comb_note = (f"the echo's period, {timed_hz:.4g} Hz, set aside: the line comb at {centre:.4g} Hz and the "
                         f"echo's power, repeating whole at {1.0 / power().period_s:.4g} Hz, agree")
        else:
            note = (f"rotation not estimable: the line comb says {centre:.4g} Hz and the echo's "
                    f"{'flash times' if aliased else 'period'} {timed_hz:.4g} Hz; the dwell does not tell which")
            return Rotation.withheld("ambiguous_period", note)
    elif chopping_hz is not None and aliased:
        known = n_blades if n_blades is not None else measured_n
        confirmed = _folded_comb_by_power(power(), chopping_hz, n_blades=known)
        if confirmed is None:
            confirmed = _folded_comb_by_flash_times(ambiguous_rates_hz, chopping_hz, n_blades=known, power=power(),
                                                    prf_hz=prf_hz, dwell_s=dwell_s)
        if confirmed is None:
            note = (f"rotation not estimable: a folded line comb at {float(np.median(chopping_hz)):.4g} Hz that "
                    "neither the flash times nor the power's period confirm (folded combs can coincide by chance)")
            return Rotation.withheld("ambiguous_period", note)
        chopping_hz = confirmed
    elif timed_hz is not None and aliased:
        held, chopping_hz, alternating = by_flash_times()
        if held:
            return held
        flashes_only = True
    elif timed_hz is not None:  # the echo's period: one blade passage
        if held := _period_made_whole(timed_hz, band_hz=band_hz, prf_hz=prf_hz):
            return held
        chopping_hz = np.array([timed_hz])
    if chopping_hz is None:
        weak = _power_flashes(power(), n_blades=n_blades, alternate=alternate)
        if weak is not None:
            return weak
        if slowest_hz > combs.MIN_CHOP_HZ:
            note = (f"rotation not estimable: no periodic blade flashes above {slowest_hz:.3g} Hz (a dwell of "
                    f"{dwell_s:.3g} s holds two chopping periods only above it)")
            return Rotation.withheld("dwell_short", note)
        note = "rotation not estimable: no periodic blade flashes"
        return Rotation.withheld("no_flashes", note)
    if not aliased and timed_hz is None and (held := _comb_against_power(power(), chopping_hz)):
        chopping_hz = _chopping_by_power(power(), chopping_hz,
                                         n_blades=n_blades if n_blades is not None else measured_n)
        if chopping_hz is None:
            return held

    @functools.cache
    def parity_and_doubling(chop_hz):
        """(parity, doubled) of the flashes on a comb at ``chop_hz``: odd N by their Doppler sides (True: by turns,
        False: both at once, None: untold; flashes alternating range sides tell an odd N aliased too), else whether
        their power repeats twice per spacing (:func:`mdpipe.process.combs.flashes_doubled`)."""
        parity = True if alternating else None if aliased else combs.odd_blades(micro, chop_hz, prf_hz=prf_hz,
                                                                                 half_width_hz=sides_band_hz)
        return parity, parity if aliased or parity is not None else combs.flashes_doubled(
            micro, chop_hz, prf_hz=prf_hz, half_width_hz=count_band_hz)

    turn_note = ""
    if (not aliased and n_blades is not None and n_blades % 2 == 0 and measured_n is None and least_n is None
            and not comb_note  # (a power repeating whole once per spacing stood for the comb: no doubling)
            and parity_and_doubling(float(chopping_hz[0])) == (None, True)):  # (flashes by turns: an odd N's)
        turned = _turn_comb(chopping_hz, n_blades=n_blades)
        if isinstance(turned, Rotation):
            return turned
        chopping_hz, turn_note = turned
    least_mps = least_tip_speed_mps(float(chopping_hz.max()), n_blades=n_blades, elevation_deg=elevation_deg)
    if not aliased and halfwidth_mps is not None and halfwidth_mps < least_mps:
        weak = _power_flashes(power(), n_blades=n_blades, alternate=alternate)
        if weak is not None:
            return weak
        note = (f"rotation not estimable: a comb at {np.median(chopping_hz):.4g} Hz in a micro-Doppler only "
                f"{halfwidth_mps:.2g} m/s wide is no rotor (blades turning that fast, seen at "
                f"{elevation_deg:g} deg, reach >= {least_mps:.2g} m/s)")
        return Rotation.withheld("not_rotor", note)
    chopping_value = float(np.median(chopping_hz))
    if pattern and measured_n is None and least_n is None and not aliased:
        note = (f"rotation not estimable: every {pattern}th line of the comb at {chopping_value:.4g} Hz stands out: "
                f"one blade of {pattern} differing (the chopping {pattern * chopping_value:.4g} Hz) or rotors at one "
                f"rate whose phases cancel the lines between (the chopping {chopping_value:.4g} Hz); rotors resolved "
                "at rates apart, or the echo repeating each 1/N turn, would tell")
        return Rotation.withheld("ambiguous_period", note)
    parity, doubled = parity_and_doubling(float(chopping_hz[0]))
    blades, source, conflict = _blade_count(measured_n, parity, n_blades=n_blades, doubled=doubled, least=least_n)
    if conflict:
        note = f"chopping frequency uncertain and rotation not estimable: {conflict}"
        return Rotation(Measured(chopping_value, "blade_conflict", note), withheld("blade_conflict", note),
                        n_blades=blades, n_blades_source=source)
    if chopping_value * dwell_s < 2 * PHASED_ROTORS:
        note = (f"rotation not estimable: a chopping frequency of {chopping_value:.4g} Hz read on {dwell_s:.3g} s could "
                f"be the flashes of up to {PHASED_ROTORS} rotors turning at one rate, their phases apart, within a "
                f"chopping period up to {PHASED_ROTORS} times longer, which the dwell does not hold twice")
        return Rotation.withheld("ambiguous_period", note)
    chopping = Measured(chopping_value)
    if source == "assumed" and flashes_only and not alternating:
        chopping = Measured(chopping_value, "assumed_blades", f"chopping frequency assumes an even blade count (an "
                            f"odd one flashes twice per chopping period: {chopping_value / 2:.4g} Hz; give --blades)")
    elif source == "assumed" and parity and not alternating:
        chopping = Measured(chopping_value, "assumed_blades", f"chopping frequency assumes equal blades (the flashes "
                            f"alternate sides: an odd count; with one blade differing this comb lines the turn rate "
                            f"and the chopping is {3 * chopping_value:.4g} Hz or more; give --blades)")
    # (flashes alternating range sides at twice a comb make it the chopping: an even N's, one blade differing or
    # not, flash on both sides at once)
    elif source == "assumed" and doubled and not alternating:
        chopping = Measured(chopping_value, "assumed_blades", f"chopping frequency assumes equal blades of an odd "
                            f"count (an even count with one blade differing lines its turn rate in this comb: the "
                            f"chopping would be {2 * chopping_value:.4g} Hz or more; give --blades)")
    rates = tuple(sorted(float(rotor.rotation_rate_from_chopping_hz(c, n_blades=blades)) for c in chopping_hz))
    rate = float(np.median(rates))
    if source == "assumed" and least_n:
        measured = Measured(rate, "assumed_blades", f"rotation rate assumes N = {blades} blades, the least the echo "
                            f"allows (every {blades}th line of the comb stands out and the echo repeats {blades} times "
                            f"per comb period: one blade differing; {2 * blades} or {3 * blades} blades whose lines "
                            "between stay under the noise would turn 1/2 or 1/3 as fast; give --blades)")
    elif source == "assumed":
        measured = Measured(rate, "assumed_blades", f"rotation rate assumes N = {blades} blades (the echo does not "
                            "tell the blade count; give --blades)")
    else:
        measured = Measured(rate, OK, turn_note)
    if comb_note:  # how the comb stood (the rate's note is the row's sentence on it, ok or not)
        measured = Measured(rate, measured.status, "; ".join(n for n in (measured.note, comb_note) if n))
    return Rotation(chopping, measured, rates, blades, source)


def _turn_comb(chopping_hz, *, n_blades):
    """The chopping frequencies of a comb (spacings ``chopping_hz``) whose power repeats twice per spacing
    (:func:`mdpipe.process.combs.flashes_doubled`), for an even blade count ``n_blades`` given: N equal blades'
    power repeats once per chopping period, so the comb lines a turn, not the chopping. Two blades: the turn rate,
    one blade differing, the chopping twice it (an X-band quadrotor seen from 86 deg, one blade 1.3 times the other:
    a comb at 131 Hz read 65.5 rev/s for 130.5). Four or more: the turn rate or a part of a turn (two opposite
    blades of four differing repeat twice a turn): withheld as ``ambiguous_period`` (a :class:`Rotation`). Returns
    the Rotation withheld, or the chopping frequencies and the note that says how they were read."""
    if n_blades == 2:
        return 2 * chopping_hz, (f"the power repeats twice per spacing of the comb at {chopping_hz[0]:.4g} Hz: with 2 "
                                 "blades given, it lines the turn rate (one blade differing), and the chopping is "
                                 "twice it")
    spacing_hz = float(np.median(chopping_hz))
    note = (f"rotation not estimable: the power repeats twice per spacing of the comb at {spacing_hz:.4g} Hz: with "
            f"{n_blades} blades given it lines a turn (one blade differing: the chopping {n_blades * spacing_hz:.4g} "
            f"Hz) or a part of one (the chopping {2 * spacing_hz:.4g} Hz or more)")
    return Rotation.withheld("ambiguous_period", note)


def _comb_multiple(lines, spacing_hz, *, band_hz, dwell_s):
    """The m (2..``combs.MAX_BLADES``) such that the comb at ``spacing_hz`` is the m-th multiple of the echo's
    fundamental, a repeat held twice in ``dwell_s``: lines between its own stand as strong, and no every-m-th
    stands out (:func:`mdpipe.process.combs.lines_between`, within ``band_hz``); else 0. Below
    ``combs.MIN_CHOP_HZ`` that fundamental is no rotor's: a bird's wing lines, every third harmonic of its 11.3 Hz
    wingbeat read as a rotor comb at 33.9 Hz. Above, it is the rotors' chopping comb where their power flashes at it
    (:func:`_power_at_fundamental`): two K-band rotors whose first six lines stand weak read at three times it,
    254 Hz for 84.6."""
    return combs.lines_between(lines, spacing_hz, half_width_hz=band_hz, min_hz=2.0 / dwell_s)


def _power_at_fundamental(found, fundamental_hz, multiple):
    """Whether the echo's power (``found``, a :class:`~mdpipe.process.flashes.PowerPeriod` or None) repeats whole
    at once or twice ``fundamental_hz``, below the comb at ``multiple`` times it: a rotor chopping at the
    fundamental flashes so (twice: an odd N). Lines between a comb's own also fill in where rotors a per cent apart
    smear their high orders (four W-band rotors chopping at 164-166 Hz, their power repeating there, showed lines
    at a third of it)."""
    if found is None or not found.whole:
        return False
    ratio = 1.0 / found.period_s / fundamental_hz
    return any(_agrees(ratio, k) for k in (1, 2) if k < multiple)


def _comb_against_power(found, comb_hz):
    """Rotation withheld as ``ambiguous_period`` when the echo's power (``found``, a
    :class:`~mdpipe.process.flashes.PowerPeriod` or None) repeats at a rate no rotor with that comb (spacings
    ``comb_hz``) gives, else None.

    Unaliased flashes are sampled whole: the power of a rotor chopping at ``f`` repeats at ``f`` (N even), ``2 f``
    (N odd) or, one blade differing, once a turn, ``f / N``; of one whose comb lines its turn rate, at ``k f`` (k
    up to 2N). A rate the comb's k or 1/k times for no whole k in those ranges (within ``POWER_COMB_TOLERANCE``:
    rotors a few per cent apart) says that the comb is none of those: six rotors 2 % apart smeared their high
    orders, and a comb at 11 times the chopping frequency, 1202 Hz, outscored it while the power repeated at 108.6
    Hz; a three-blade rotor's comb read at 3 f, 486 Hz, its power repeating at 2 f."""
    if found is None:
        return None
    ratio = 1.0 / found.period_s / float(np.median(comb_hz))
    whole = [k for k in range(1, 2 * combs.MAX_BLADES + 1) if abs(ratio / k - 1) <= POWER_COMB_TOLERANCE]
    whole += [k for k in range(2, combs.MAX_BLADES + 1) if abs(ratio * k - 1) <= POWER_COMB_TOLERANCE]
    if whole:
        return None
    note = (f"rotation not estimable: the line comb says {np.median(comb_hz):.4g} Hz and the echo's power repeats "
            f"at {1.0 / found.period_s:.4g} Hz, {ratio:.3g} times it, as no rotor with that comb does")
    return Rotation.withheld("ambiguous_period", note)


def _period_made_whole(period_hz, *, band_hz, prf_hz):
    """Rotation withheld as ``ambiguous_period`` when the echo's period (at ``period_hz``, no comb beside it) may be
    a whole multiple of its own, made whole by the chirps: in a band of half-width ``band_hz`` over
    ``WIDE_BAND_SHARE`` of the span's, the echo decorrelates over a fraction of a chirp, so that its autocorrelation
    peaks only at lags near a whole number of chirps, and a period of 34.8 chirps shows at 4 of them, 139.0 (six
    3-blade rotors at one rate, their tips reaching 92 % of the span, read at a quarter of their rate); else None."""
    if band_hz < WIDE_BAND_SHARE * prf_hz / 2:
        return None
    chirps = prf_hz / period_hz
    note = (f"rotation not estimable: the echo repeats every {chirps:.1f} chirps ({period_hz:.4g} Hz), but its band "
            f"fills {band_hz / (prf_hz / 2):.0%} of the span: it decorrelates within a chirp, and a period of a "
            "fraction of it that is no whole number of chirps does not show; another PRF tells")
    return Rotation.withheld("ambiguous_period", note)


def _chopping_by_power(found, comb_hz, *, n_blades):
    """The chopping frequencies (the comb's spacings ``comb_hz`` over a whole m, or N times them) that an unaliased
    comb and the echo's power (``found``, a :class:`~mdpipe.process.flashes.PowerPeriod`, repeating whole) both
    allow for the blade count ``n_blades`` (given or measured), where they allow exactly one; else None.

    N blades' power repeats whole once per chopping period, twice for an odd N, or, one blade differing, once a
    turn (the chopping N times its rate); their comb is the chopping comb, a whole multiple m of it where the lines
    between cancel (rotors a phase apart), or the turn rate. A 3-blade quadrotor seen 0.25 s showed its comb at
    3 times the chopping (486 Hz) and its power repeating at twice it (326 Hz): 2/3 of the comb, which no whole
    ratio reads, and only 162 Hz is both.
    """
    if n_blades is None or found is None or not found.whole:
        return None
    power_hz = 1.0 / found.period_s
    centre_hz = float(np.median(comb_hz))
    by_power = [power_hz / k for k in ((1, 2) if n_blades % 2 else (1,))] + [power_hz * n_blades]
    by_comb = [(m, centre_hz / m) for m in range(1, combs.MAX_BLADES + 1)] + [(1.0 / n_blades, centre_hz * n_blades)]
    both = [(m, chopping) for m, chopping in by_comb if any(_agrees(chopping / p) for p in by_power)]
    if len({round(chopping, 6) for _, chopping in both}) != 1:
        return None
    return np.asarray(comb_hz, dtype=float) / both[0][0]


def least_tip_speed_mps(chopping_hz, *, n_blades, elevation_deg):
    """The least radial speed (m/s) the tips of any rotor chopping at ``chopping_hz`` reach: blades of
    ``MIN_BLADE_M`` turning at ``chopping_hz / N`` (``n_blades`` given, else ``combs.MAX_BLADES``), their disc seen
    at ``elevation_deg`` tilted ``ROTOR_TILT_DEG`` towards face-on; 0 when the elevation is not given.

    The echo gives ``r cos(beta)``, which has no floor while beta is unknown: a quadrotor seen from below (88 deg,
    discs tilted 3-4 deg) spread its 12 cm blades' tips over +-3.8 m/s, its comb at 218 Hz.
    """
    seen_deg = None if elevation_deg is None else _disc_seen_deg(elevation_deg, towards_face_on=True)
    if seen_deg is None or seen_deg >= 90.0:
        return 0.0
    turn_hz = chopping_hz / (n_blades if n_blades is not None else combs.MAX_BLADES)
    return float(2 * np.pi * turn_hz * MIN_BLADE_M * np.cos(np.deg2rad(seen_deg)))


def _span_ambiguity(what, frequency_hz, *, prf_hz, dwell_s, power):
    """Rotation withheld as ``ambiguous_period`` when an aliased echo's comb spacing or flash rate (``what`` at
    ``frequency_hz``) is the PRF over a whole number M, within what the dwell resolves (``1 / dwell_s``: M chirps a
    period, drifting less than a chirp over the dwell), and the echo's power (``power()``, a
    :class:`~mdpipe.process.flashes.PowerPeriod` or None) does not repeat whole at a whole multiple of it (the
    flash rate itself, no shorter repeat left); else None. A whole repeat at k times it (k >= 2) leaves the
    chopping to what reads k (a blade count; not flash times at it: :func:`_flashes_missed`).

    A chopping comb at ``m f`` then folds onto the grid ``k f`` (every residue of ``k m`` mod M, for m prime to
    M), and flashes shorter than a chirp every ``M / m`` chirps are caught every m-th, each M chirps: four equal
    2-blade rotors chopping at 141.3 Hz sampled at 6283 Hz (PRF / 44.5) folded to a comb at 70.6 Hz (PRF / 89),
    and their flash times repeated at 70.7 Hz; six rotors chopping at 161 Hz flashed every 432 chirps (27.6 Hz).
    """
    if not _on_span_grid(frequency_hz, prf_hz=prf_hz, dwell_s=dwell_s):
        return None
    span_orders = prf_hz / frequency_hz
    if _whole_multiple(power(), frequency_hz) >= 1:
        return None
    note = (f"rotation not estimable: the {what} at {frequency_hz:.4g} Hz, the PRF over {span_orders:.1f}: "
            "a whole multiple of it folds onto it, its flashes shorter than a chirp caught at some passages only; "
            "another PRF tells which")
    return Rotation.withheld("ambiguous_period", note)


def _on_span_grid(frequency_hz, *, prf_hz, dwell_s):
    """Whether ``frequency_hz`` is the PRF over a whole number M within what the dwell resolves (``1 / dwell_s``: M
    chirps a period, drifting less than a chirp over the dwell), where a whole multiple of it folds onto it."""
    return on_chirp_grid(prf_hz / frequency_hz, dwell_chirps=dwell_s * prf_hz)


def _comb_agrees_with_power(found, chopping_hz, *, period_ratio, count_from_comb):
    """Whether an unaliased comb (chopping frequencies ``chopping_hz``) stands against the echo's period,
    ``period_ratio`` times the comb's median, that no blade count reconciles: the echo's power (``found``, a
    :class:`~mdpipe.process.flashes.PowerPeriod` or None) repeats whole at the comb's median (within ``AGREEMENT``),
    the period lies at no whole ratio to the comb, and no blade count was read from the comb's own line pattern
    (``count_from_comb``: measured, N given or not).

    The comb (the dwell's lines) and the power (its flashes' repeat, blind to their phases) are readings of
    different kinds and agree; the period, the complex echo's autocorrelation, is the one reading out. At a whole
    ratio the disagreement has a cause that leaves comb and power agreeing on a wrong rate: rotors at one rate a
    fraction of a chopping period apart cancel the lines between a comb's every k-th and flash k times per chopping
    period (comb and power at k times a chopping the period reads), and one blade differing lines the turn rate
    (comb and power at the turn, the period at the chopping). A count the line pattern measured is no second reading
    either: rotors at one rate and phase fool it, and an odd N's power repeats twice per chopping period (two 3-blade
    rotors at 89.7 rev/s, 60 deg apart, in `make offmodel-blades`: their comb at the chopping read as the turn of 2
    blades, one differing, and the chopping taken at twice it, where the power repeated; 3 times the rate, `ok`,
    had this test not been made; with N = 3 given, the pattern's count of 2 in conflict with it, a chopping of 538 Hz
    for 269 as a `blade_conflict`). Measured: a quadrotor at X band given N = 2 (comb 220.5 Hz, power 219.2 Hz,
    period 912 Hz, 4.14 times the comb; truth 218.5 Hz)."""
    if count_from_comb or _whole_ratio(period_ratio):
        return False
    return _whole_multiple(found, float(np.median(chopping_hz))) == 1


def _no_passages_hidden(ramp, flash_hz, k, *, prf_hz):
    """Whether flash times at ``flash_hz`` stand against a folded comb at ``k`` times them as the echo's power
    resolved within the ramp (``ramp()``, a :class:`~mdpipe.process.flashes.RampTrain`, or None: not read) tells:
    for k = 3, it repeats whole at them and the gap between ramps (``1 - ramp_share`` of the chirp period) is under a
    third of the chirp period.

    A rotor chopping at the comb flashes 3 times per flash-time period P. Flashes shorter than a chirp are caught
    whole in the part of the ramp they fall in, not at all between the ramps; whole ramps, weighing a flash by where
    it falls in their window, can leave the flash times at P (six rotors chopping at 161 Hz left flash times every
    432 chirps, 27.6 Hz, in the held-out drone sweep). With P off the chirp grid the passages drift through the ramp
    and all are seen; with P a multiple of 3 chirps all three fall at one place, seen together (flash times at P / 3)
    or not at all; else they fall a third of the chirp period apart: two seen within the ramp repeat at P / 3, which
    the ramp's test reads (:func:`~mdpipe.process.flashes.ramp_repeats_whole`), and one seen alone needs the other
    two between the ramps, a gap of a third of the chirp period. Not for other k: of 2 passages one may always fall
    between the ramps, and for k = 5 two passages 2 P / 5 apart repeat at no P / j (a synthetic ramp train at 5
    times so passed the test). A 77 GHz quadrotor of the held-out sweep, ramps over 0.8 of the chirp: flash times
    164.83 Hz, the power resolved within the ramp whole at 164.84 Hz, a folded comb at 3 times them (truth
    164.82 Hz)."""
    if k != 3 or ramp is None or ramp() is None or 1.0 - ramp().ramp_share >= 1.0 / 3.0:
        return False
    return bool(ramp_repeats_whole(ramp(), prf_hz / flash_hz, shortest_chirps=prf_hz / combs.MAX_CHOP_HZ))


def _whole_multiple(found, frequency_hz):
    """The whole k >= 1 at k times ``frequency_hz`` of which the echo's power (``found``, a
    :class:`~mdpipe.process.flashes.PowerPeriod` or None) repeats whole, within ``AGREEMENT``; else 0."""
    if found is None or not found.whole:
        return 0
    ratio = 1.0 / found.period_s / frequency_hz
    k = round(ratio)
    return k if k >= 1 and _agrees(ratio, k) else 0


def _flash_times_of_each_side(timed_hz, *, n_blades):
    """Rotation withheld as ``ambiguous_period``: aliased flash times at ``timed_hz`` alone, an odd blade count
    ``n_blades`` given, and each of the target's range sides flashing at every flash time on its own
    (:func:`~mdpipe.process.flashes.sides_flash_apart`).

    An odd N's equal blades flash 2N times a turn, by turns on the range sides (an approaching blade's beat moved to
    one, a receding one's half a chopping period later to the other): flash times at twice the chopping, halved
    for it. Each side flashing at every flash time is what those flashes show at the chopping itself, each side
    once in its period: two low-PRF 3-blade quadrotors, their tips folded 6 and 15 times, flashed so at 309 and
    182 Hz, their chopping 313 and 184 Hz, and were read at half it, `ok`. Flash times are the dwell's strongest
    repeat, which stroboscopic sampling can put at a side's (the sides did not alternate at half their period
    either): which one the dwell holds is not told.
    """
    note = (f"rotation not estimable: flash times at {timed_hz:.4g} Hz, each of the target's range sides flashing "
            f"at every one on its own, as an odd count's flashes by turns do at its chopping ({n_blades} blades "
            f"given): the chopping is {timed_hz:.4g} Hz, or {timed_hz / 2:.4g} Hz where these are every flash")
    return Rotation.withheld("ambiguous_period", note)


def _flashes_missed(found, timed_hz, *, n_blades):
    """Rotation withheld as ``ambiguous_period`` when the echo's power (``found``, a
    :class:`~mdpipe.process.flashes.PowerPeriod` or None) repeats whole at k >= 2 times the rate of flash times
    that a folded comb repeats: the flash times then caught every k-th flash only, as comb and flash times do when
    the PRF is a whole multiple of the chopping over k. Four rotors chopping at 141.3 Hz sampled at PRF / 44.5
    left comb and flash times at 70.7 Hz, the power (resolved within the ramp) whole at 141.2 Hz. An odd blade
    count (``n_blades``: given, measured, or shown by flashes alternating range sides) flashes twice per chopping
    period: k = 2 is then its own. Else None."""
    k = _whole_multiple(found, timed_hz)
    if k < 2 or (k == 2 and n_blades is not None and n_blades % 2):
        return None
    note = (f"rotation not estimable: the flash times and the folded line comb say {timed_hz:.4g} Hz and the echo's "
            f"power repeats whole at {1.0 / found.period_s:.4g} Hz, {k} times it: flashes shorter than a "
            "chirp caught at some passages only; another PRF tells which")
    return Rotation.withheld("ambiguous_period", note)


def _comb_beyond_band(micro, lines, *, band_hz, prf_hz, noise_power, min_hz, max_hz=combs.MAX_CHOP_HZ):
    """A rotor comb of single lines each under the band's threshold (tapered blades: lines 12-14 dB over the noise
    out to the 16th order, the band measured ending at the 3rd), searched over the span (unfolded); returns its
    spacings and extent (Hz), else ``(None, None)``.

    Taken only where its first line lies within the band measured (the rotor's strongest lines are its first)
    and it holds ``MIN_WIDE_ORDERS`` orders a side: over the span a short dwell's few-line combs near the top
    spacing pass the comb test on noise (a moving point read a 1700 Hz comb on 3 lines, its band 32 Hz wide).
    Nor where lines between its own stand as strong (:func:`mdpipe.process.combs.lines_between`): it is then a
    multiple of rotors' chopping combs smeared by their rates' spread past the comb test (593 Hz read for 198).
    """
    comb = combs.find_combs(micro, prf_hz=prf_hz, noise_power=noise_power, half_width_hz=prf_hz / 2, min_hz=min_hz,
                            max_hz=min(max_hz, band_hz), lines=lines, folded=False)
    if comb is None:
        return None, None
    extent_hz = combs.comb_extent_hz(lines, comb[0], half_width_hz=prf_hz / 2)
    if extent_hz < MIN_WIDE_ORDERS * comb[0]:
        return None, None
    if combs.lines_between(lines, comb[0], half_width_hz=extent_hz, min_hz=min_hz):
        return None, None
    return comb, extent_hz


def _comb_blades(micro, lines, spacing_hz, *, aliased, prf_hz, band_hz, noise_power, on_body, n_blades=None,
                 power=lambda: None):
    """Chopping frequencies from comb spacings, the blade count where the line pattern tells it, and that
    pattern (the N of the first comb's every N-th line standing out, confirmed or not; None without one).

    A comb whose every N-th line stands out is a rotor's turn seen through one blade that differs:
    its chopping frequency is N times the spacing. A comb with weaker lines between its lines is the
    chopping comb of such a rotor. Either way N is measured. A pattern of every N-th line is confirmed by
    N given, by the same pattern on a further rotor's comb resolved at another rate
    (:func:`_pattern_on_rotors_apart`), by the echo repeating each 1/N turn, by rotors drifting apart on one comb that
    stands for them (:func:`_rotors_drift_on_comb`, unfolded combs; ``noise_power`` per chirp), or by the echo's
    power (``power()``, a
    :class:`~mdpipe.process.flashes.PowerPeriod` or None) flashing as N blades turning at the comb's rate
    do, when that is more than twice per spacing (N > 2: a comb of equal blades at the chopping frequency
    flashes once or twice per spacing, as two blades turning at it do; :func:`_power_flashes_as`). Folded
    (aliased) combs tell N only by the power or by the pattern on rotors resolved at rates apart (their lines
    interleave orders: the pattern on one comb, even of the N given, is not trusted; the other rotors' lines folded
    onto a comb's orders fall on its multiples of N no more often than between, and a pattern that two rotors'
    combs both show is their blades'; not for a comb on the PRF's grid, :func:`_on_span_grid`, whose folded orders
    beyond the span fall back onto its own and its neighbours'). An unfolded comb whose odd orders stand out is one
    at twice its spacing, read half a spacing off its hub's Doppler
    (:func:`~mdpipe.process.combs.odd_orders_stand_out`), where no body line (``on_body`` False) centred it there.
    Centred on the body line, it is not: its odd orders stand out where rotors at one rate, phased, cancel the even
    ones as far as their echoes are alike (an independent simulator's four 2-blade rotors 45 deg apart at 57.3 rev/s,
    their comb at the chopping, read as one at twice it with weaker lines between: 2 blades at 114.5 rev/s, `ok`).
    """
    if not aliased and not on_body and combs.odd_orders_stand_out(lines, float(spacing_hz[0]), half_width_hz=band_hz):
        spacing_hz = 2 * spacing_hz
    pattern = combs.blade_count_from_line_pattern(lines, float(spacing_hz[0]), half_width_hz=band_hz)
    if pattern and pattern == n_blades and not aliased:
        return spacing_hz * pattern, pattern, pattern
    if pattern and _power_flashes_as(pattern, spacing_hz, power()):
        return spacing_hz * pattern, pattern, pattern
    on_grid = aliased and _on_span_grid(float(spacing_hz[0]), prf_hz=prf_hz, dwell_s=len(micro) / prf_hz)
    if pattern and not on_grid and _pattern_on_rotors_apart(lines, spacing_hz, pattern, band_hz=band_hz):
        return spacing_hz * pattern, pattern, pattern
    if aliased:
        return spacing_hz, None, pattern
    if pattern:
        # rotors at equal rates whose phases cancel some lines leave a pattern too; a tagged rotor's echo
        # repeats almost exactly each 1/N turn, and exactly each turn
        r = autocorrelation(micro)
        turn = prf_hz / float(spacing_hz[0])
        sub, whole = best_near(r, turn / pattern, half_width=2), best_near(r, turn, half_width=2)
        if sub >= TAGGED_REPEAT and whole > sub:
            return spacing_hz * pattern, pattern, pattern
        if _rotors_drift_on_comb(micro, lines, float(spacing_hz[0]), whole, noise_power=noise_power):
            return spacing_hz * pattern, pattern, pattern
    return spacing_hz, combs.blade_count_from_sublines(lines, float(spacing_hz[0]), half_width_hz=band_hz), pattern


def _rotors_drift_on_comb(micro, lines, spacing_hz, turn_repeat, *, noise_power):
    """Whether the rotors of one unfolded comb at ``spacing_hz`` turn at rates apart, so that no phases of theirs
    cancel its lines, and the comb stands for them all.

    Rotors whose phases cancel some of a comb's lines must hold those phases over the dwell: they turn at one rate,
    and their echo repeats each turn as one rotor's does. Where it repeats (``turn_repeat``, the autocorrelation at
    a turn) with under ``DRIFTING_REPEAT`` of the signal's power (the noise power per chirp, ``noise_power``, taken
    out of ``micro``'s), they drift through each other's phases, and a line pattern is their blades': six 2-blade
    rotors within 0.9 % of 58 rev/s, wandering 2 %, one blade of each 1.87 times the other, repeated each turn with
    0.47 (the independent simulator's rotors at one rate: 0.86-0.99). The comb's first lines, where rotors a few per
    cent apart are not resolved, must then centre within ``AGREEMENT`` of it (on the dwell's line scores ``lines``,
    :func:`mdpipe.process.combs.first_lines_rate_hz`): a comb read over many orders follows the rotor whose lines
    stand strongest (four 4-blade rotors at 78.2-81.7 rev/s seen 0.1 s: a comb at 78.1 Hz, 2.6 % under their mean, its
    first lines centring on 80.0 Hz).
    """
    power = float(np.mean(np.abs(micro) ** 2))
    signal_share = 1.0 - noise_power / power if power > 0 else 0.0
    if not (signal_share > 0 and turn_repeat < DRIFTING_REPEAT * signal_share):
        return False
    centre_hz = combs.first_lines_rate_hz(lines, spacing_hz)
    return centre_hz is not None and _agrees(centre_hz / spacing_hz)


def _folds_onto_odd_orders(spacing_hz, *, prf_hz, dwell_s):
    """Whether a chopping comb at twice ``spacing_hz``, folded once, falls on the odd orders of the comb at it: the
    PRF lies within ``HANN_LOBE_BINS`` dwell-spectrum bins (``1 / dwell_s``) of an odd multiple M of ``spacing_hz``,
    and its m-th line folds to ``(2 m - M)`` times it (:func:`_fold_multiples`). Every second line of that comb
    standing out is then what equal blades' chopping lines show over their own folded ones: four equal 2-blade rotors
    at 77 GHz, their tips folded twice, the PRF 172.93 times their 135.5 Hz turn (1.5 bins from 173), stepped every
    second line of a comb at 135.5 Hz, and N = 2 was read as measured where the echo does not tell it (4 blades at
    half the rate look alike). False for a spacing over PRF / 1.5 (M = 1: no comb).
    """
    return 2 in _fold_multiples(spacing_hz, prf_hz=prf_hz, dwell_s=dwell_s, up_to=2)


def _fold_multiples(spacing_hz, *, prf_hz, dwell_s, up_to):
    """The whole multiples k (2 to ``up_to``) of ``spacing_hz`` whose comb, folded by the PRF, lands on every order of
    the comb at it within ``HANN_LOBE_BINS`` dwell-spectrum bins (``1 / dwell_s``): k prime to the whole number M
    nearest the PRF over the spacing. The comb at ``k f`` folded n times lies at ``(k m - n M) f``, off the grid by n
    times the PRF's offset from ``M f``; its approaching and receding lines folded n times fill the residues ``-n M``
    and ``n M`` mod k, every order once n reaches ``k // 2`` (k = 2 or 3 prime to M: once; M = 26, k = 3: the orders
    of 1 and 2 mod 3), and the echo shows one comb at f for either. A k sharing a factor d with M fills only the
    multiples of ``d f``, and the comb reads that. Empty where the PRF is off every multiple."""
    ratio = prf_hz / spacing_hz
    if not (np.isfinite(ratio) and ratio >= 1.5):  # (M = 1: a spacing over half the PRF is read on no comb)
        return ()
    nearest = int(round(ratio))
    offset_bins = chirp_grid_drift(ratio, dwell_chirps=prf_hz * dwell_s)
    return tuple(k for k in range(2, int(up_to) + 1)
                 if math.gcd(k, nearest) == 1 and (k // 2) * offset_bins < HANN_LOBE_BINS)


def _pattern_on_rotors_apart(lines, spacing_hz, pattern, *, band_hz):
    """Whether the line pattern ``pattern`` of the first comb (spacing ``spacing_hz[0]``) shows again on a further
    rotor's comb, read with the first comb's lines taken out: each rotor's own blades, one differing.

    Rotors whose phases cancel some lines turn at one rate and share one comb; rotors at rates apart drift
    through each other's phases, so a pattern on two of their combs is neither's cancellation. A comb too close
    to the first to be read apart loses its lines with the first's and confirms nothing.
    """
    if len(spacing_hz) < 2:
        return False
    first = float(spacing_hz[0])
    others = lines.without(first, np.arange(1, int(band_hz / first) + 1))
    return any(combs.blade_count_from_line_pattern(others, float(s), half_width_hz=band_hz) == pattern
               for s in spacing_hz[1:])


def _power_flashes_as(pattern, spacing_hz, power):
    """Whether the echo's power (a whole :class:`~mdpipe.process.flashes.PowerPeriod`) flashes as ``pattern``
    blades turning at the comb's rate do, where that is more than twice per spacing, on combs of rotors resolved
    at different rates.

    Rotors at one rate whose phases cancel some lines leave a line pattern, and their flashes, evenly spaced,
    can come as often as N blades' (four 2-blade rotors 45 deg apart: every fourth line, four flashes per
    spacing, read N = 4 at twice the rate); rotors at rates apart drift through each other's phases.
    """
    if power is None or not power.whole or len(spacing_hz) < 2:  # the combs resolve rotors at rates apart
        return False
    flashes_per_turn = rotor.flashes_per_revolution(pattern)
    flashes_hz = flashes_per_turn * float(np.median(spacing_hz))
    return flashes_per_turn > 2 and _agrees(1.0 / power.period_s / flashes_hz)


def _blade_count(measured, parity, *, n_blades, doubled=None, least=None):
    """(N, source, conflict sentence or None): given, measured from the echo, or assumed.

    ``measured``: N from blade imbalance lines (or None); ``parity``: True for flashes alternating sides
    (odd N), False for both sides at once (even), None when unclear; ``doubled``: the power repeats twice per
    comb spacing (an odd N, or an even one's turn comb), from which an odd N is assumed; ``least``: the least
    count the echo allows, assumed before either.
    """
    if n_blades is not None:
        if measured is not None and measured != n_blades:
            return n_blades, "given", (f"{n_blades} blades given, but the lines between the chopping lines show "
                                       f"{measured} blades of unequal reflectivity")
        if parity is not None and parity != bool(n_blades % 2):
            return n_blades, "given", (f"{n_blades} blades given, but " + ("the flashes alternate sides of the "
                                       "Doppler span (odd N)" if parity else "every flash spans both sides of the "
                                       "Doppler span (even N)"))
        return n_blades, "given", None
    if measured is not None:
        return measured, "measured", None
    return (least or (ASSUMED_ODD_BLADES if doubled else ASSUMED_EVEN_BLADES)), "assumed", None


def blade_length(demodulated, *, rate, chopping_hz, aliased, half_width_hz, prf_hz, wavelength_m, noise_power, params,
                 n_blades):
    """Tip Doppler from the flash edges, and r by inverting Eq. 6.

    Returns (tip bandwidth Measured, blade length Measured, edges (low_hz, high_hz) or None).
    The edges are those of a flash's rectangular spectrum only where the frame's window (a Hann main lobe +-2 bins)
    blurs a small part of it: the tips must span ``MIN_EDGE_BINS`` Doppler bins a side, ``f_tip`` times the frame
    length (``w Gamma / N`` for a frame of w chopping periods, ``Gamma = f_tip / f_rot``). The frame is first
    ``edge_window_periods`` chopping periods, then lengthened to ``EDGE_BINS`` bins where that stays within a flash
    period and a quarter turn (:func:`_edges_resolved`). Measured on :mod:`mdpipe.physics.rotor` echoes (one rotor,
    four at rates 3 % apart, four at one rate 0/30/65/100 deg apart; uniform, 16-point and tapered blades, tips 0.6
    and 0.3 of the root; 6-30 cm at X band; 2 and 3 blades; noise 15 dB under the echo): of 120 cases 79 give the
    tip Doppler over 8 bins, median error 0.6 %, all within 3.1 % but four 3-blade rotors at one rate (+3.5 to
    +4.1 %). Point blades spaced over lambda / 2 (8-32 points, X, K and 77 GHz, one rotor or four apart) flash
    off broadside too, short of the tips (:func:`mdpipe.process.spectral.broadside`): 109 values, median 0.5 %,
    worst -12.5 % (3 blades of 16 points 1.1 lambda apart; -47 to -65 % before the edges were read on the widest
    flashes). In a quarter chopping period alone (the frame before), tapered blades at Gamma 41-61 read -7 to
    -12 % and three blades at Gamma 41 +6.5 %. Two rotors at one rate flashing under about 0.4 ms apart bend the
    plateau as a taper would and pass: r 10-17 % off (a tip Doppler of 3.7 kHz).
    """
    if aliased:
        note = "blade length not estimable: aliased"
        return withheld("aliased", note), withheld("aliased", note), None
    if rate.value is None:
        note = "blade length not estimable: needs the rotation rate"
        return withheld("no_rotation", note), withheld("no_rotation", note), None
    # the body line, demodulated to 0 Hz, would outshine the flashes' plateau: notch it out first
    micro = highpass(demodulated, prf_hz=prf_hz, cutoff_hz=EDGE_NOTCH_SHARE * half_width_hz)
    edges = spectral.flash_edges(micro, prf_hz=prf_hz, window_s=params.edge_window_periods / chopping_hz,
                                 noise_power=noise_power, hop_fraction=params.edge_hop_fraction)
    longer = ""
    if edges.low_hz is not None:
        longest_s = min(float(rotor.flash_period_s(rate.value, n_blades=n_blades)), MAX_EDGE_TURN / rate.value)
        edges, longer = _edges_resolved(micro, edges, prf_hz=prf_hz, noise_power=noise_power,
                                        hop_fraction=params.edge_hop_fraction, longest_s=longest_s)
    if edges.low_hz is None:
        note = "blade length not estimable: no flash frame with both Doppler edges inside the span"
        return withheld("no_edges", note), withheld("no_edges", note), None
    bandwidth = edges.high_hz - edges.low_hz
    if half_width_hz > EDGE_BAND_EXCESS * bandwidth / 2:
        note = (f"blade length not estimable: the micro-Doppler reaches {half_width_hz:.4g} Hz, "
                f"{half_width_hz / (bandwidth / 2):.2f} times the flash edges' +-{bandwidth / 2:.4g} Hz: they are "
                "not the tips' (tips folded about the span's ends, or lost)")
        return withheld("edges_inside_band", note), withheld("edges_inside_band", note), None
    if edges.n_edges < MIN_EDGE_FRAMES or not edges.spread_hz <= EDGE_SPREAD_SHARE * bandwidth:
        note = (f"blade length not estimable: the flash edges scatter from flash to flash (+-{bandwidth / 2:.4g} Hz, "
                f"standard error {edges.spread_hz / bandwidth:.1%} from {edges.n_edges} flashes a side; at most "
                f"{EDGE_SPREAD_SHARE:.1%} from {MIN_EDGE_FRAMES} or more): the flashes are near the noise")
        return withheld("edges_scatter", note), withheld("edges_scatter", note), None
    tip = Measured(float(bandwidth))
    bins = bandwidth / 2 * edges.window_s
    if bins < MIN_EDGE_BINS:
        blurred = (f"the tips span {bins:.1f} Doppler bins a side (< {MIN_EDGE_BINS:g}) of the flash frames "
                   f"({edges.window_s * 1e3:.3g} ms, {bandwidth / 2 / rate.value:.1f} rotation harmonics): the frame's "
                   f"window blurs the edges of the flash's spectrum, and they read wide{longer}")
        tip = Measured(float(bandwidth), "few_harmonics", f"tip Doppler from the flash edges uncertain: {blurred}")
        length = withheld("few_harmonics", f"blade length not estimable: {blurred}")
    elif params.elevation_deg is not None and abs(params.elevation_deg) > MAX_ELEVATION_DEG:
        length = withheld("elevation", f"blade length not estimable: elevation {params.elevation_deg:g} deg (Eq. 6 "
                          f"divides by cos(beta) = {np.cos(np.deg2rad(params.elevation_deg)):.2f})")
    else:
        value = float(rotor.blade_length_from_bandwidth_m(bandwidth, rotation_rate_hz=rate.value,
                                                           wavelength_m=wavelength_m,
                                                           elevation_deg=params.elevation_deg or 0.0))
        tilt = rotor.tilt_error(params.elevation_deg or 0.0, (-ROTOR_TILT_DEG, ROTOR_TILT_DEG))
        if rate.status != OK:
            length = Measured(value, rate.status, rate.note.replace("rotation rate", "blade length"))
        elif params.elevation_deg is not None and tilt > TILT_TOLERANCE:
            length = Measured(value, "tilt_sensitive", f"blade length to +-{tilt:.0%} only: at beta = "
                              f"{params.elevation_deg:g} deg a rotor disc tilted {ROTOR_TILT_DEG:g} deg by the drone's "
                              "attitude moves cos(beta) that much")
        elif params.elevation_deg is None:
            length = Measured(value, "assumed_elevation", "blade length assumes the rotor plane faces the radar edge-on "
                              "(beta = 0; the echo gives r cos(beta): give --elevation-deg)")
        else:
            length = Measured(value)
    return tip, length, (edges.low_hz, edges.high_hz)


def _edges_resolved(micro, edges, *, prf_hz, noise_power, hop_fraction, longest_s):
    """The flash edges read again in a frame where the tips ``edges`` found span ``EDGE_BINS`` Doppler bins a side, at
    most ``longest_s`` long (a flash period: a Hann frame centred on a flash gives the next flashes of its rotor no
    weight; a quarter turn: ``MAX_EDGE_TURN``). Flashes of other rotors that fall in the longer frame beat with its
    flash: their frames are left out (:func:`mdpipe.process.spectral.plateau_ripple`), where the fringes fit in the
    plateau (two flashes under about 0.4 ms apart at a tip Doppler of 3.7 kHz bend it as a taper would, unseen).

    Returns ``(edges, why)``: the longer frame's, or those given where no longer frame is wanted or it reads no edges
    (``why``, a clause for the notes, then says so)."""
    wanted_s = min(longest_s, EDGE_BINS / ((edges.high_hz - edges.low_hz) / 2))
    if wanted_s <= edges.window_s:
        return edges, ""
    again = spectral.flash_edges(micro, prf_hz=prf_hz, window_s=wanted_s, noise_power=noise_power,
                                 hop_fraction=hop_fraction)
    if again.low_hz is None:
        return edges, (f" (in frames of {again.window_s * 1e3:.3g} ms, long enough, no flash with both edges stood "
                       "alone: other rotors' flashes beat with it)")
    return again, ""


def wingbeat_rate(demodulated, *, prf_hz, noise_power, dwell_s, band_hz=None, still=False):
    """Wingbeat frequency (Hz) of a bird's body-demodulated echo, from two wingbeats in the dwell on; given as
    ``ambiguous_period`` where two looks read it an octave apart, or a stroke side's rows repeat at twice the period
    read (:class:`~mdpipe.process.wingbeat.Octave`), as ``repeats_scatter`` where the period's standard error (its
    repeats' scatter about k T, three repeats or more) exceeds ``WINGBEAT_SPREAD_SHARE`` of it (of 302 wingbeats so
    fitted on the evaluation's sweeps where the truth says they are measurable, the four over it, 1.03-1.22 %, were
    0.7-10.5 % off, three over 3 %; the 298 under 0.8 % all within 2.5 %), and as ``short_bursts`` where it rests on
    two repeats or fewer across flapping bursts under three of its periods long, as the wing rows mark them
    (:class:`~mdpipe.process.wingbeat.ShortBursts`).
    ``still``: the body neither flies nor travels, its wing rows read over its line's leakage
    (:func:`~mdpipe.process.wingbeat.wing_frames`)."""
    beat = wingbeat(demodulated, prf_hz=prf_hz, noise_power=noise_power, band_hz=band_hz, still=still)
    if isinstance(beat, Octave):
        why = (f"the wing rows repeat every {beat.short_s:.3g} s, those of one stroke side every {beat.period_s:.3g} s "
               "only (the two strokes alike: a dwell of more beats would tell)" if beat.by_sides else
               f"read in frames of two lengths, the wing pattern repeats every {beat.short_s:.3g} s and every "
               f"{beat.period_s:.3g} s (the rows' stroke sign, blind near the body line, would tell)")
        return Measured(1.0 / beat.period_s, "ambiguous_period",
                        f"wingbeat {1.0 / beat.period_s:.3g} Hz or twice it: {why}")
    if isinstance(beat, ShortBursts):
        return Measured(1.0 / beat.period_s, "short_bursts",
                        f"wingbeat {1.0 / beat.period_s:.3g} Hz, read across flapping bursts of {beat.burst_s:.2g} s "
                        "at most, under three of its periods: its repeat pairs frames across the switches to gliding")
    if beat is not None and np.isfinite(beat.error_s) and beat.error_s > WINGBEAT_SPREAD_SHARE * beat.period_s:
        return Measured(1.0 / beat.period_s, "repeats_scatter",
                        f"wingbeat {1.0 / beat.period_s:.3g} Hz, its pattern's repeats scattered about whole multiples "
                        f"of its period: a standard error of {beat.error_s / beat.period_s:.1%} of it (the wings' "
                        f"pattern changes from beat to beat, as flapping starts or stops)")
    if beat is not None:
        return Measured(1.0 / beat.period_s)
    note = (f"no wingbeat between {max(MIN_WINGBEAT_HZ, 2.0 / dwell_s):.2g} and {MAX_WINGBEAT_HZ:g} Hz "
            f"(a dwell of {dwell_s:.3g} s holds two wingbeats only above {2.0 / dwell_s:.2g} Hz)")
    return withheld("dwell_short" if dwell_s < 2.0 / MAX_WINGBEAT_HZ else "no_wingbeat", note)


def flapping(dwell, *, still=False):
    """The share of the dwell a bird flaps, gliding between bursts (:func:`~mdpipe.process.wingbeat.flap_glide_share`
    on ``dwell``, the dwell's spectrogram and noise level: :func:`~mdpipe.process.wingbeat.dwell_frames`; ``still``: the
    body neither flies nor travels), or withheld as ``no_glide``."""
    share = flap_glide_share(*dwell, still=still)
    if share is None:
        return withheld("no_glide", "")
    return Measured(share)


def wing_stroke(swing, *, still, dwell_s):
    """How far a flying body's wings' reach swings over the dwell, a share of its greatest (``swing()``:
    :func:`~mdpipe.process.wingbeat.stroke_swing` on the dwell's spectrogram and noise level): a stroke seen, where the
    dwell holds too few beats for a wingbeat (birds beating 2-3.5 Hz seen for 0.4-0.9 s). Withheld as ``not_flying``
    where the body neither flies nor travels (``still``, :func:`_least_wing_spread_mps` as the caller read it: a
    swaying branch's reach swings too), else as :func:`_stroke` reads it."""
    if still:
        return withheld("not_flying", "")
    return _stroke(swing, dwell_s=dwell_s)


def _stroke(swing, *, dwell_s):
    """The swing of the wings' reach over the dwell (``swing()``, read only here) where it is a stroke's: withheld as
    ``dwell_short`` where the frames (an eighth of ``dwell_s``) are shorter than ``STROKE_FRAME_S``, a slow rotor's
    turn (within one, a rotor's tips' reach holds from frame to frame), ``no_stroke`` where the reach swings under
    ``STROKE_SWING`` or no wing rows are lit."""
    if dwell_s / 8 < STROKE_FRAME_S:
        return withheld("dwell_short", "")
    value = swing()
    if value is None or value < STROKE_SWING:
        return withheld("no_stroke", "")
    return Measured(value)


def _wing_reach_mps(weak_hz, *, prf_hz, wavelength_m):
    """:func:`~mdpipe.process.wingbeat.wing_reach_hz` of the weak rows' reach ``weak_hz`` (Hz,
    :func:`~mdpipe.process.wingbeat.weak_reach_hz` on the dwell's spectrogram) as a speed (m/s), or None."""
    reach_hz = wing_reach_hz(weak_hz, prf_hz=prf_hz)
    return None if reach_hz is None else abs(_speed_mps(reach_hz, wavelength_m))


def _stroke_overrunning_span_mps(weak_hz, swing, *, prf_hz, wavelength_m, dwell_s):
    """The least reach (m/s) of wings whose faint rows light the span past ``REACH_SPAN_SHARE`` of its half
    (:func:`~mdpipe.process.wingbeat.overruns_span` of their reach ``weak_hz``, Hz) and whose
    reach swings over the dwell as a stroke's does (``swing()``, :func:`~mdpipe.process.wingbeat.stroke_swing`, read as
    :func:`wing_stroke` reads it, :func:`_stroke`: within 2 kHz of the body line), that share of the span's half as a
    speed; else None.

    Wing tips at 5-7 m/s overrun the span of a 94 GHz radar under a PRF of about 7 kHz (+-1.6-4.8 m/s at 2-6 kHz), a
    77 GHz one under 6 kHz, a K-band one under 2 kHz: their rows fill it a few dB over the noise, the dwell's band shows
    only the body line and their reach is known only to pass that share of the span; a wing's reach falls at the turns
    of its stroke. The bound returned is a spread as any other: held to 1 m/s at least (0.5 flying) by :func:`wings`,
    over what a swaying branch reaches, so a body that does not fly is read too (the gull of the default sweep crosses
    the beam at 5.9 m/s, 0.43 m/s in range); none of the 35 branches of the three default-family sweeps moved. The swing
    does not tell blades from wings by itself: blade tips hold their speed, but faint tips' rows light the span
    unevenly from frame to frame (their power beating, frames shorter than a turn, noise). Of the drones of the five
    evaluation sweeps and `make offmodel` whose faint rows pass that share of the span and whose echo repeats (21), 13
    swing 0.15 or more (up to 0.83), and a synthetic fill of the span beating at 6 Hz 0.13-0.78; each was read a drone
    first by its blade flashes (a comb, or flashes of an ambiguous period, after which a beat counts only within the
    measured reach of wings), or lies beyond this reading (a span of 12.5 m/s or more, whose share passes wings', or a
    dwell under 0.4 s). Two 77 GHz drones of six rotors seen 0.5 s at -5 dB, swinging 0.67 and 0.45 in spans this
    reading covers, are drones by their flashes alone: one whose blades show no flash and fill a W-band span faintly,
    beating, would read as a bird. Small birds beating 8-16 Hz swing under 0.06 (a 64 ms frame holds half a beat or
    more, a mid-stroke in each) and are read by their band instead."""
    if _stroke(swing, dwell_s=dwell_s).value is None or not overruns_span(weak_hz, prf_hz=prf_hz):
        return None
    return abs(_speed_mps(readable_reach_hz(prf_hz), wavelength_m))


def _least_wing_spread_mps(body_velocity, *, dwell_s):
    """Whether the body flies (``MIN_FLIGHT_SPEED_MPS``, or ``MIN_FLIGHT_DISTANCE_M`` in the ``dwell_s``), and the
    least half-width (m/s) its wings may spread: ``MIN_FLYING_WING_SPREAD_MPS`` if it flies, else
    ``MIN_WING_SPREAD_MPS``."""
    speed_mps = None if body_velocity.value is None else abs(body_velocity.value)
    flying = speed_mps is not None and (speed_mps >= MIN_FLIGHT_SPEED_MPS
                                        or speed_mps * dwell_s >= MIN_FLIGHT_DISTANCE_M)
    return flying, MIN_FLYING_WING_SPREAD_MPS if flying else MIN_WING_SPREAD_MPS


def _within_wing_reach(reach_mps, least_mps):
    """Whether a wing reach (m/s, or None: unknown) lies between ``least_mps`` and ``DRONE_SPREAD_MPS``."""
    return reach_mps is not None and least_mps <= reach_mps <= DRONE_SPREAD_MPS


def _wings_over_ambiguous_period(turn, beat, *, body_velocity, dwell_s, reach_mps):
    """The rotation ``turn`` of an unaliased band, withheld as ``ambiguous_period`` (blade flashes whose period the
    echo leaves open), or ``not_rotor`` where the echo beats like wings (``beat``, accepted by :func:`wings`) and its
    faint rows end within the reach of wings (``reach_mps()``, measured, between the least wing spread and
    ``DRONE_SPREAD_MPS``). Blade tips move at 20-150 m/s and light the rows of an unaliased band out to their Doppler,
    even flashing a few dB over the noise (the drones of three benchmarks whose flashes' period was ambiguous and whose
    reach was read: 24-208 m/s); a bird's power may repeat in part as its wing and body lines beat (four birds of
    7-14 Hz wingbeats at X, 77 and 94 GHz, flying 8-15 m/s: every 0.9-3.7 ms, their rows reaching 1.2-3.2 m/s; those
    repeats have since stopped counting as flashes: none stands over the lags about its own,
    :func:`~mdpipe.process.flashes.power_period`).
    A wingbeat read an octave apart (``ambiguous_period``, :class:`~mdpipe.process.wingbeat.Octave`) counts: a
    wing-like beat either way. Returns the rotation and whether the beat stands."""
    if beat.value is None or not _within_wing_reach(reach_mps(), _least_wing_spread_mps(body_velocity,
                                                                                        dwell_s=dwell_s)[1]):
        return turn, False
    note = (f"rotation not estimable: the echo repeats, but not as blade flashes do: it beats at {beat.value:.3g} Hz "
            f"and its rows end within {reach_mps():.2g} m/s of the body line, as wings do (blade tips reach further)")
    return Rotation.withheld("not_rotor", note), True


def wings(beat, halfwidth, body_velocity, *, dwell_s, described=None, reach_mps=lambda: None,
          overrun_mps=lambda: None):
    """A repeating micro-Doppler is a wingbeat only if its spread is that of wings (m/s, wavelength-free).

    Below ``MIN_WING_SPREAD_MPS`` it is swaying clutter (a branch, leaves); above ``DRONE_SPREAD_MPS``
    faster than wing tips move. A target whose body flies at ``MIN_FLIGHT_SPEED_MPS`` or more, or travels
    ``MIN_FLIGHT_DISTANCE_M`` in the ``dwell_s`` (a branch, anchored, moves at most twice its sway amplitude,
    tenths of a metre), is no branch: its wings may spread down to ``MIN_FLYING_WING_SPREAD_MPS`` (a bird
    flying along the line of sight beats its wings across it; a heron crossing at 1.2 m/s spread 0.94 m/s). An
    aliased band is at least the span's half-width: wings when that lies between the bounds (at 77-94 GHz a span
    of 1-4 m/s, which a bird's wing tips overrun; a span over ``DRONE_SPREAD_MPS`` already reads drone). ``beat``
    may be any measurement of wings (a flapping share): ``described`` names it in the notes (by default: a
    micro-Doppler repeating at its value in Hz).

    Where the band is narrower than wings (or none stands out of the dwell spectrum), ``reach_mps`` (the wings'
    reach in the frames, m/s, or None: :func:`~mdpipe.process.wingbeat.wing_reach_hz`) stands for it: weak wings,
    or wings beating in bursts between glides, light the frames they beat in a few dB over the noise, and the dwell's
    band, 10 dB over its smoothed spectrum, shows only the body line. Where that reach passes ``REACH_SPAN_SHARE`` of
    the span's half (not read), ``overrun_mps`` (the least it can be, m/s, where it swings as a stroke's:
    :func:`_stroke_overrunning_span_mps`; else None) stands for it.
    """
    if beat.value is None:
        return beat
    described = described or f"a micro-Doppler repeating at {beat.value:.3g} Hz"
    flying, low = _least_wing_spread_mps(body_velocity, dwell_s=dwell_s)
    if halfwidth.value is None or (halfwidth.status == OK and halfwidth.value < low):
        if _within_wing_reach(reach_mps(), low) or _within_wing_reach(overrun_mps(), low):
            return beat
    if halfwidth.value is None:
        return withheld("not_applicable", f"{described}, but no band above the noise to tell wings from swaying "
                        "clutter")
    if halfwidth.status in (OK, "aliased") and low <= halfwidth.value <= DRONE_SPREAD_MPS:
        return beat
    return withheld("not_applicable", f"{described} is no wingbeat: its "
                    f"half-width {halfwidth.value:.2g} m/s is outside the {low:g}-{DRONE_SPREAD_MPS:g} m/s of wings"
                    + ("" if flying else f" ({MIN_FLYING_WING_SPREAD_MPS:g} m/s for a body flying at "
                                         f"{MIN_FLIGHT_SPEED_MPS:g} m/s or more, or {MIN_FLIGHT_DISTANCE_M:g} m "
                                         "in the dwell)"))


def _columns(primary, measured, derived=None):
    """The row entries of one measured quantity: its value, derived values, and every one's status."""
    entries = {primary: measured.value, f"{primary}_status": measured.status}
    for key in FEATURE_GROUPS[primary]:
        entries[key] = None if measured.value is None or derived is None else derived.get(key)
        entries[f"{key}_status"] = measured.status
    return entries


def analyse_target(signal, *, prf_hz, wavelength_m, noise_power, params, track=None, flash_views=None,
                   ramp_share=1.0, ranged=True, hum=mains.SEARCH, flanks=None, reread=True):
    """Measure every feature of one target's complex slow-time ``signal`` (channels combined).

    Parameters
    ----------
    signal : ndarray (n_chirps,) complex
    prf_hz, wavelength_m : float
    noise_power : float
        Noise power per chirp of ``signal`` (V^2).
    params : ProcessParams
    ranged : bool
        False for an echo without range (a CW recording): its body velocity is unfolded by speed alone
        (:func:`dealias_velocity`), and its noise, read from the echo, may be the floor of blade tips folded over a
        span too narrow for them (:func:`hidden_aliasing_note`).
    track : RangeTrack or None
        The target's range over the dwell, which unfolds an aliased body Doppler; None: held in one range bin, or,
        not ``ranged``, an echo without range (a CW recording: :mod:`mdpipe.process.cw`).
    flash_views : callable or None
        Returns the target's :class:`~mdpipe.process.ranging.FlashViews` (its slow time in parts of every ramp and
        at its range sides; :func:`mdpipe.process.pipeline.flash_views`), called only where a path reads the echo's
        power period or leaves flash times ambiguous, or a chopping is read (:func:`_flashes_between`); ``ramp_share``:
        the sampled part of the ramp's share of the chirp period.
    hum : Hum or None
        The mains hum the caller took out of ``signal`` already (None: it found none); by default it is looked for
        here (``params.mains_hz``) and taken out of the echo and its ``flash_views`` (:mod:`mdpipe.process.mains`).
    flanks : callable or None
        Returns the target's :class:`~mdpipe.process.ranging.Flanks`: the power of the range bins either side of it,
        where a long ramp moves its blades' flashes (:func:`mdpipe.process.ranging.flank_powers`), and the capture's
        common mode, read only where its own echo shows a body line and no flashes, and no hum was found in it
        (:func:`_flashes_in_flanks`); None: not read (a short ramp, a CW recording, bursts or clipping in the capture).
    reread : bool
        Whether a chopping read is read again on the ramp's parts (:func:`_flashes_between`): not where bursts of
        another radar cross the capture or samples clip (a burst falls in some parts of some ramps, again and again:
        values moved under bursts every 9.71 chirps in `make bench-impairments`).
    """
    dwell_s = len(signal) / prf_hz
    s = np.asarray(signal, dtype=np.complex128)
    s = s - s.mean()  # static clutter in this bin
    if hum is mains.SEARCH:
        s, hum = mains.taken_out(s, prf_hz=prf_hz, mains_hz=params.mains_frequencies_hz)
        if hum is not None and flash_views is not None:
            flash_views = functools.cache(functools.partial(_views_without_hum, flash_views, hum, prf_hz=prf_hz))
    moving = float(np.mean(np.abs(s) ** 2))
    snr = (moving - noise_power) / noise_power if noise_power > 0 else np.inf
    snr_db = Measured(float(10 * np.log10(snr))) if snr > 0 else withheld("no_signal", "no power above the noise")
    body = body_motion(s, prf_hz=prf_hz, wavelength_m=wavelength_m, track=track, ranged=ranged)
    hidden = None if ranged else hidden_aliasing_note(prf_hz=prf_hz, wavelength_m=wavelength_m,
                                                      elevation_deg=params.elevation_deg)
    band = doppler_band(s, body.demodulated, prf_hz=prf_hz, wavelength_m=wavelength_m, noise_power=noise_power,
                        hidden_aliasing=hidden)
    body_doppler_hz = 0.0 if body.track_hz is None else float(doppler.fold_hz(np.mean(body.track_hz), prf_hz=prf_hz))
    bandwidth, extent = paper_bandwidth(body.demodulated, prf_hz=prf_hz, threshold_db=params.threshold_db,
                                        body_doppler_hz=body_doppler_hz, aliased=band.aliased)
    ramp = sides = None
    if flash_views is not None:
        if ramp_readable(ramp_share):  # (else the capture is not read again for the ramp's parts)
            ramp = functools.cache(lambda: ramp_train(demodulated_parts(flash_views().parts, body.track_hz,
                                                                        prf_hz=prf_hz),
                                                      ramp_share=ramp_share, prf_hz=prf_hz))
        sides = functools.cache(lambda: demodulated_parts(flash_views().sides, body.track_hz, prf_hz=prf_hz))
    turn = rotation(body.demodulated, aliased=band.aliased, half_width_hz=band.half_width_hz, prf_hz=prf_hz,
                    noise_power=noise_power, n_blades=params.n_blades, dwell_s=dwell_s,
                    halfwidth_mps=band.halfwidth.value, body_found=body.track_hz is not None,
                    dense_half_width_hz=band.dense_half_width_hz, elevation_deg=params.elevation_deg, ramp=ramp,
                    sides=sides)
    if hidden is not None:
        turn = _undersampled(turn, hidden)
    if hum is not None:
        turn = _on_hum(turn, hum, body_hz=body_doppler_hz, prf_hz=prf_hz)
    as_read = turn
    if reread:
        turn = _flashes_between(turn, ramp, prf_hz=prf_hz)

    def lengths(read):  # the tip Doppler, blade length and flash edges of a rotation read
        return blade_length(body.demodulated, rate=read.rate, chopping_hz=read.chopping.value, aliased=band.aliased,
                            half_width_hz=band.half_width_hz, prf_hz=prf_hz, wavelength_m=wavelength_m,
                            noise_power=noise_power, params=params, n_blades=read.n_blades)

    tip, length, edges = lengths(turn)
    folded = turn if turn is not as_read else _folded_unseen(  # (read on the ramp's parts: no shorter flash period)
        turn, aliased=band.aliased, tips_seen=edges is not None, prf_hz=prf_hz, wavelength_m=wavelength_m,
        elevation_deg=params.elevation_deg, dwell_s=dwell_s)
    if folded is not turn:
        turn = folded
        tip, length, edges = lengths(turn)  # (no rate: none)
    wings_may_repeat = (turn.chopping.value is None and turn.chopping.status == "ambiguous_period"
                        and not band.aliased)  # (or wings' beat: see _wings_over_ambiguous_period)
    if flanks is not None and hum is None and body.track_hz is not None and turn.chopping.status == "no_flashes":
        # (no rate either way: the lengths stand; flashes on both flanks are no wings': wings_may_repeat stays False)
        spread_hz = float(np.subtract(*np.percentile(doppler.fold_hz(np.asarray(body.track_hz) - body_doppler_hz,
                                                                      prf_hz=prf_hz), BODY_SPREAD_PERCENTILES)))
        turn = _flashes_in_flanks(turn, flanks, prf_hz=prf_hz, mains_hz=params.mains_frequencies_hz,
                                  own_power=np.abs(s) ** 2, body_hz=body_doppler_hz, body_spread_hz=spread_hz)
    if turn.chopping.value is not None or (turn.chopping.status in ROTOR_EVIDENCE and not wings_may_repeat):
        beat = flaps = stroke = withheld("not_applicable", "")  # blade flashes exclude a bird
    elif turn.chopping.status == "not_rotor":  # a comb spaced over any wingbeat (combs.MIN_CHOP_HZ up)
        beat = flaps = stroke = withheld("not_applicable", "no wingbeat read: a line comb repeats the echo faster "
                                         "than wings beat, and a slower repeat in it is its lines' beat (rotors at "
                                         "rates apart)")
    else:
        dwell = functools.cache(lambda: dwell_frames(body.demodulated, prf_hz=prf_hz, noise_power=noise_power))
        weak = functools.cache(lambda: weak_reach_hz(*dwell()))  # read by the wings' reach and by their overrun
        reach = functools.cache(lambda: _wing_reach_mps(weak(), prf_hz=prf_hz, wavelength_m=wavelength_m))
        swing = functools.cache(lambda: stroke_swing(*dwell()))  # read by the stroke and by wings overrunning the span
        overrun = functools.cache(lambda: _stroke_overrunning_span_mps(weak(), swing, prf_hz=prf_hz,
                                                                       wavelength_m=wavelength_m, dwell_s=dwell_s))
        as_wings = functools.partial(wings, halfwidth=band.halfwidth, body_velocity=body.velocity, dwell_s=dwell_s,
                                     reach_mps=reach, overrun_mps=overrun)  # each held to the spread of wings
        still = not _least_wing_spread_mps(body.velocity, dwell_s=dwell_s)[0]  # read by the wings' three readings
        beat = as_wings(wingbeat_rate(body.demodulated, prf_hz=prf_hz, noise_power=noise_power, dwell_s=dwell_s,
                                      band_hz=2 * band.half_width_hz, still=still))
        flaps = flapping(dwell(), still=still)
        flaps = as_wings(flaps, described=flaps.value is not None and f"a micro-Doppler in bursts over "
                         f"{flaps.value:.0%} of the dwell, dark between them,")
        stroke = wing_stroke(swing, still=still, dwell_s=dwell_s)
        stroke = as_wings(stroke, described=stroke.value is not None and f"a micro-Doppler whose reach swings "
                          f"{stroke.value:.0%} of its greatest over the dwell")
        if wings_may_repeat:
            turn, beating = _wings_over_ambiguous_period(turn, beat, body_velocity=body.velocity, dwell_s=dwell_s,
                                                         reach_mps=reach)
            if not beating:
                beat = flaps = stroke = withheld("not_applicable", "")  # blade flashes exclude a bird
    if hidden is not None:
        beat, flaps, stroke = (_undersampled_wings(m, hidden) for m in (beat, flaps, stroke))
    rate_hz = turn.rate.value
    row = {
        **_columns("snr_db", snr_db),
        **_columns("micro_doppler_halfwidth_mps", band.halfwidth),
        **_columns("doppler_bw_hz", bandwidth, extent and {
            "doppler_bw_mps": float(bandwidth.value * wavelength_m / 2), "doppler_low_hz": extent[0],
            "doppler_high_hz": extent[1]}),
        **_columns("chopping_freq_hz", turn.chopping),
        **_columns("rotation_rate_hz", turn.rate, rate_hz and {
            "rotation_period_s": 1.0 / rate_hz, "rotor_rates_hz": list(turn.rotor_rates_hz),
            "flash_period_s": float(rotor.flash_period_s(rate_hz, n_blades=turn.n_blades))}),
        **_columns("doppler_bw_spectrogram_hz", tip, {"tip_doppler_hz": tip.value and tip.value / 2}),
        **_columns("blade_length_m", length),
        **_columns("body_velocity_mps", body.velocity, {"body_doppler_hz": body_doppler_hz}),
        **_columns("wingbeat_freq_hz", beat, beat.value and {"wingbeat_period_s": 1.0 / beat.value}),
        **_columns("flapping_share", flaps),
        **_columns("wing_stroke_swing", stroke),
        "aliased": bool(band.aliased), "n_rotors": len(turn.rotor_rates_hz) or None,
        "n_blades": turn.n_blades, "n_blades_source": turn.n_blades_source,
        "mains_hum_hz": None if hum is None else hum.f0_hz,
    }
    window, hop = display_window_s(row, params)
    shown = doppler.spectrogram(s, prf_hz=prf_hz, window_s=window, hop_s=hop)
    row["stft_window_s"], row["stft_hop_s"] = shown.window_s, shown.hop_s
    notes = [m.note for m in (body.velocity, band.halfwidth, bandwidth, turn.chopping, turn.rate, tip, length, beat,
                              flaps, stroke)
             if m.note and (m.status != OK or m is body.velocity or m is turn.rate)]  # (ok: how it was read)
    notes = list(dict.fromkeys(notes))  # one sentence once (blade length and its tip share theirs)
    if hum is not None:
        notes.append(hum.note())
    notes.extend(display_adjustments(params, shown, prf_hz=prf_hz, dwell_s=dwell_s))
    # the edges were read about the body line; the figures show the echo as received
    shown_edges = None if edges is None else tuple(e + body_doppler_hz for e in edges)
    return TargetAnalysis(row=row, spectrum=band.spectrum, spectrogram=shown, paper_extent_hz=extent,
                          flash_edges_hz=shown_edges, notes=notes)
