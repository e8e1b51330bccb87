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
by their flashes instead, which land in both images at once (even blade counts) or by turns, half a flash period
apart (odd ones: :func:`flashes_by_turns`; :func:`flash_image_owners`).
"""

from typing import NamedTuple

import numpy as np

from mdpipe.physics.rotor import SPEED_OF_SOUND_MPS
from mdpipe.process.filters import robust_sigma
from mdpipe.process.flashes import correlation_near, standardized_correlations
from mdpipe.process.interference import correlation

IMAGE_CHOP_SHARE = 0.02  # two targets' combs this close (relative) may be one drone's
COINCIDENT_FLASHES = 0.5  # two targets' powers correlated this well over the dwell flash together: one drone's images
TURN_SIGMAS = 4.0        # two powers flashing by turns correlate this many robust sigmas at their offset, and each
                         # repeats this many at twice it ...
TURN_SHARE = 0.5         # ... and under this share of that at the offset itself
IMAGE_SYMMETRY = 0.25    # a drone between its images lies this share of their half-span from their midpoint, at most
AT_ONCE, BY_TURNS = "at_once", "by_turns"  # how two images' flashes come: together (even blade counts) or by turns


class FlashImages(NamedTuple):
    """:func:`flash_image_owners`' reading: each row's owner (None: a target), and the images among them told by
    flashes coming by turns with another's (:func:`flashes_by_turns`)."""

    owners: list
    by_turns: frozenset = frozenset()


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


def flashes_by_turns(power_a, power_b, *, longest_chirps):
    """Whether two targets' powers (per chirp, over one dwell) flash by turns, half a flash period apart: the two
    range-Doppler images of rotors with an odd blade count, one holding the approaching blades' flashes, the other the
    receding blades' (an odd count's blade reaches the receding side half a chopping period after one passed the
    approaching side; an even count's opposite blades pass both at once, :func:`flashes_coincide`).

    Their cross-correlation peaks at an offset ``tau`` (any odd multiple of half a flash period, the one whose lag
    falls nearest whole chirps for flashes shorter than a chirp), up to ``longest_chirps`` (the longest chopping
    period searched), ``TURN_SIGMAS`` robust sigmas of it over the lags; each power repeats at ``2 tau`` (whole flash
    periods) ``TURN_SIGMAS`` of its own, and at ``tau`` under ``TURN_SHARE`` of that (else ``tau`` is a whole period
    of its own and the pair is no pair of sides: two drones' trains at one rate line up at some offset too; only half
    a period apart are they sides). Measured on the low-PRF sweeps (seeds 555-557): of 15 quadrotors of 3-blade rotors
    seen as two or three detections, 14 paired so (17 pairs, and one pair of a 2-blade quadrotor's images that flash
    at once only in part): cross-correlation 5.9-33 sigmas, each power's repeat at ``2 tau`` 5.5-21 sigmas, at
    ``tau`` -0.23 to 0.49 of it; the fifteenth's pair stood 3.9 sigmas. A drone's hub beside one of its images, and
    images flashing at once, repeated at ``tau`` 0.55-3.5 times ``2 tau`` in one power or both. Two quadrotors
    within reach, their rotors within 3 % of one rate (2 % apart in each), paired in 1-4 of 40 draws, at one rate
    in 2-5 (synthetic trains, ``tests/test_images.py``); neither shows a body line where this is asked
    (:func:`flash_image_owners`), as a drone's hub may. Offsets of 2 chirps or more are read (at 1 the repeat at
    ``tau`` takes in lag 0)."""
    a, b = np.asarray(power_a, dtype=np.float64), np.asarray(power_b, dtype=np.float64)
    if a.shape != b.shape or a.ndim != 1 or not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        return False
    longest = min(int(longest_chirps), len(a) // 6)  # (each power is read at twice the offset)
    correlation = standardized_correlations(np.stack([a, b], axis=1), last=2 * longest + 2) if longest >= 2 else None
    if correlation is None:
        return False
    ahead, behind = correlation(0, 1)[1:longest + 1], correlation(1, 0)[1:longest + 1]  # lags 1.. and -1..
    across = np.concatenate([ahead, behind])
    sigma = robust_sigma(across)
    offset = int(np.argmax(across) % longest) + 1
    if not (sigma > 0 and across.max() >= TURN_SIGMAS * sigma):
        return False
    for own in (correlation(0, 0), correlation(1, 1)):
        own_sigma = robust_sigma(own[1:2 * longest + 2])
        twice = correlation_near(own, 2 * offset)
        if not (own_sigma > 0 and twice >= TURN_SIGMAS * own_sigma
                and correlation_near(own, offset) < TURN_SHARE * twice):
            return False
    return True


def flash_image_owners(rows, powers, owners, *, reach_m, longest_chirps=0):
    """``owners`` (:func:`image_owners`) with the images its combs missed, told by their flashes (a
    :class:`FlashImages`): targets that neither are nor own a comb image, within ``reach_m`` of one another, whose
    ``powers`` (per chirp) all flash together (:func:`flashes_coincide`, every pair of them) or by turns
    (:func:`flashes_by_turns`, offsets up to ``longest_chirps``; 0: not read; both without a body line, as images
    are: two drones' hubs flashing at one rate half a period apart are no pair of sides) are one drone's images, one
    for each side's blades.

    A long ramp moves a blade's flash far in range (an up-chirp's beat moves the approaching blades one way and the
    receding the other, by their Doppler times the sampled ramp), and at a low PRF the images show no comb of their
    own to match: their tips fold many times. Two blades opposite flash at once, on both sides: at PRFs of 1.5-6 kHz
    the two images of 2-blade rotors correlated 0.51-0.96, chirp for chirp, while the drone's own range bin, its body
    line steady, did not (0.06-0.13). Images that straddle a target read as a drone whose body line was found, its
    range within ``IMAGE_SYMMETRY`` of their half-span from their midpoint and within ``reach_m`` of each, are its
    own, however strong it is against them; else the strongest image owns the others (and, without a body line, is
    analysed at their hub by :func:`mdpipe.process.pipeline.without_images`). A target read otherwise keeps none: the
    images may be all that shows the drone. Odd blade counts flash one side at a time: their images do not flash
    together but by turns (on the low-PRF sweeps, seeds 555-557, 15 of the 37 captures holding more than one detection
    were such a drone, its second image read as a second drone). Bursts of another radar crossing ours light every bin
    at once, and all targets flash together; a clipped echo's images (:mod:`mdpipe.process.saturation`) swing with its
    power: the caller does not ask then (on `make bench-impairments`, a clipped capture's image was grouped so and
    left a drone). A target whose echo holds mains hum (``mains_hum_hz``) swings with the supply, not with blades: it
    is no member."""
    owners = list(owners)
    owning = {owner for owner in owners if owner is not None}
    pool = [i for i, owner in enumerate(owners) if owner is None and i not in owning
            and rows[i].get("range_m") is not None and rows[i].get("mains_hum_hz") is None]

    def together(i, j):
        """How targets ``i`` and ``j`` flash as one drone's images: ``AT_ONCE``, ``BY_TURNS`` or None."""
        if abs(rows[i]["range_m"] - rows[j]["range_m"]) > reach_m:
            return None
        if flashes_coincide(powers[i], powers[j]):
            return AT_ONCE
        if (longest_chirps and seen_from_a_side(rows[i]) and seen_from_a_side(rows[j])
                and flashes_by_turns(powers[i], powers[j], longest_chirps=longest_chirps)):
            return BY_TURNS
        return None

    clusters, grouped, turns = [], set(), set()
    for n, i in enumerate(pool):  # strongest first, each joined by every weaker one flashing with all its members
        if i in grouped:
            continue
        members, paired = [i], set()
        for j in pool[n + 1:]:
            if j in grouped:
                continue
            ways = [together(k, j) for k in members]
            if all(ways):
                paired.update((k, j) for k, way in zip(members, ways) if way == BY_TURNS)
                members.append(j)
        if len(members) > 1:
            clusters.append(members)
            grouped.update(members)
            turns.update(k for pair in paired for k in pair)
    hubs = set()  # (a drone is one cluster's hub at most)
    for members in clusters:
        hub = straddled(rows, members, reach_m=reach_m, among=[k for k, row in enumerate(rows) if owners[k] is None
                                                               and k not in grouped and k not in hubs
                                                               and row.get("class") == "drone"])
        hubs.add(hub)
        owner = members[0] if hub is None else hub
        for i in members:
            if i != owner:
                owners[i] = owner
    return FlashImages(owners, frozenset(i for i in turns if owners[i] is not None))


def straddled(rows, members, *, reach_m, among):
    """The first of the rows ``among`` (indices) that shows a body line and lies between the ranges of ``members`` (one
    drone's images), within ``IMAGE_SYMMETRY`` of their half-span from their midpoint and within ``reach_m`` of each:
    the drone's hub, detected as a target of its own; else None."""
    ranges = [rows[i]["range_m"] for i in members]
    middle, half_span = (min(ranges) + max(ranges)) / 2, (max(ranges) - min(ranges)) / 2
    return next((k for k in among if rows[k].get("body_velocity_mps") is not None and rows[k].get("range_m") is not None
                 and abs(rows[k]["range_m"] - middle) <= IMAGE_SYMMETRY * half_span
                 and all(abs(rows[k]["range_m"] - r) <= reach_m for r in ranges)), None)


def hubs_between(rows, owners, *, reach_m):
    """``owners`` (:func:`flash_image_owners`' or :func:`image_owners`') with the images of a drone seen only from its
    sides (its owner without a body line, :func:`seen_from_a_side`) given to the target detected between them at its
    hub (:func:`straddled`: a body line) where that reads a drone; and, where it reads otherwise (its own range bin
    holding too little of the blades to show them: a body line alone), that target for each such owner: the drone
    analysed at the images' hub stands in its place (:func:`mdpipe.process.pipeline.without_images`). Returns
    ``(owners, hubs)``, ``hubs`` a dict owner -> target.

    Two W-band drones of the low-PRF sweep (a quadrotor at seed 555, a hexarotor at 556) were read twice so: their
    comb images, analysed at their hub, and their body 0.1-0.7 m from it (the quadrotor's read `none`, its bin holding
    0.8 % of the blades' power)."""
    owners, hubs = list(owners), {}
    owning = {owner for owner in owners if owner is not None}
    free = [k for k, owner in enumerate(owners) if owner is None and k not in owning]
    for owner in sorted(owning):  # (strongest first: a target is one drone's hub at most)
        if not seen_from_a_side(rows[owner]):
            continue
        members = [owner] + [i for i, o in enumerate(owners) if o == owner]
        hub = straddled(rows, members, reach_m=reach_m, among=free)
        if hub is None:
            continue
        free.remove(hub)
        if rows[hub].get("class") == "drone":
            for i in members:
                owners[i] = hub
        else:
            hubs[owner] = hub
    return owners, hubs


def _told(image, by_flashes):
    """How ``image`` was told for another detection's image (``by_flashes``: ``AT_ONCE``, ``BY_TURNS``, or None: by its
    comb)."""
    return {AT_ONCE: "its blade flashes coinciding chirp for chirp with another detection's",
            BY_TURNS: "its blade flashes coming by turns with another detection's, half a flash period apart (the "
                      "approaching and the receding blades of an odd blade count)",
            None: f"its line comb at {image.get('chopping_freq_hz') or 0:.4g} Hz"}[by_flashes]


def image_note(image, *, reach_m, by_flashes=None):
    """The clause for the kept row: where its image lay and why it is no target of its own (``by_flashes``: told by
    its flashes, ``AT_ONCE`` or ``BY_TURNS`` with another's, :func:`flash_image_owners`; None: by its comb)."""
    return (f"a second detection at {image['range_m']:.2f} m, {_told(image, by_flashes)}, is this drone's "
            f"range-Doppler image (blade flashes land up to {reach_m:.3g} m off a drone at this radar's ramp), not a "
            "target: the drone's hub lies at this range or between them")


def seen_from_a_side(row):
    """Whether a drone's ``row`` shows no body line: the body echoes from the hub, so a detection without it,
    paired with an image (:func:`image_owners`), is itself one side's blade flashes."""
    return row.get("body_velocity_mps") is None


def hub_note(first, second, *, reach_m, by_flashes=None):
    """The clause for a drone analysed at its hub between its two images, rows ``first`` and ``second`` (told as
    :func:`image_note` says)."""
    return (f"analysed at its hub, midway between two detections of its blade flashes at {first['range_m']:.2f} and "
            f"{second['range_m']:.2f} m (the second, {_told(second, by_flashes)}), its range-Doppler images (an "
            "up-chirp's beat moves the approaching blades' flashes one way and the receding blades' the other, up to "
            f"{reach_m:.3g} m at this radar's ramp): each image holds one side's flashes, repeating once per chopping "
            "period whatever the blade count")
