"""Range-Doppler images: one drone's blade flashes detected a few range bins off it, as a second target.

An FMCW beat frequency holds the Doppler with the range: a scatterer at Doppler ``f_D`` lands ``f_D T_s`` range bins
off its range (``T_s`` the sampled part of the ramp). A blade's tip flashes at up to ``2 v_tip / lambda``: at 94 GHz a
tip at 74 m/s lands 4 bins (of 0.6 m) off its hub, the approaching tips on one side, the receding on the other. Their
mean power over the dwell can peak there above the body's, and the tracker then follows two targets, each with the
drone's whole line comb (three W-band drones of the evaluation sweeps at seeds 2026 and 777 and of the held-out one:
two rows a drone, 1.2-3.3 bins either side of the truth, their chopping frequencies 0-0.34 % apart).

A weaker target is taken for an image of a stronger one when both show a line comb whose chopping frequencies lie
within ``IMAGE_CHOP_SHARE`` of each other and it lies within the reach of a blade tip's Doppler no faster than sound
(``SPEED_OF_SOUND_MPS``) of it. Two drones of one make hovering within those few metres would be taken for one.

Where the stronger shows no body line, both are images, each of one side's blades: the drone is analysed again at its
hub, midway between them (:func:`mdpipe.process.pipeline.without_images`). In those four drones the midpoint lay
0.05-0.16 m from the truth, the stronger image 0.76-2.2 m.

At a low PRF and a long ramp the images lie metres off and their tips fold too often to show a comb: they are told
by their flashes instead, which land in both images at once (:func:`flash_image_owners`).
"""

import numpy as np

from mdpipe.physics.rotor import SPEED_OF_SOUND_MPS
from mdpipe.process.interference import correlation

IMAGE_CHOP_SHARE = 0.02  # two targets' combs this close (relative) may be one drone's
COINCIDENT_FLASHES = 0.5  # two targets' powers correlated this well over the dwell flash together: one drone's images
IMAGE_SYMMETRY = 0.25    # a drone between its images lies this share of their half-span from their midpoint, at most


def image_reach_m(params):
    """How far (m) from a drone its blade flashes can land in range: the Doppler of a tip at the speed of sound,
    ``2 v / lambda``, times the sampled ramp ``T_s`` (range bins), times the bin."""
    return 2.0 * SPEED_OF_SOUND_MPS / params.wavelength_m * params.sampled_duration_s * params.range_bin_m


def image_owners(rows, *, reach_m):
    """For each of ``rows`` (strongest first), the index of the stronger row it is an image of, else None: both hold
    a chopping frequency, within ``IMAGE_CHOP_SHARE`` of each other, and their ranges lie within ``reach_m``. A row
    that is an image owns none."""
    owners = [None] * len(rows)
    for j, row in enumerate(rows):
        if row.get("chopping_freq_hz") is None or row.get("range_m") is None:
            continue
        for i in range(j):
            other = rows[i]
            if owners[i] is not None or other.get("chopping_freq_hz") is None or other.get("range_m") is None:
                continue
            if (abs(other["chopping_freq_hz"] - row["chopping_freq_hz"]) <= IMAGE_CHOP_SHARE * other["chopping_freq_hz"]
                    and abs(other["range_m"] - row["range_m"]) <= reach_m):
                owners[j] = i
                break
    return owners


def flashes_coincide(power_a, power_b):
    """Whether two targets' powers (per chirp, over one dwell) correlate ``COINCIDENT_FLASHES`` or more
    (:func:`mdpipe.process.interference.correlation`): the same flashes, chirp for chirp. Independent echoes a few
    metres apart correlate to a few hundredths (a drone and a bird or a walker at 24-94 GHz: 0.01-0.06), a target and
    the common mode of the range bins 0.34 at most (:mod:`mdpipe.process.interference`); a drone's two images at a low
    PRF 0.51-0.96. Powers of other lengths, or not finite, coincide with none."""
    a, b = np.asarray(power_a, dtype=np.float64), np.asarray(power_b, dtype=np.float64)
    if a.shape != b.shape or a.ndim != 1 or not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        return False
    return correlation(a, b) >= COINCIDENT_FLASHES


def flash_image_owners(rows, powers, owners, *, reach_m):
    """``owners`` (:func:`image_owners`) with the images its combs missed, told by their flashes: targets that neither
    are nor own a comb image, within ``reach_m`` of one another, whose ``powers`` (per chirp) all flash together
    (:func:`flashes_coincide`, every pair of them) are one drone's images, one for each side's blades.

    A long ramp moves a blade's flash far in range (an up-chirp's beat moves the approaching blades one way and the
    receding the other, by their Doppler times the sampled ramp), and at a low PRF the images show no comb of their
    own to match: their tips fold many times. Two blades opposite flash at once, on both sides: at PRFs of 1.5-6 kHz
    the two images of 2-blade rotors correlated 0.51-0.96, chirp for chirp, while the drone's own range bin, its body
    line steady, did not (0.06-0.13). Images that straddle a target read as a drone whose body line was found, its
    range within ``IMAGE_SYMMETRY`` of their half-span from their midpoint and within ``reach_m`` of each, are its
    own, however strong it is against them; else the strongest image owns the others (and, without a body line, is
    analysed at their hub by :func:`mdpipe.process.pipeline.without_images`). A target read otherwise keeps none: the
    images may be all that shows the drone. Odd blade counts flash one side at a time: their images do not flash
    together and are not told so. Bursts of another radar crossing ours light every bin at once, and all targets
    flash together; a clipped echo's images (:mod:`mdpipe.process.saturation`) swing with its power: the caller does
    not ask then (on `make bench-impairments`, a clipped capture's image was grouped so and left a drone). A target
    whose echo holds mains hum (``mains_hum_hz``) swings with the supply, not with blades: it is no member."""
    owners = list(owners)
    owning = {owner for owner in owners if owner is not None}
    pool = [i for i, owner in enumerate(owners) if owner is None and i not in owning
            and rows[i].get("range_m") is not None and rows[i].get("mains_hum_hz") is None]

    def together(i, j):
        return abs(rows[i]["range_m"] - rows[j]["range_m"]) <= reach_m and flashes_coincide(powers[i], powers[j])

    clusters, grouped = [], set()
    for n, i in enumerate(pool):  # strongest first, each joined by every weaker one flashing with all its members
        if i in grouped:
            continue
        members = [i]
        for j in pool[n + 1:]:
            if j not in grouped and all(together(k, j) for k in members):
                members.append(j)
        if len(members) > 1:
            clusters.append(members)
            grouped.update(members)
    for members in clusters:
        ranges = [rows[i]["range_m"] for i in members]
        middle, half_span = (min(ranges) + max(ranges)) / 2, (max(ranges) - min(ranges)) / 2
        hub = next((k for k, row in enumerate(rows) if owners[k] is None and k not in grouped
                    and row.get("class") == "drone" and row.get("body_velocity_mps") is not None
                    and row.get("range_m") is not None and abs(row["range_m"] - middle) <= IMAGE_SYMMETRY * half_span
                    and all(abs(row["range_m"] - r) <= reach_m for r in ranges)), None)
        owner = members[0] if hub is None else hub
        for i in members:
            if i != owner:
                owners[i] = owner
    return owners


def image_note(image, *, reach_m, by_flashes=False):
    """The clause for the kept row: where its image lay and why it is no target of its own (``by_flashes``: told by
    its flashes, :func:`flash_image_owners`, else by its comb)."""
    told = ("its blade flashes coinciding chirp for chirp with another detection's" if by_flashes else
            f"its line comb at {image['chopping_freq_hz']:.4g} Hz")
    return (f"a second detection at {image['range_m']:.2f} m, {told}, is this drone's range-Doppler image (blade "
            f"flashes land up to {reach_m:.3g} m off a drone at this radar's ramp), not a target: the drone's hub lies "
            "at this range or between them")


def seen_from_a_side(row):
    """Whether a drone's ``row`` shows no body line: the body echoes from the hub, so a detection without it,
    paired with an image (:func:`image_owners`), is itself one side's blade flashes."""
    return row.get("body_velocity_mps") is None


def hub_note(first, second, *, reach_m):
    """The clause for a drone analysed at its hub between its two images, rows ``first`` and ``second``."""
    return (f"analysed at its hub, midway between two detections of its blade flashes at {first['range_m']:.2f} and "
            f"{second['range_m']:.2f} m, its range-Doppler images (an up-chirp's beat moves the approaching blades' "
            f"flashes one way and the receding blades' the other, up to {reach_m:.3g} m at this radar's ramp): each "
            "image holds one side's flashes, repeating once per chopping period whatever the blade count")
