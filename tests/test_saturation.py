"""ADC saturation: clipping's images of a target are read as such, not as more drones and birds."""

from pathlib import Path

import pytest

from hostile import overdriven
from mdpipe.params import ProcessParams
from mdpipe.process import saturation
from mdpipe.process.features import FEATURE_KEYS, STATUS_KEYS
from mdpipe.process.pipeline import process_capture

SAMPLES = Path(__file__).resolve().parent.parent / "data_samples"


def _row(range_m, snr_db, label):
    """A target row as the pipeline makes it: every feature measured (``ok``)."""
    return {**dict.fromkeys(FEATURE_KEYS, 1.0), **dict.fromkeys(STATUS_KEYS, "ok"), "range_m": range_m,
            "snr_db": snr_db, "class": label, "n_blades": 2, "n_blades_source": "given",
            "notes": f"class: what made it {label}"}


def test_image_ceiling_follows_the_clipped_share():
    # 20 log10(s) + 16 dB: 3 % of the samples clipped -> images up to 14.5 dB under the target; never above it
    assert saturation.image_ceiling_db(0.03) == pytest.approx(-14.46, abs=0.01)
    assert saturation.image_ceiling_db(1e-3) == pytest.approx(-44.0, abs=0.01)
    assert saturation.image_ceiling_db(0.5) == 0.0


def test_a_weak_detection_of_a_clipped_capture_is_an_image_a_strong_one_a_target():
    rows = [_row(30.0, 40.0, "drone"), _row(90.0, 21.0, "drone"), _row(50.0, 30.0, "bird")]
    out = saturation.saturated_rows(rows, [40.0, 21.0, 30.0], 0.03, ["a warning"])
    assert out[0] == rows[0] and out[2] == rows[2]  # the target, and one 10 dB under it (above the -14.5 dB ceiling)
    image = out[1]
    assert image["class"] == "none"
    assert {image[key] for key in STATUS_KEYS if key != "snr_db_status"} == {"clipping_image"}
    kept = STATUS_KEYS + ("n_blades", "n_blades_source", "snr_db", "mains_hum_hz")
    assert all(image[key] is None for key in FEATURE_KEYS if key not in kept)
    assert image["snr_db"] == 21.0 and image["snr_db_status"] == "ok"  # its own strength stays measured
    assert image["mains_hum_hz"] == 1.0  # and the hum found in it
    assert image["n_blades"] == 2 and image["n_blades_source"] == "given"  # what the user gave stays
    assert "image of the target at 30 m" in image["notes"] and "read as drone (what made it drone)" in image["notes"]
    assert image["notes"].endswith("; a warning")


def test_rows_of_a_capture_that_does_not_clip_are_left_as_they_are():
    rows = [_row(30.0, 40.0, "drone"), _row(90.0, 10.0, "bird")]
    assert saturation.saturated_rows(rows, [40.0, 10.0], 0.0) is rows
    assert saturation.saturated_rows(rows, [40.0, 10.0], None) is rows  # float samples: no full scale known


def test_overdriven_xband_drone_its_third_harmonic_image_read_none(tmp_path):
    """The bundled X-band Phantom (140 Hz chopping, 30 m) with 3 % of its samples clipped: the beat's third harmonic
    is a copy of the drone at 3 x 30 m, its blade comb intact; it read `drone` before images were recognised."""
    clean = process_capture(SAMPLES / "phantom4_xband.h5", ProcessParams(n_blades=2)).rows
    assert [row["class"] for row in clean] == ["drone"]
    rows = process_capture(overdriven(SAMPLES / "phantom4_xband.h5", tmp_path / "over.h5", 0.03),
                           ProcessParams(n_blades=2)).rows
    assert rows[0]["clipped_share"] == pytest.approx(0.03, rel=0.05)
    drone, image = rows[0], next(row for row in rows if abs(row["range_m"] - 3 * clean[0]["range_m"]) < 1.0)
    assert drone["class"] == "drone" and drone["chopping_freq_hz_status"] == "ok"
    assert drone["chopping_freq_hz"] == pytest.approx(clean[0]["chopping_freq_hz"], rel=0.03)
    assert image["class"] == "none" and image["chopping_freq_hz_status"] == "clipping_image"
    assert "its echo read as drone" in image["notes"]
    assert all(row["class"] == "none" for row in rows[1:])
