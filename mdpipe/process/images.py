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
"""

from mdpipe.physics.rotor import SPEED_OF_SOUND_MPS

IMAGE_CHOP_SHARE = 0.02  # two targets' combs this close (relative) may be one drone's


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


def image_note(image, *, reach_m):
    """The clause for the kept row: where its image lay and why it is no target of its own."""
    return (f"a second detection at {image['range_m']:.2f} m, its line comb at {image['chopping_freq_hz']:.4g} Hz, is "
            f"this drone's range-Doppler image (blade flashes land up to {reach_m:.3g} m off a drone at this radar's "
            "ramp), not a target: the drone's hub lies at this range or between the two")


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
