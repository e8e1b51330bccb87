"""Validity of each measured value, as data: ``ok`` or a reason code, beside the sentence for people.

Every feature column ``X`` of a row has a companion ``X_status``. A value with status ``ok`` is a
measurement mdpipe stands behind. A value with another status is either absent (null, the code says
why) or present but not stood behind: for ``assumed_blades``, ``assumed_elevation`` and ``assumed_speed`` resting
on an assumption the row or its status names (``n_blades``, ``n_blades_source``, ``elevation_deg``); a tip Doppler
with ``few_harmonics``; a wingbeat with ``ambiguous_period`` (it or twice it), ``repeats_scatter`` or
``short_bursts`` (not sharp to 3 %); a CW recording's rotation or wings with ``undersampled``.
Programs should use values whose status is ``ok``.
"""

from dataclasses import dataclass

OK = "ok"

STATUS_CODES = {
    OK: "measured",
    "no_target": "no moving target was detected in the range gate",
    "no_signal": "the capture holds no usable signal in this bin",
    "aliased": "the micro-Doppler wraps around the span 1/Tp: its extent is unknown",
    "dwell_short": "the dwell holds too few periods of what is measured",
    "no_flashes": "no periodic blade flashes (no line comb) in the echo",
    "ambiguous_period": ("periods a whole multiple apart (two estimators, flashes seen only in the power's "
                         "period, which may be a multiple of theirs, a comb whose every N-th line stands out: "
                         "a turn or a chopping comb, or a wingbeat whose two looks read an octave apart); the dwell "
                         "does not tell which"),
    "not_rotor": ("the echo is periodic, but too narrow in Doppler for blades turning at that rate, or its rows end "
                  "within the reach of wings"),
    "assumed_blades": "depends on the blade count, which the echo does not tell and the user did not give",
    "assumed_elevation": "depends on the rotor plane's elevation beta, which was not given: beta = 0 assumed",
    "blade_conflict": "the blade count given contradicts the echo (odd/even flashes or blade imbalance lines)",
    "no_rotation": "needs the rotation rate, which was not measured",
    "undersampled": ("read from an I/Q (CW) recording whose sample rate cannot hold a rotor's blade tips: a rotation "
                     "given may be a fraction or a multiple of the true one, and wings cannot be told from a drone's "
                     "inner blades (read as `none`)"),
    "elevation": "the rotor plane is too close to face-on (|beta| > 80 deg): Eq. 6 divides by ~0",
    "few_harmonics": "the blade tips span too few Doppler bins (under 8 a side) of a frame holding one flash for the "
                     "flash edges to be sharp",
    "no_edges": "no flash frame shows both Doppler edges inside the span",
    "edges_inside_band": "the micro-Doppler reaches well beyond the flash edges: they are not the tips' (folded tips)",
    "edges_scatter": "the flash edges scatter too much from flash to flash (flashes near the noise): their median is not sharp",
    "tilt_sensitive": ("at this elevation a rotor disc tilted by the drone's attitude (up to 5 deg) moves cos(beta), and r, "
                       "by more than 3 %"),
    "no_body_line": "no body line stands out of the micro-Doppler",
    "body_unsteady": "the strongest line jumps between the body and rotor lines: no steady body track",
    "velocity_ambiguous": "the Doppler gives the velocity only modulo lambda PRF / 2 and the range track cannot tell which",
    "assumed_speed": ("an I/Q (CW) recording's body velocity: the one alias of its Doppler under 25 m/s, given on that "
                      "assumption (a faster target would read another; no range tells which)"),
    "body_only": "only the body line crosses the threshold: no micro-Doppler extent",
    "below_threshold": "nothing in the spectrum stands the threshold above its mean",
    "no_wingbeat": "no repeating wingbeat pattern in the dwell",
    "short_bursts": ("a wingbeat read on two repeats or fewer for a bird whose flapping bursts, as the wing rows mark "
                     "them, hold under three of its periods: its repeat pairs frames across the switches to gliding, "
                     "which shift it by a few per cent"),
    "repeats_scatter": ("the wing pattern's repeats scatter about whole multiples of its period (a standard error over "
                        "1 % of it): the period is not sharp to the 3 % a wingbeat is held to"),
    "no_glide": "no flapping bursts with glides between them (wings that beat throughout, or no wings)",
    "no_stroke": "no wing rows whose reach changes over the dwell as a stroke's does (a rotor's holds, a glide's too)",
    "not_flying": ("the body neither flies nor travels in the dwell: a swaying branch's micro-Doppler changes as a "
                   "stroke's does"),
    "not_applicable": "not a quantity of this target (e.g. the wingbeat of an echo with blade flashes)",
    "clipping_image": ("the capture clips and this echo is weak enough to be a harmonic or intermodulation image of its "
                       "strongest target (read as `none`)"),
    "mains_hum": ("the chopping frequency read falls on the harmonics of the mains hum taken out of the echo "
                  "(`mains_hum_hz`): a rotor held still at a multiple of the grid's rate and hum give the same lines "
                  "(`--mains-hz none` keeps them)"),
    "interference": ("another radar's chirps cross the capture and this echo's power follows their bursts, or its only "
                     "sign of a rotor is flashes of an ambiguous period, as bursts repeat (read as `none`)"),
    "impulse": ("this echo's power over the noise lies in its 2 strongest samples and the 4 beside each, its others "
                "within the noise: a glitch or a click, not a target (read as `none`)"),
}


@dataclass(frozen=True)
class Measured:
    """A value, its status code (a key of :data:`STATUS_CODES`) and, unless ok, the sentence why."""

    value: object = None
    status: str = OK
    note: str = ""

    def __post_init__(self):
        if self.status not in STATUS_CODES:
            raise ValueError(f"unknown status {self.status!r}")


def withheld(status, note):
    """No value, for the reason ``status`` (``note`` says it for people)."""
    return Measured(None, status, note)
