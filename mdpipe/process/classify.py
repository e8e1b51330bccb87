"""drone / bird / none, from wavelength-independent quantities: periodicity rates and spreads in m/s.

A rotor's blade tips move at 20-150 m/s and flash 50-2000 times a second; a bird's wing tips
move at a few m/s and beat 0.3-20 times a second; a swaying branch or a leaf moves at tenths of a
m/s. So one rule serves X band and 94 GHz:

* drone: a blade line comb (a chopping frequency measured), blade flashes whose period is ambiguous
  (``ROTOR_EVIDENCE``: the chopping withheld for that reason), or a micro-Doppler half-width above
  ``DRONE_SPREAD_MPS`` (an aliased band counts as at least half the unambiguous span);
* bird: a wingbeat, which is only measured with a half-width between ``MIN_WING_SPREAD_MPS`` (or
  ``MIN_FLYING_WING_SPREAD_MPS`` for a body flying at ``MIN_FLIGHT_SPEED_MPS`` or more, or travelling
  ``MIN_FLIGHT_DISTANCE_M`` in the dwell) and ``DRONE_SPREAD_MPS`` (about the body line, or the band's
  centre when no body line stands out; for an aliased band, the span's half-width, which the wings' spread
  exceeds; for faint wings whose rows pass 0.8 of the span's half with a reach that swings as a stroke's, that share
  of it); or, within the same bounds, wings lit in bursts and dark between them while the body line holds
  (``flapping_share``: glides between bursts too short for a wingbeat, or the turns of a slow stroke; rotors never
  stop); or, for a body that flies, within the same bounds, wings whose reach swings over the dwell as a stroke's
  does (``wing_stroke_swing``: too few beats for a wingbeat; a rotor's tips hold their speed);
* none: a wing signature in an I/Q recording whose span cannot hold a rotor's tips (status ``undersampled``: a
  drone's inner blades, all it shows of one, beat as wings do);
* none: nothing moving above the noise, or neither signature (a branch swaying in the wind repeats
  too, but its micro-Doppler stays below ``MIN_WING_SPREAD_MPS`` and it does not fly).
"""

DRONE_SPREAD_MPS = 10.0
MIN_WING_SPREAD_MPS = 1.0
MIN_FLIGHT_SPEED_MPS = 2.0         # a body this fast flies: no branch (its body line stays at 0 m/s) ...
MIN_FLIGHT_DISTANCE_M = 1.0        # ... or one that travels this far in the dwell (a branch sways by tenths of a m)
MIN_FLYING_WING_SPREAD_MPS = 0.5   # ... and its wings may spread this little (beating across the line of sight)
ROTOR_EVIDENCE = ("ambiguous_period", "blade_conflict")  # chopping statuses of blade flashes found, rotation withheld
UNDERSAMPLED = "undersampled"  # a wing reading of a CW echo whose span cannot hold a rotor's tips: no bird
WING_KEYS = ("wingbeat_freq_hz", "flapping_share", "wing_stroke_swing")


def classify(row, *, detected):
    """Class of a feature row, and the reason."""
    if not detected:
        return "none", "no moving target above the noise"
    spread = row.get("micro_doppler_halfwidth_mps")
    if row.get("chopping_freq_hz") is not None:
        return "drone", f"blade line comb at {row['chopping_freq_hz']:.1f} Hz"
    if row.get("chopping_freq_hz_status") in ROTOR_EVIDENCE:
        return "drone", "blade flashes, their period ambiguous"
    if spread is not None and spread > DRONE_SPREAD_MPS:
        return "drone", f"micro-Doppler half-width {spread:.1f} m/s > {DRONE_SPREAD_MPS:g} m/s"
    if any(row.get(f"{key}_status") == UNDERSAMPLED for key in WING_KEYS):
        return "none", ("a micro-Doppler that beats as wings do, but in a span too narrow for a rotor's tips, where a "
                        "drone's inner blades beat so too")
    if row.get("wingbeat_freq_hz") is not None:  # only measured with a wing-like half-width (features.wings)
        return "bird", f"wingbeat {row['wingbeat_freq_hz']:.2f} Hz, half-width {spread or 0:.1f} m/s"
    if row.get("flapping_share") is not None:  # likewise
        return "bird", (f"wing micro-Doppler in bursts over {row['flapping_share']:.0%} of the dwell, dark between "
                        f"them while the body line holds, half-width {spread or 0:.1f} m/s")
    if row.get("wing_stroke_swing") is not None:  # likewise, and only for a body that flies
        return "bird", (f"wings whose reach swings {row['wing_stroke_swing']:.0%} of its greatest over the dwell (a "
                        f"stroke; too few beats for a wingbeat), half-width {spread or 0:.1f} m/s")
    return "none", "moving, but neither blade flashes nor a wingbeat"
