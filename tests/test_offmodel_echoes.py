"""Echoes of a simulator written apart from mdpipe's (benchmarks/offmodel: blades as strips of points lambda / 8
apart, every IF sample of every chirp): a few of its scenes, end to end, against their own truth."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from bench_offmodel import run_scene  # noqa: E402


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
