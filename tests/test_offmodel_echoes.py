"""Echoes of a simulator written apart from mdpipe's (benchmarks/offmodel: blades as strips of points lambda / 8
apart, every IF sample of every chirp): a few of its scenes, end to end, against their own truth."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from bench_offmodel import run_scene, score  # noqa: E402


@pytest.mark.parametrize("sid, what", [
    (112, "one 2-blade rotor, tips brighter than the root (0.4 + 1.6 x^2 along the span), X band"),
    (113, "four such rotors at rates 3 % apart"),
    (196, "four rotors of rough blades (correlated amplitude, +-0.4 rad phase) at one rate, 5 dB"),
    (117, "four rotors of uniform blades at rates 3 % apart"),
])
def test_blade_length_on_blades_of_other_reflectivity(tmp_path, sid, what):
    """The rate within 1 % and r within 2 %, `ok`. Tip-bright and rough blades read +7.0-7.2 % before the edge
    was read against a trend rising above the plateau's median."""
    _, description, truth, row, _ = run_scene(sid, tmp_path)
    assert row["class"] == "drone", description
    assert row["rotation_rate_hz_status"] == "ok" and row["rotation_rate_hz"] == pytest.approx(truth["rate"], rel=0.01)
    assert row["blade_length_m_status"] == "ok" and row["blade_length_m"] == pytest.approx(truth["r"], rel=0.02)


def test_wingbeat_of_a_bird_of_flapping_wing_points(tmp_path):
    """A bird approaching at 8 m/s at X band, wing tips flapping 40 deg at 6 Hz: a bird, its wingbeat within 0.5 %."""
    _, description, truth, row, _ = run_scene(2, tmp_path)
    assert row["class"] == "bird", description
    assert row["wingbeat_freq_hz_status"] == "ok"
    assert row["wingbeat_freq_hz"] == pytest.approx(truth["wb"], rel=0.005)


@pytest.mark.parametrize("sid", [43, 154, 210, pytest.param(53, marks=pytest.mark.slow)])  # (53: 7 s a run)
def test_wingbeat_read_off_the_body_line(tmp_path, sid):
    """Birds whose rows lit in half the frames are the body line's main lobe (0-2 wing rows): the wings cross the
    body's Doppler at both turns of the stroke, so those rows repeat at T / 2 (or, a slow beat in them, 2 T). Read
    on the rows lit in a quarter of the frames (26-51 wing rows), which keep the stroke's sign: within 1 %. They
    read 2.0, 2.0, 2.0 and 0.5 times the wingbeat, `ok`, before."""
    _, description, truth, row, _ = run_scene(sid, tmp_path)
    assert row["class"] == "bird", description
    assert row["wingbeat_freq_hz_status"] == "ok"
    assert row["wingbeat_freq_hz"] == pytest.approx(truth["wb"], rel=0.01)


@pytest.mark.parametrize("sid", [222, 255])
def test_a_wingbeat_comb_is_no_rotor_comb(tmp_path, sid):
    """X-band birds beating 9.2 and 8.7 Hz: their echo holds lines at every multiple of the wingbeat, and a comb at
    its 3rd or 11th multiple has nothing between its lines in the coarse 0.25 s spectra, where lines 9 Hz apart
    blur. The whole dwell resolves the wingbeat's lines: no rotor comb, a bird (a drone with a chopping frequency at
    3 and 11 times the wingbeat, `ok`, before)."""
    _, description, truth, row, _ = run_scene(sid, tmp_path)
    assert row["class"] == "bird", description
    assert row["chopping_freq_hz"] is None


def test_a_comb_read_half_a_chopping_frequency_off_its_hub(tmp_path):
    """Six 2-blade rotors at 51.6-52.2 rev/s (one blade 1.22 times the other), no body line: the echo was
    demodulated half a chopping frequency off the hubs' Doppler, where the chopping lines fall at odd multiples of
    the turn rate and the comb reads at half the chopping frequency (the rate 50 % low, r 111 % long, `ok`, before).
    Its odd orders standing out over the even ones make it the comb at twice its spacing: the rate within 0.5 %."""
    _, description, truth, row, _ = run_scene(124, tmp_path)
    assert row["rotation_rate_hz_status"] == "ok", description
    assert row["rotation_rate_hz"] == pytest.approx(truth["rate"], rel=0.005)


@pytest.mark.parametrize("sid", [63, 258])
def test_a_bird_whose_wings_shine_as_its_body(tmp_path, sid):
    """Birds at 94 and 77 GHz flying 9.5 and 8.8 m/s, wing tips 0.97 and 0.84 times as bright as the body: their body
    lines stand 5.9 and 5.1 dB over the wings' turns in the median frame, under the 6 dB asked, and the echoes
    read `none`. The body line keeps to its track in 99-100 % of the frames and moves as the range track does:
    a bird, its body velocity within 0.1 m/s and its wingbeat within 0.5 %."""
    _, description, truth, row, _ = run_scene(sid, tmp_path)
    assert row["class"] == "bird", description
    assert row["body_velocity_mps_status"] == "ok"
    assert row["body_velocity_mps"] == pytest.approx(truth["body_v"], abs=0.1)
    assert row["wingbeat_freq_hz_status"] == "ok"
    assert row["wingbeat_freq_hz"] == pytest.approx(truth["wb"], rel=0.005)


def test_a_comb_of_a_wingbeat_s_harmonics_is_no_rotor(tmp_path):
    """An X-band bird beating 11.3 Hz, its body line found by its track: demodulated, its wing lines at every
    multiple of the wingbeat read as a comb at 33.9 Hz, 11.3 rev/s `ok` for a drone. The lines between that comb's
    stand as strong: the harmonics of a repeat slower than any rotor chops. A bird, its wingbeat within 0.5 %."""
    _, description, truth, row, _ = run_scene(327, tmp_path)
    assert row["class"] == "bird", description
    assert row["chopping_freq_hz"] is None and row["rotation_rate_hz"] is None
    assert row["wingbeat_freq_hz"] == pytest.approx(truth["wb"], rel=0.005)


def test_a_comb_at_three_times_the_chopping_read_at_its_fundamental(tmp_path):
    """Two K-band rotors of 2 blades at 41.9 and 42.6 rev/s, 5 dB: the lines of their chopping comb (84.6 Hz) at
    orders 1-6 stand weak, and the comb read at 254 Hz, 3 times it (the rate 3x, `ok`). The lines between that
    comb's stand as strong, and the echo's power repeats whole at 85 Hz: the comb is read at its fundamental, the
    rate within 0.5 %."""
    _, description, truth, row, _ = run_scene(194, tmp_path)
    assert row["rotation_rate_hz_status"] == "ok", description
    assert row["rotation_rate_hz"] == pytest.approx(truth["rate"], rel=0.005)


@pytest.mark.slow  # (its scene takes 11 s to make)
def test_a_period_made_whole_by_the_chirps_is_withheld(tmp_path):
    """Six 3-blade rotors at one rate at 77 GHz, -5 dB, their tips reaching 92 % of the span: the echo, decorrelating
    within a chirp, repeats only at lags near a whole number of chirps, and its period, 34.8 chirps,
    showed at 4 times it (139.0): a quarter of the rate, `ok`. The period of such a band is withheld."""
    _, description, truth, row, _ = run_scene(31, tmp_path)
    assert row["chopping_freq_hz"] is None and row["rotation_rate_hz"] is None, description
    assert row["rotation_rate_hz_status"] == "ambiguous_period"


def test_a_bird_whose_power_repeats_in_part_is_no_drone(tmp_path):
    """An X-band bird flying 8.2 m/s, beating 12.1 Hz, 0 dB: its power, wing and body lines beating, repeated in
    part every 3.7 ms, taken for blade flashes whose period is ambiguous (a drone, before), then refused as
    `not_rotor` by its rows' reach (within 3.2 m/s of the body line, where blade tips would light them out to tens
    of m/s). That partial repeat does not stand over the lags about its own (the wings' beat correlates the power
    over many lags): no flashes now. A bird, within 0.5 %."""
    _, description, truth, row, _ = run_scene(378, tmp_path)
    assert row["class"] == "bird", description
    assert row["rotation_rate_hz_status"] == "no_flashes"
    assert row["wingbeat_freq_hz_status"] == "ok"
    assert row["wingbeat_freq_hz"] == pytest.approx(truth["wb"], rel=0.005)


@pytest.mark.parametrize("sid, what", [
    (110, "two 3-blade rotors at one rate, 77 GHz: the echo beats at 9.5 Hz within a 7.9 m/s band"),
    (362, "one 2-blade rotor of rough, unequal blades at 20 deg, 77 GHz: it beats at 19.4 Hz within 2.3 m/s"),
])
def test_a_drone_that_beats_like_wings_stays_a_drone(tmp_path, sid, what):
    """Drones whose power repeats in part and whose echo also beats like wings within a wing-like band: their faint
    rows are not seen to end within wings' reach (blades light them beyond it), so the flashes stand: a drone."""
    _, description, truth, row, _ = run_scene(sid, tmp_path)
    assert row["class"] == "drone", description
    assert row["rotation_rate_hz_status"] == "ambiguous_period"
    assert row["wingbeat_freq_hz"] is None


def test_a_wingbeat_read_an_octave_apart_is_a_bird(tmp_path):
    """An X-band bird flying 14.4 m/s, beating 3.89 Hz: in 64 ms frames its wing pattern repeats at 7.78 Hz (wings
    crossing the body's Doppler at both turns), read again in 32 ms frames at 3.91 Hz. The looks disagree by an
    octave, and it read `none` (no wingbeat). A wingbeat is there either way: a bird, its wingbeat given as
    `ambiguous_period` at the second look's 3.91 Hz, within 1 % of the truth."""
    _, description, truth, row, _ = run_scene(132, tmp_path)
    assert row["class"] == "bird", description
    assert row["wingbeat_freq_hz_status"] == "ambiguous_period"
    assert row["wingbeat_freq_hz"] == pytest.approx(truth["wb"], rel=0.01)


def test_unequal_blades_folded_once_read_two_blades_from_every_second_line(tmp_path):
    """Four X-band rotors of 2 blades 0.5-2.5 % apart, one blade of each 1.5-1.9x the other, tips folded once
    (`make offmodel-blades`, `unequal_aliased` 3), N not given: flash times at twice a folded comb whose every second
    line stands out measure N = 2, the rate within 0.5 % (withheld as `ambiguous_period` before)."""
    from bench_blade_count import run_scene as blade_scene
    _, _, truth, row = blade_scene("unequal_aliased", 3, tmp_path)
    assert row["n_blades"] == 2 and row["n_blades_source"] == "measured"
    assert row["rotation_rate_hz_status"] == "ok"
    assert row["rotation_rate_hz"] == pytest.approx(truth["rate"], rel=0.005)



@pytest.mark.parametrize("kind, draw", [("even_phased", 2), ("even_phased", 5), ("odd_phased", 2)])
def test_rotors_phased_at_one_rate_centred_on_their_body_are_not_read_at_twice_their_comb(tmp_path, kind, draw):
    """Rotors of equal blades at exactly one rate, phased (`make offmodel-blades`: four 2-blade rotors 45 deg apart, two
    3-blade ones 60 deg apart), a body line at the hub's Doppler, N not given: their phases cancel some lines as far
    as their echoes are alike, and the comb at the chopping frequency shows its odd orders standing out. Read as a
    comb at twice it, demodulated half a spacing off, with weaker lines between (N measured), they gave 114.5, 113.1
    and 283.1 rev/s for 57.3, 56.5 and 94.4, `ok`. A comb centred on a body line is not half a spacing off: the
    chopping stands, the rate under the blade count assumed (`assumed_blades`) and, here, within 0.5 %."""
    from bench_blade_count import run_scene as blade_scene
    _, _, truth, row = blade_scene(kind, draw, tmp_path)
    assert row["class"] == "drone" and row["rotation_rate_hz_status"] == "assumed_blades"
    assert row["n_blades_source"] == "assumed"
    assert row["rotation_rate_hz"] == pytest.approx(truth["rate"], rel=0.005)



@pytest.mark.parametrize("given", [None, 3])
def test_rotors_phased_at_one_rate_leave_comb_and_power_agreeing_on_no_blade_count_the_pattern_read(tmp_path, given):
    """Two 3-blade rotors at exactly 89.7 rev/s, 60 deg apart, X band (`make offmodel-blades`, `odd_phased` 3): their
    comb lies at the chopping, 269 Hz, every second line standing out as one blade of two differing would make it,
    the power repeats whole at 538 Hz (an odd N flashes twice per chopping period) and the echo's period reads 287.5
    Hz. Comb and power agree only on the chopping the line pattern's count (2) made of the comb, 538 Hz: the period
    is not set aside for them, N given or not (3 times the rate, `ok`, without N; 538 Hz as `blade_conflict` with
    N = 3 given, the pattern's count in conflict with it)."""
    from bench_blade_count import run_scene as blade_scene
    from mdpipe.params import ProcessParams
    from mdpipe.process.pipeline import process_capture
    _, _, truth, row = blade_scene("odd_phased", 3, tmp_path)
    if given is not None:
        row = process_capture(str(tmp_path / "odd_phased_3.h5"),
                              ProcessParams(elevation_deg=truth["beta"], n_blades=given)).rows[0]
    assert row["class"] == "drone"
    assert row["chopping_freq_hz"] is None and row["chopping_freq_hz_status"] == "ambiguous_period"
    assert row["rotation_rate_hz"] is None and row["rotation_rate_hz_status"] == "ambiguous_period"


def test_the_benchmark_splits_the_rotation_coverage_by_band():
    """Three drones where the rotation is measurable (N given, loud, three turns, chopping under PRF / 2) at X and 77
    GHz, one not (N not given): per band, measurable / given ok / ok within 2 %."""
    truth = dict(kind="drone", prf=8000.0, snr=10.0, dwell=0.5, rates=[80.0], chop=160.0, rate=80.0, given_blades=True,
                 given_el=False, beta=10.0, tip_hz=3000.0, lam=0.03, body_v=0.0)
    row = {"class": "drone", **{f: None for f in ("chopping_freq_hz", "blade_length_m", "body_velocity_mps",
                                                  "wingbeat_freq_hz")},
           **{f"{f}_status": None for f in ("chopping_freq_hz", "blade_length_m", "body_velocity_mps",
                                             "wingbeat_freq_hz")}}
    results = [(0, "X 4x2bl", truth, {**row, "rotation_rate_hz": 80.4, "rotation_rate_hz_status": "ok"}, ["drone"]),
               (1, "77 4x2bl", truth, {**row, "rotation_rate_hz": 160.0, "rotation_rate_hz_status": "ok"}, ["drone"]),
               (2, "77 4x2bl", truth, {**row, "rotation_rate_hz": None, "rotation_rate_hz_status": "no_flashes"},
                ["drone"]),
               (3, "77 4x2bl", {**truth, "given_blades": False},
                {**row, "rotation_rate_hz": 80.0, "rotation_rate_hz_status": "assumed_blades"}, ["drone"])]
    _, coverage, by_band, bad = score(results)
    assert coverage["rotation_rate_hz"] == [3, 2, 1]
    assert by_band == {"X": [1, 1, 1], "77": [2, 1, 0]}  # the 77 GHz value given ok is 2x off: given, not right
    assert [(sid, what) for sid, what, *_ in bad] == [(1, "rotation_rate_hz")]
