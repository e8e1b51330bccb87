"""Range-Doppler images: a drone's blade flashes detected off its range are no second target."""

import functools

import numpy as np
import pytest

from mdpipe.params import RadarParams
from mdpipe.process.images import (BY_TURNS, flash_image_owners, flashes_by_turns, flashes_coincide, hubs_between,
                                   image_note, image_owners, image_reach_m)


def test_the_reach_of_a_tip_at_the_speed_of_sound_is_its_doppler_times_the_sampled_ramp_in_bins():
    """77 GHz, 64 samples at 855.5 kHz (T_s = 74.8 us) over 250 MHz of the sampled sweep: bins of 0.6 m; a tip at
    343 m/s flashes at 2 v / lambda = 176 kHz, 13.2 bins: 7.9 m."""
    params = RadarParams(f_start_hz=76.5e9, f_stop_hz=76.75e9, ramp_up_s=74.81e-6, chirp_period_s=93.5e-6,
                         sample_rate_hz=855504.0, n_samples=64, n_channels=1)
    doppler_hz = 2 * 343.0 / params.wavelength_m
    assert doppler_hz == pytest.approx(176.0e3, rel=0.01)
    assert image_reach_m(params) == pytest.approx(doppler_hz * 64 / 855504.0 * params.range_bin_m, rel=1e-12)
    assert image_reach_m(params) == pytest.approx(7.9, rel=0.01)


def row(range_m, chopping_hz):
    return {"range_m": range_m, "chopping_freq_hz": chopping_hz}


def test_a_weaker_comb_within_reach_and_two_per_cent_is_the_strongers_image():
    rows = [row(14.39, 150.34), row(12.59, 150.85)]
    assert image_owners(rows, reach_m=5.0) == [None, 0]


@pytest.mark.parametrize("rows, reach_m", [
    ([row(14.39, 150.34), row(12.59, 154.0)], 5.0),   # combs 2.4 % apart: two drones
    ([row(14.39, 150.34), row(8.0, 150.34)], 5.0),    # beyond a tip's reach
    ([row(14.39, 150.34), row(12.59, None)], 5.0),    # no comb in the weaker: a bird, a point
    ([row(14.39, None), row(12.59, 150.34)], 5.0),    # no comb in the stronger
])
def test_targets_that_differ_in_comb_or_lie_beyond_reach_stay_targets(rows, reach_m):
    assert image_owners(rows, reach_m=reach_m) == [None, None]


def test_an_image_owns_no_image_of_its_own():
    """Three detections in a row, each within reach of the next: the second is the first's image, and the third,
    within reach of the second only, stays a target."""
    rows = [row(10.0, 150.0), row(13.0, 150.5), row(16.0, 150.2)]
    assert image_owners(rows, reach_m=4.0) == [None, 0, None]


def flashing(rng, n=2048, share=0.1):
    """A power per chirp: flashes (a tenth of the chirps, 30 times the floor) over an exponential floor."""
    return rng.exponential(1.0, n) + 30.0 * (rng.random(n) < share)


def target(range_m, cls="drone", body=None, chopping_hz=None):
    return {"range_m": range_m, "class": cls, "body_velocity_mps": body, "chopping_freq_hz": chopping_hz}


def two_images(rng, n=2048):
    """Two powers carrying the same flashes chirp for chirp, each over its own floor."""
    flashes = 30.0 * (rng.random(n) < 0.1)
    return [flashes + rng.exponential(1.0, n), flashes + rng.exponential(1.0, n)]


@pytest.mark.parametrize("drone_first", [True, False])
def test_two_images_flashing_together_either_side_of_a_drone_are_its_own(drone_first):
    """A hovering drone at 10.8 m (its body line found) and two detections at 7.2 and 15.6 m whose powers carry the
    same flashes chirp for chirp: the approaching and the receding blades' images, the drone 0.6 m from their
    midpoint (0.14 of their half-span). The drone owns them whether it is stronger or weaker than they are."""
    rng = np.random.default_rng(1)
    drone, images = (target(10.79, body=-0.08), rng.exponential(50.0, 2048)), two_images(rng)
    rows = [target(7.20, "bird"), target(15.59, "bird")]
    powers = list(images)
    if drone_first:
        rows, powers = [drone[0]] + rows, [drone[1]] + powers
        assert flash_image_owners(rows, powers, [None] * 3, reach_m=23.0).owners == [None, 0, 0]
    else:
        rows, powers = rows + [drone[0]], powers + [drone[1]]
        assert flash_image_owners(rows, powers, [None] * 3, reach_m=23.0).owners == [2, 2, None]


@pytest.mark.parametrize("between", [target(10.79, body=None), target(10.79, "none", body=-0.08),
                                     target(13.0, body=-0.08)])
def test_images_flashing_together_with_no_drone_between_them_are_the_strongests(between):
    """No body line found between them, none read a drone (the images may be all that shows it), or off their
    midpoint by more than a quarter of their half-span: the stronger image owns the weaker, and the pipeline analyses
    the drone at their hub."""
    rng = np.random.default_rng(2)
    powers = [rng.exponential(50.0, 2048)] + two_images(rng)
    rows = [between, target(7.20), target(15.59)]
    assert flash_image_owners(rows, powers, [None] * 3, reach_m=23.0).owners == [None, None, 1]


@pytest.mark.parametrize("case", ["independent", "beyond_reach", "other_length", "not_finite", "mains_hum"])
def test_targets_whose_flashes_do_not_coincide_or_lie_beyond_reach_stay_targets(case):
    """Independent echoes correlate near 0; coinciding flashes beyond a tip's reach are another drone's; powers of
    other lengths, or not finite, are compared with none; an echo holding mains hum swings with the supply."""
    rng = np.random.default_rng(3)
    rows = [target(10.8, body=0.1), target(7.2), target(40.0 if case == "beyond_reach" else 15.6)]
    powers = [flashing(rng)] + ([flashing(rng), flashing(rng)] if case == "independent" else two_images(rng))
    if case == "other_length":
        powers[2] = powers[2][:-1]
    if case == "not_finite":
        powers[2][5] = np.nan
    if case == "mains_hum":
        rows[2]["mains_hum_hz"] = 50.0
    assert flash_image_owners(rows, powers, [None] * 3, reach_m=23.0).owners == [None, None, None]


def test_a_target_owning_a_comb_image_is_no_flash_image():
    """Row 1 owns row 2 by their combs; rows 0 and 1 flash together, but row 1 stays (its comb image's note lives on
    its row), and a comb image is grouped with nothing."""
    rng = np.random.default_rng(4)
    images = two_images(rng)
    powers = [images[0], images[1], images[1] + rng.exponential(1.0, 2048)]
    rows = [target(10.8), target(12.0, chopping_hz=150.0), target(13.0, chopping_hz=150.5)]
    assert flash_image_owners(rows, powers, [None, None, 1], reach_m=10.0).owners == [None, None, 1]


def test_every_member_of_a_group_flashes_with_every_other():
    """Three detections: the first and third flash with the second but not with each other (a chain): the second
    joins the first, the third stays a target."""
    rng = np.random.default_rng(6)
    a, b = (30.0 * (rng.random(4096) < 0.1) for _ in range(2))
    powers = [a + rng.exponential(1.0, 4096), a + b + rng.exponential(1.0, 4096), b + rng.exponential(1.0, 4096)]
    assert flashes_coincide(powers[0], powers[1]) and flashes_coincide(powers[1], powers[2])
    assert not flashes_coincide(powers[0], powers[2])
    rows = [target(10.0), target(12.0), target(14.0)]
    assert flash_image_owners(rows, powers, [None] * 3, reach_m=10.0).owners == [None, 0, None]


@pytest.mark.parametrize("scale, coincide", [(1.0, True), (0.0, False)])
def test_flashes_coincide_chirp_for_chirp(scale, coincide):
    rng = np.random.default_rng(5)
    flashes = 30.0 * (rng.random(4096) < 0.05)
    a = flashes + rng.exponential(1.0, 4096)
    b = scale * flashes + rng.exponential(1.0, 4096)
    assert flashes_coincide(a, b) is coincide
    assert not flashes_coincide(a, np.ones(4096))  # a power without flashes (no spread) coincides with none


@pytest.mark.parametrize("crossed, clipped, kept", [(False, False, 1), (True, False, 3), (False, True, 3)])
def test_no_images_are_told_by_flashes_where_bursts_cross_every_bin_or_samples_clip(crossed, clipped, kept):
    """Another radar's chirps crossing ours light every range bin at once, and a clipped echo's images swing with its
    power: all targets then flash together, and none is taken for another's image by its flashes (the pipeline's
    ``without_images``, given ``crossed`` or ``clipped``)."""
    from mdpipe.process.pipeline import without_images
    params = RadarParams(f_start_hz=94.0e9, f_stop_hz=94.25e9, ramp_up_s=180.1e-6, chirp_period_s=225.1e-6,
                         sample_rate_hz=355366.0, n_samples=64, n_channels=1)
    rng = np.random.default_rng(7)
    powers = [rng.exponential(50.0, 2048)] + two_images(rng)
    rows = [dict(target(r, c, body=v), notes="", target=i)
            for i, (r, c, v) in enumerate([(10.79, "drone", -0.08), (7.20, "bird", None), (15.59, "bird", None)])]
    targets = [(None, np.sqrt(p).astype(complex), 0.0, None) for p in powers]
    detections, _, rows, _ = without_images([0, 1, 2], targets, rows, [0, 1, 2], params, crossed=crossed,
                                            clipped=clipped)
    assert detections == [0, 1, 2][:kept] and len(rows) == kept
    assert rows[0]["notes"].count("coinciding chirp for chirp") == 3 - kept


def rotor_flashes(rng, periods, phases, *, half=0.0, n=2048, width=0.25, flash=30.0):
    """A power per chirp: the flashes of rotors each ``periods`` chirps apart (fractional: caught stroboscopically),
    from ``phases`` and ``half`` a period on (0.5: the other side of an odd blade count), each a Gaussian ``width``
    chirps wide (shorter than a chirp), over an exponential floor."""
    t = np.arange(n, dtype=np.float64)[:, None]
    power = rng.exponential(1.0, n)
    for period, phase in zip(periods, phases):
        times = phase + half * period + period * np.arange(int(n / period) + 2)
        power += flash * np.exp(-0.5 * ((t - times[None, :]) / width) ** 2).sum(axis=1)
    return power


def quadrotor(rng, period_chirps, spread=0.02):
    """Four rotors' flash periods within ``spread`` of ``period_chirps``, and their phases."""
    periods = period_chirps * (1 + rng.uniform(-spread, spread, 4))
    return periods, rng.uniform(0, period_chirps, 4)


def test_an_odd_blade_counts_two_images_flash_by_turns_and_are_one_drones():
    """Four 3-blade rotors 1 % apart, flashing every 12.1-12.3 chirps: the approaching blades' image and the receding
    blades' half a chopping period later. They do not flash at once; by turns they do, and the weaker is the
    stronger's image, noted so (none where offsets are not read)."""
    rng = np.random.default_rng(8)
    periods, phases = quadrotor(rng, 12.2, spread=0.01)
    approaching, receding = (rotor_flashes(rng, periods, phases, half=h) for h in (0.0, 0.5))
    assert flashes_by_turns(approaching, receding, longest_chirps=100)
    assert not flashes_coincide(approaching, receding)
    rows = [target(7.2), target(15.6)]
    told = flash_image_owners(rows, [approaching, receding], [None, None], reach_m=23.0, longest_chirps=100)
    assert told.owners == [None, 0] and told.by_turns == {1}
    assert flash_image_owners(rows, [approaching, receding], [None, None], reach_m=23.0).owners == [None, None]
    assert "by turns with another detection's, half a flash period apart" in image_note(
        {"range_m": 15.6}, reach_m=23.0, by_flashes=BY_TURNS)


def test_images_flashing_at_once_are_told_at_once_not_by_turns():
    """An even count's two images (opposite blades on both sides at once) repeat at any offset found between them
    themselves: no pair of sides by turns, but one drone's images by :func:`flashes_coincide`."""
    rng = np.random.default_rng(9)
    periods, phases = quadrotor(rng, 12.2)
    first, second = rotor_flashes(rng, periods, phases), rotor_flashes(rng, periods, phases)
    assert not flashes_by_turns(first, second, longest_chirps=100) and flashes_coincide(first, second)
    told = flash_image_owners([target(7.2), target(15.6)], [first, second], [None, None], reach_m=23.0,
                              longest_chirps=100)
    assert told.owners == [None, 0] and told.by_turns == frozenset()


@pytest.mark.parametrize("case", ["noise", "short_offsets", "body_line", "beyond_reach"])
def test_powers_that_are_no_pair_of_sides_are_not_told_by_turns(case):
    """Noise has no offset; offsets under two chirps are not read; a detection showing a body line is a hub, not an
    image, although its flashes come by turns with another's; beyond a tip's reach, another drone."""
    rng = np.random.default_rng(9)
    periods, phases = quadrotor(rng, 12.2)
    first, second = rotor_flashes(rng, periods, phases), rotor_flashes(rng, periods, phases, half=0.5)
    if case == "noise":
        first, second = rng.exponential(1.0, 2048), rng.exponential(1.0, 2048)
    longest = 1 if case == "short_offsets" else 100
    assert flashes_by_turns(first, second, longest_chirps=longest) is (case in ("body_line", "beyond_reach"))
    rows = [target(7.2), target(40.0 if case == "beyond_reach" else 15.6, body=0.2 if case == "body_line" else None)]
    assert flash_image_owners(rows, [first, second], [None, None], reach_m=23.0,
                              longest_chirps=longest).owners == [None, None]


def test_two_drones_flashing_near_one_rate_are_seldom_taken_for_sides():
    """Two quadrotors of 3-blade rotors within reach, each from its own phases, the second's rotors within 3 % of the
    first's mean period, or at the first's very periods: their trains may line up half a period apart by chance. Of
    40 draws (periods 5-30 chirps, rotors 2 % apart) the two sides of one drone pair in 36-39, two drones 3 % apart
    in 1-4, two at one rate in 2-5, two at unrelated rates in 0-1 (six seeds measured; seed 0 here)."""
    rng = np.random.default_rng(0)
    sides = apart = one_rate = unrelated = 0
    for _ in range(40):
        periods, phases = quadrotor(rng, rng.uniform(5.0, 30.0))
        first = rotor_flashes(rng, periods, phases)
        sides += flashes_by_turns(first, rotor_flashes(rng, periods, phases, half=0.5), longest_chirps=100)
        other = periods.mean() * (1 + rng.uniform(-0.03, 0.03, 4))
        apart += flashes_by_turns(first, rotor_flashes(rng, other, rng.uniform(0, periods.mean(), 4)),
                                  longest_chirps=100)
        one_rate += flashes_by_turns(first, rotor_flashes(rng, periods, rng.uniform(0, periods.mean(), 4)),
                                     longest_chirps=100)
        unrelated += flashes_by_turns(first, rotor_flashes(rng, *quadrotor(rng, rng.uniform(5.0, 30.0))),
                                      longest_chirps=100)
    assert sides >= 36 and apart <= 4 and one_rate <= 5 and unrelated <= 1


def test_two_drones_whose_trains_only_drift_past_each_other_are_no_sides():
    """Two quadrotors whose rotors flash every 23.5-23.7 and 22.7-23.3 chirps (2 % apart): over the dwell each
    train drifts past the other, and at some offset each repeats at twice it and not at it, but their
    cross-correlation stands under four sigmas there: of 30 draws of their phases none pairs (3 without that test)."""
    paired = 0
    for seed in range(30):
        rng = np.random.default_rng(seed)
        first = rotor_flashes(rng, [23.66, 23.60, 23.51, 23.50], rng.uniform(0, 23.5, 4))
        second = rotor_flashes(rng, [23.20, 23.21, 23.33, 22.67], rng.uniform(0, 23.2, 4))
        paired += flashes_by_turns(first, second, longest_chirps=100)
    assert paired == 0


def comb_images_and(between):
    """Two comb images of one drone without a body line (4.8 and 12.0 m, the weaker owned by the stronger) and a
    third target ``between``."""
    rows = [target(4.80, chopping_hz=169.4), target(11.99, chopping_hz=168.8), between]
    return rows, image_owners(rows, reach_m=45.0)


@pytest.mark.parametrize("cls, owners, hubs", [("drone", [2, 2, None], {}), ("none", [None, 0, None], {0: 2})])
def test_a_body_detected_between_a_drones_images_is_its_hub(cls, owners, hubs):
    """A target with a body line at the images' midpoint is the drone: it owns them where it reads a drone, else it is
    the place the drone analysed at their hub stands in (its own bin held too little of the blades)."""
    rows, by_combs = comb_images_and(target(8.39, cls, body=-0.07))
    assert by_combs == [None, 0, None]
    assert hubs_between(rows, by_combs, reach_m=45.0) == (owners, hubs)


@pytest.mark.parametrize("between, images_body", [
    (target(10.5, "none", body=-0.07), None),   # off the midpoint by 0.59 of their half-span
    (target(8.39, "none", body=None), None),    # no body line: no hub
    (target(8.39, "none", body=-0.07), 0.2)])   # the stronger image shows a body line: not seen from a side
def test_no_hub_is_taken_off_the_images_midpoint_or_without_a_body_line(between, images_body):
    rows, by_combs = comb_images_and(between)
    rows[0]["body_velocity_mps"] = images_body
    assert hubs_between(rows, by_combs, reach_m=45.0) == (by_combs, {})


def pipeline_images(between, *, seed):
    """:func:`comb_images_and` ``between`` as the pipeline's rows (notes, target numbers) and targets (noise powers),
    and ``without_images`` for a 94 GHz radar whose ramp moves a tip at the speed of sound 46 m off."""
    from mdpipe.process.pipeline import without_images
    params = RadarParams(f_start_hz=94.0e9, f_stop_hz=94.25e9, ramp_up_s=354.3e-6, chirp_period_s=442.9e-6,
                         sample_rate_hz=361286.0, n_samples=128, n_channels=1)
    rng = np.random.default_rng(seed)
    rows, _ = comb_images_and(between)
    rows = [dict(row, notes="", target=i) for i, row in enumerate(rows)]
    targets = [(None, np.sqrt(rng.exponential(1.0, 2048)).astype(complex), 0.0, None) for _ in rows]
    return rows, targets, functools.partial(without_images, params=params)


def test_the_drone_analysed_at_its_images_hub_stands_in_for_the_target_detected_there():
    """``without_images``: the images' hub analysis reads a drone; it replaces the `none` row at the hub, the images
    go, and the row's note names them."""
    rows, targets, without_images = pipeline_images(target(8.39, "none", body=-0.07), seed=10)
    drone = dict(target(8.49, chopping_hz=170.3, body=-0.07), notes="class: blade line comb at 170.3 Hz")

    def hub(owner, image):
        assert (owner, image) == (0, 1)
        return "hub", targets[2], dict(drone), "analysis"

    detections, _, kept, analyses = without_images(["a", "b", "c"], targets, rows, [0, 1, 2], hub=hub)
    assert detections == ["hub"] and analyses == ["analysis"] and len(kept) == 1
    assert kept[0]["range_m"] == 8.49 and kept[0]["class"] == "drone" and kept[0]["target"] == 0
    assert "analysed at its hub, midway between two detections of its blade flashes at 4.80 and 11.99 m" in (
        kept[0]["notes"])


@pytest.mark.parametrize("cls", ["none", "drone"])
def test_a_target_is_one_drones_hub_at_most(cls):
    """Two drones' comb images (169 and 120 Hz) both straddle one body detected at 8.39 m: the stronger group takes
    it for its hub (owned by it where it reads a drone, standing in for it where it does not), the other keeps its own
    owner (analysed at its images' hub)."""
    rows = [target(4.80, chopping_hz=169.4), target(5.50, chopping_hz=120.0), target(11.99, chopping_hz=168.8),
            target(11.30, chopping_hz=120.3), target(8.39, cls, body=-0.07)]
    by_combs = image_owners(rows, reach_m=45.0)
    assert by_combs == [None, None, 0, 1, None]
    if cls == "none":
        assert hubs_between(rows, by_combs, reach_m=45.0) == (by_combs, {0: 4})
    else:
        assert hubs_between(rows, by_combs, reach_m=45.0) == ([4, None, 4, 1, None], {})


def test_a_drone_between_two_pairs_of_images_owns_one_pair():
    """A drone with a body line at 10 m between two pairs of detections flashing together (7 and 13 m, 8 and 12 m):
    the stronger pair is its images, the other pair its own (another drone's sides)."""
    rng = np.random.default_rng(13)
    first, second = two_images(rng), two_images(rng)
    rows = [target(10.0, body=-0.05), target(7.0), target(13.0), target(8.0), target(12.0)]
    powers = [rng.exponential(50.0, 2048), first[0], first[1], second[0], second[1]]
    assert flash_image_owners(rows, powers, [None] * 5, reach_m=23.0).owners == [None, 0, 0, None, 3]


def test_comb_images_given_to_the_drone_between_them_are_noted_as_told_by_their_combs():
    """``without_images``: a drone with a body line at the midpoint of two comb images owns both, each noted by its
    comb (the stronger had owned the weaker by their combs), and nothing is analysed again."""
    rows, targets, without_images = pipeline_images(target(8.39, "drone", body=-0.07), seed=11)

    def hub(owner, image):
        raise AssertionError("a drone with a body line between its images is not analysed again")

    _, _, kept, _ = without_images(["a", "b", "c"], targets, rows, [0, 1, 2], hub=hub)
    assert len(kept) == 1 and kept[0]["range_m"] == 8.39
    assert kept[0]["notes"].count("its line comb at") == 2 and "coinciding" not in kept[0]["notes"]


@pytest.mark.parametrize("case", ["not_finite", "other_length", "constant", "short"])
def test_powers_that_cannot_be_compared_flash_by_turns_with_none(case):
    rng = np.random.default_rng(12)
    periods, phases = quadrotor(rng, 12.2)
    first, second = rotor_flashes(rng, periods, phases), rotor_flashes(rng, periods, phases, half=0.5)
    assert flashes_by_turns(first, second, longest_chirps=100)
    if case == "not_finite":
        second[7] = np.inf
    elif case == "other_length":
        second = second[:-1]
    elif case == "constant":
        second = np.ones_like(second)
    else:
        first, second = first[:11], second[:11]
    assert not flashes_by_turns(first, second, longest_chirps=100)
