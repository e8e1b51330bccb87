"""drone / bird / none, from wavelength-independent quantities: periodicity rates and spreads in m/s.

A rotor's blade tips move at 20-150 m/s and flash 50-2000 times a second; a bird's wing tips
move at a few m/s and beat 0.3-20 times a second. So one rule serves X band and 76 GHz:

* drone: periodic blade flashes, or a micro-Doppler half-width above ``DRONE_SPREAD_MPS``
  (an aliased band counts as at least half the unambiguous span);
* bird: a wingbeat with a half-width below ``DRONE_SPREAD_MPS``;
* none: nothing moving above the noise, or neither signature.
"""

DRONE_SPREAD_MPS = 10.0


def classify(row, *, detected):
    """Class of a feature row, and the reason."""
    if not detected:
        return "none", "no moving target above the noise"
    spread = row.get("micro_doppler_halfwidth_mps")
    if row.get("rotation_rate_hz") is not None:
        return "drone", f"periodic blade flashes at {row['chopping_freq_hz']:.1f} Hz"
    if spread is not None and spread > DRONE_SPREAD_MPS:
        return "drone", f"micro-Doppler half-width {spread:.1f} m/s > {DRONE_SPREAD_MPS:g} m/s"
    if row.get("wingbeat_freq_hz") is not None:
        return "bird", f"wingbeat {row['wingbeat_freq_hz']:.2f} Hz, half-width {spread or 0:.1f} m/s"
    return "none", "moving, but neither blade flashes nor a wingbeat"
