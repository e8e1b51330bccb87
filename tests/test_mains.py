"""Mains hum (mdpipe/process/mains.py): lines at the grid's harmonics found, taken out, and not confused with a rotor's
comb on a target's Doppler; a rotor held still at a multiple of the grid's rate withheld with its reason."""

import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import simulate
from mdpipe.params import ProcessParams
from mdpipe.process import mains
from mdpipe.process.pipeline import process_capture
from mdpipe.simulate.scene import load_scene_mapping

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from bench_cw import record  # noqa: E402

FS = 20000.0
BOTH = (50.0, 60.0)


def noise(n, rng):
    return (rng.standard_normal(n) + 1j * rng.standard_normal(n)) / np.sqrt(2)


def hum(n, f0_hz, *, level_db, orders, rng, fs=FS, real=False):
    """Hum at ``f0_hz`` with lines at ``orders`` (amplitude falling as 1 / k), ``level_db`` over unit noise power:
    real (in I only, as a sound card's) or complex (its two sides unequal)."""
    t = np.arange(n) / fs
    x = np.zeros(n, dtype=complex)
    for k in orders:
        a = 10 ** (level_db / 20) / k
        x += a * np.cos(2 * np.pi * k * f0_hz * t + rng.uniform(0, 2 * np.pi)) if real else \
            a * np.exp(1j * (2 * np.pi * k * f0_hz * t + rng.uniform(0, 2 * np.pi))) * (1 + 0.5 * (-1) ** k)
    return x


def write_iq(path, samples, *, fc, fs):
    with h5py.File(path, "w") as h5:
        h5.attrs["fc"], h5.attrs["fs"] = fc, fs
        h5["IQ"] = samples.astype(np.complex64)
    return str(path)


@pytest.mark.parametrize("f0_hz, orders, real", [(50.03, range(1, 30), False), (59.97, range(2, 30, 2), True)])
@pytest.mark.parametrize("level_db", [0.0, 30.0])
def test_hum_is_found_at_the_grid_frequency_and_taken_out(f0_hz, orders, real, level_db):
    """Hum over unit noise for 4 s at 20 kHz: every harmonic of a grid 0.06 % off 50 Hz (complex), or a rectifier's
    even ones of 60 Hz in I only: its frequency within 0.002 Hz, taken out to no hum left and under 0.2 of the noise's
    power off the noise (the notches take a few per cent of it)."""
    rng = np.random.default_rng(3)
    n = int(4 * FS)
    w = noise(n, rng)
    x = w + hum(n, f0_hz, level_db=level_db, orders=orders, rng=rng, real=real)
    x = x - x.mean()
    found = mains.find_hum(x, prf_hz=FS, mains_hz=BOTH)
    assert found is not None and found.f0_hz == pytest.approx(f0_hz, abs=0.002)
    assert len(found.lines) >= mains.MIN_LINES
    cleaned = mains.without_hum(x, found, prf_hz=FS)
    assert mains.find_hum(cleaned, prf_hz=FS, mains_hz=BOTH) is None
    assert np.mean(np.abs(cleaned - (w - w.mean())) ** 2) < 0.2


def test_noise_a_target_off_the_grid_and_other_grids_have_no_hum():
    """White noise (100 draws), a sharp comb of lines every 100 Hz riding on a body 317 Hz off 0 Hz (a flying
    target's: its lines lie on no multiple of the grid's), and 50 Hz hum searched for 60 Hz only: no hum."""
    rng = np.random.default_rng(4)
    n = int(2 * FS)
    assert not any(mains.find_hum(noise(n, rng), prf_hz=FS, mains_hz=BOTH) for _ in range(100))
    t = np.arange(n) / FS
    comb = sum(np.exp(2j * np.pi * (317.0 + 100.0 * k) * t) for k in range(-10, 11))
    assert mains.find_hum(noise(n, rng) + 10 * comb, prf_hz=FS, mains_hz=BOTH) is None
    x = noise(n, rng) + hum(n, 50.0, level_db=30, orders=range(1, 10), rng=rng)
    assert mains.find_hum(x, prf_hz=FS, mains_hz=(60.0,)) is None
    assert mains.find_hum(x, prf_hz=FS, mains_hz=BOTH).f0_hz == pytest.approx(50.0, abs=0.002)


def test_hum_in_a_cw_recording_is_no_target(tmp_path):
    """60 Hz hum in I only, 30 dB over the noise of a 24 GHz recording of 4 s (a drone at 60 rev/s, chopping 120 Hz
    `ok`, before): nothing detected, the grid's frequency in `mains_hum_hz`."""
    rng = np.random.default_rng(5)
    n = int(4 * FS)
    path = write_iq(tmp_path / "hum.h5", noise(n, rng) + hum(n, 60.0, level_db=30, orders=range(1, 40), rng=rng,
                                                              real=True), fc=24e9, fs=FS)
    row = process_capture(path, ProcessParams()).rows[0]
    assert row["class"] == "none" and row["target"] is None
    assert row["mains_hum_hz"] == pytest.approx(60.0, abs=0.002)
    assert "mains hum at 60.00 Hz" in row["notes"]
    row = process_capture(path, ProcessParams(mains_hz="none")).rows[0]
    assert row["class"] == "drone" and row["mains_hum_hz"] is None  # what hum was read as


def test_a_rotor_recorded_with_hum_reads_as_without(tmp_path):
    """The other simulator's rotor at 83.7 rev/s, X band, recorded by a CW radar, and the same recording with 50 Hz
    hum (every harmonic, in I only) 20 dB over its noise: rate and blade length `ok` and as right as without it (0.5
    % and 2 %, as tests/test_cw.py holds them; 83.70 and 83.45 rev/s read), the hum reported."""
    path, _, truth = record(0, tmp_path, "filtered")
    params = ProcessParams(n_blades=truth["nbl"], elevation_deg=truth["beta"])
    clean = process_capture(str(path), params).rows[0]
    with h5py.File(path, "r") as h5:
        samples, fc, fs = h5["IQ"][...], float(h5.attrs["fc"]), float(h5.attrs["fs"])
    floor = np.median(np.abs(samples - samples.mean()) ** 2)  # the noise's order, under the echo's flashes
    rng = np.random.default_rng(6)
    samples = samples + np.sqrt(floor) * hum(len(samples), 50.0, level_db=20, orders=range(1, 40), rng=rng, fs=fs,
                                              real=True)
    row = process_capture(write_iq(tmp_path / "hum.h5", samples, fc=fc, fs=fs), params).rows[0]
    assert row["class"] == clean["class"] == "drone"
    assert row["mains_hum_hz"] == pytest.approx(50.0, abs=0.01) and clean["mains_hum_hz"] is None
    assert row["rotation_rate_hz_status"] == clean["rotation_rate_hz_status"] == "ok"
    for reading in (clean, row):
        assert reading["rotation_rate_hz"] == pytest.approx(truth["rate"], rel=0.005)
        assert reading["blade_length_m_status"] == "ok"
        assert reading["blade_length_m"] == pytest.approx(truth["r"], rel=0.02)


def test_supply_ripple_on_static_clutter_is_no_drone(tmp_path):
    """An FMCW capture of two static scatterers (76 GHz, 1.6 s) whose gain ripples 5 % at 50 Hz and its harmonics
    (a supply's): the ripple's Doppler lines about 0 Hz read as a drone (blade flashes, their period ambiguous)
    before; now none, the hum reported on each echo."""
    mapping = load_scene_mapping(ROOT / "configs" / "samples" / "clutter_only.yaml")
    mapping["radar"].update(n_chirps=16384, chirp_period_s=100e-6, n_samples=256, sample_rate_hz=5e6)
    path, _ = simulate(tmp_path, mapping)
    with h5py.File(path, "r+") as h5:
        t = np.arange(16384) * 100e-6
        gain = 1 + 0.05 * (np.cos(2 * np.pi * 100 * t) + 0.5 * np.cos(2 * np.pi * 200 * t + 1)
                           + 0.3 * np.cos(2 * np.pi * 300 * t + 2) + 0.5 * np.cos(2 * np.pi * 50 * t + 0.3))
        for name in [k for k in h5 if k.startswith("Chn")]:
            h5[name][...] = np.clip(np.rint(h5[name][...] * gain[:, None]), -32768, 32767).astype(np.int16)
    rows = process_capture(path, ProcessParams()).rows
    assert rows and all(r["class"] == "none" for r in rows)
    assert all(r["mains_hum_hz"] == pytest.approx(50.0, abs=0.01) for r in rows if r["target"] is not None)


@pytest.mark.parametrize("rate_hz, prf_hz, is_hum", [(100.0, 62500.0, False), (50.0, 62500.0, False),
                                                   (50.0, 4000.0, True)])
def test_a_rotor_held_still_at_a_multiple_of_the_grid(tmp_path, rate_hz, prf_hz, is_hum):
    """Paper Table I config 6 (X band, four 2-blade rotors held still, no body), 0.26-1 s: at 100 rev/s its lines
    every 200 Hz fall on every fourth harmonic of 50 Hz, which hum does not do; at 50 rev/s, every 100 Hz, as a
    rectifier's ripple, but they go on beyond hum's 40 orders (to its tips' 3.3 kHz): no hum, the rate within 0.5 %.
    Sampled at 4 kHz the span ends before the 40th order: taken for hum (a drone still, its rotation lost), and read
    within 0.5 % with `--mains-hz none`."""
    mapping = load_scene_mapping(ROOT / "configs" / "paper" / "table1_config6.yaml")
    mapping["radar"].update(n_chirps=int(min(16000, prf_hz)), chirp_period_s=1.0 / prf_hz)
    mapping["targets"][0]["rotors"]["rev_per_s"] = [rate_hz, -rate_hz, rate_hz, -rate_hz]
    path, truth = simulate(tmp_path, mapping)
    row = process_capture(path, ProcessParams()).rows[0]
    assert row["class"] == "drone"
    if not is_hum:
        assert row["mains_hum_hz"] is None
        assert row["rotation_rate_hz"] == pytest.approx(rate_hz, rel=0.005)
        return
    assert row["mains_hum_hz"] == pytest.approx(50.0, abs=0.01)
    assert row["rotation_rate_hz"] is None and row["rotation_rate_hz_status"] != "ok"
    row = process_capture(path, ProcessParams(mains_hz="none")).rows[0]
    assert row["mains_hum_hz"] is None and row["rotation_rate_hz"] == pytest.approx(rate_hz, rel=0.005)


@pytest.mark.parametrize("period_s, mains_hz, repeats", [
    (0.020, (50.0,), True), (0.010, (50.0,), True), (1 / 60, (50.0, 60.0), True), (1 / 120, (60.0,), True),
    (0.0201, (50.0,), True),    # within the grid's 1 %
    (0.0252, (60.0,), True),    # 3.024 half periods: within 1 % of 3 (the grid within 1 %), not of an absolute 0.01
    (0.0203, (50.0,), False),   # 1.5 % off
    (0.015, (50.0, 60.0), False), (0.005, (50.0,), False),  # half a half period: no whole one
    (0.020, (), False)])        # --mains-hz none: no grid
def test_a_power_repeating_with_the_grid(period_s, mains_hz, repeats):
    from mdpipe.process.mains import repeats_with_grid
    assert repeats_with_grid(period_s, mains_hz) is repeats


def test_a_power_line_lies_on_the_grid_at_its_first_harmonics_folded_by_the_prf():
    """A line at 150 Hz lies on a 50 Hz grid's 3rd harmonic, within 3 times 1 % of it, not beyond; 20 Hz on a 60 Hz
    grid's 4th, 240 Hz, folded by a PRF of 220 Hz; 250 Hz (the 5th) and 37 Hz on neither."""
    from mdpipe.process.mains import line_on_grid
    assert line_on_grid(150.0, (50.0,), prf_hz=3000.0)
    assert line_on_grid(151.4, (50.0,), prf_hz=3000.0) and not line_on_grid(151.6, (50.0,), prf_hz=3000.0)
    assert line_on_grid(20.0, (60.0,), prf_hz=220.0)
    assert not line_on_grid(250.0, (50.0,), prf_hz=3000.0)
    assert not line_on_grid(37.0, (50.0, 60.0), prf_hz=1000.0)
    assert not line_on_grid(150.0, (), prf_hz=3000.0)
