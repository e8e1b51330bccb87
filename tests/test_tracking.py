"""Following a target across range bins without spectral splatter, and the manual range gate.

Known answers: a point moving radially across 4-5 range bins is one Doppler line at -2 v / lambda
(paper sign), and the energy of its dwell spectrum outside +-3 Doppler bins of that line equals
that of the same echo with its range held in one bin (the simulator's ``range_migration: off``:
the same phase history and 1/R^2 amplitude, a fixed beat frequency) to within -40 dB of the total:
the range tracking adds no amplitude or phase step. A bird crossing bins keeps the Doppler floor
far from its body line where the same bird held in one bin has it.
"""

import numpy as np
import pytest

from conftest import RADARLOG_SMALL, XBAND, scene_mapping, simulate
from mdpipe.errors import ParameterError
from mdpipe.io import open_capture
from mdpipe.params import ProcessParams
from mdpipe.process import ranging, selection
from mdpipe.process.doppler import power_spectrum
from mdpipe.process.pipeline import process_capture, target_signals, target_tracks

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]
LINE_HALF_WIDTH_BINS = 3
SPLATTER_DB = -40.0


def tracked_signal(path, process=ProcessParams()):
    """Pass 1, detection and pass 2 of the pipeline: the strongest target's slow time and (range_min_m, range_max_m)."""
    with open_capture(path) as reader:
        stats = ranging.gate_statistics(reader, window=process.range_window, zero_pad=process.zero_pad,
                                        min_range_m=process.min_range_m, max_range_m=reader.params.max_range_m,
                                        chunk_chirps=process.chunk_chirps)
        detections = selection.detect(stats, selection.detection_test(stats), max_targets=1)
        tracks = target_tracks(stats, detections, process, reader.params.n_samples)
        track, signal, _, _ = target_signals(reader, stats, tracks, process)[0]
        range_min_m, range_max_m = track.range_m.min(), track.range_m.max()
        return signal, reader.params, (range_min_m, range_max_m)


def off_line_fraction(signal, prf_hz):
    """Share of the dwell energy beyond LINE_HALF_WIDTH_BINS Doppler bins from the strongest line, and its Doppler."""
    spectrum = power_spectrum(signal, prf_hz=prf_hz)
    n, peak = len(spectrum.power), int(np.argmax(spectrum.power))
    distance = np.abs((np.arange(n) - peak + n // 2) % n - n // 2)
    return spectrum.power[distance > LINE_HALF_WIDTH_BINS].sum() / spectrum.power.sum(), spectrum.f_hz[peak]


@pytest.mark.parametrize("radar, speed_mps, bins_crossed", [
    (XBAND | {"chirp_period_s": 250e-6, "n_chirps": 12000}, 10.0, 4),   # 7.5 m bins, 3 s, 30 m
    (RADARLOG_SMALL | {"n_chirps": 30000}, 10.0, 5),                    # 3.75 m bins, 1.92 s, 19.2 m
])
def test_point_crossing_bins_is_one_line_without_splatter(tmp_path, radar, speed_mps, bins_crossed):
    point = {"type": "point", "motion": {"position_m": [30.0, 0.0, 0.0], "velocity_mps": [speed_mps, 0.0, 0.0]}}
    fractions = {}
    for migration in ("off", "on"):
        path, _ = simulate(tmp_path, scene_mapping(radar, [point], fidelity={"range_migration": migration}),
                           f"{migration}.h5")
        signal, params, (near_m, far_m) = tracked_signal(path)
        fractions[migration], line_hz = off_line_fraction(signal, params.prf_hz)
    # the migrating echo's phase is that of the sweep's centre frequency (the one-bin echo's, of its start)
    assert line_hz == pytest.approx(-2 * speed_mps / params.wavelength_m, abs=params.prf_hz / len(signal))
    travel_m = speed_mps * params.duration_s(len(signal))
    assert travel_m / params.range_bin_m >= bins_crossed
    assert far_m - near_m == pytest.approx(travel_m, abs=0.5 * params.range_bin_m)  # the track followed it
    assert fractions["on"] - fractions["off"] < 10 ** (SPLATTER_DB / 10)


def test_bird_crossing_bins_leaves_the_far_doppler_floor_alone(tmp_path):
    """76 GHz, 3.75 m bins: a bird flying away at 8 m/s crosses 4 bins in 2 s. Far from its body line
    (> 0.3 PRF; the wings reach ~0.1 PRF) the noise-free spectrum holds only window sidelobes, at the
    level of the same bird held in one bin (stepwise bin switching raised it by 25 dB)."""
    bird = {"type": "bird", "motion": {"position_m": [20.0, 0.0, 3.0], "velocity_mps": [8.0, 0.0, 0.0]},
            "wingbeat_hz": 3.0, "upper_arm_m": 0.3, "forearm_m": 0.3, "wing_rcs_m2": 0.05, "body_rcs_m2": 0.05}
    radar = RADARLOG_SMALL | {"chirp_period_s": 128e-6, "n_chirps": 16000}
    floor_db = {}
    for migration in ("off", "on"):
        path, _ = simulate(tmp_path, scene_mapping(radar, [bird], fidelity={"range_migration": migration}),
                           f"{migration}.h5")
        signal, params, (near_m, far_m) = tracked_signal(path)
        spectrum = power_spectrum(signal, prf_hz=params.prf_hz)
        body_hz = spectrum.f_hz[np.argmax(spectrum.power)]
        far = np.abs(spectrum.f_hz - body_hz) > 0.3 * params.prf_hz
        floor_db[migration] = 10 * np.log10(np.median(spectrum.power[far]) / spectrum.power.max())
    assert far_m - near_m > 3 * params.range_bin_m
    assert floor_db["on"] < floor_db["off"] + 3.0


def test_manual_range_is_a_fixed_gate_at_that_range():
    """--range-m 11 on the FIMI sample (drone at 3.75 m, 3.75 m bins): 11 m is analysed, not the drone."""
    result = process_capture(ROOT / "data_samples" / "fimi_1rx.h5", ProcessParams(range_m=11.0))
    row = result.rows[0]
    assert row["range_m"] == row["range_min_m"] == row["range_max_m"] == pytest.approx(11.0, abs=1e-9)
    assert row["range_bin"] == 3
    detected = process_capture(ROOT / "data_samples" / "fimi_1rx.h5", ProcessParams()).rows[0]
    assert detected["range_bin"] == 1 and detected["class"] == "drone"
    assert row["snr_db"] < detected["snr_db"] - 10  # two bins away from the drone: its range sidelobes only


@pytest.mark.parametrize("range_m, allowed", [(5000.0, r"\[1, 200\] m"), (0.5, r"\[1, 200\] m")])
def test_manual_range_outside_the_gate_is_an_error(range_m, allowed):
    with pytest.raises(ParameterError, match=rf"range_m={range_m:g} m lies outside the range gate {allowed}"):
        process_capture(ROOT / "data_samples" / "fimi_1rx.h5", ProcessParams(range_m=range_m))


def test_full_fft_and_dft_on_the_track_agree(tmp_path):
    """``range_bins="all"`` (an FFT padded to the 1/8-bin grid, columns picked) and the DFT at the grid columns
    are the same numbers (float64: to rounding), two channels combined, on a target crossing bins."""
    point = {"type": "point", "motion": {"position_m": [30.0, 5.0, 0.0], "velocity_mps": [10.0, 0.0, 0.0]}}
    path, _ = simulate(tmp_path, scene_mapping(RADARLOG_SMALL | {"n_chirps": 4096, "n_channels": 2}, [point],
                                               noise={"snr_db": 0.0}))
    in_use, _, (near_m, far_m) = tracked_signal(path, ProcessParams(dtype="float64"))
    full, _, _ = tracked_signal(path, ProcessParams(dtype="float64", range_bins="all"))
    assert far_m - near_m > 2.0
    assert np.linalg.norm(full - in_use) < 1e-9 * np.linalg.norm(in_use)


def test_static_clutter_beside_a_crossing_target_leaves_no_line(tmp_path):
    """A point receding at 3 m/s across ~4 bins of 7.5 m at X band passes a static scatterer 30 dB stronger.
    Blending the bins the track crosses would modulate the clutter into a line near 0 Hz that outshines the
    target; with each column's static part taken out along the track, the body line is the target's."""
    radar = XBAND | {"n_chirps": 40000, "chirp_period_s": 250e-6}  # 10 s at PRF 4 kHz
    mover = {"type": "point", "motion": {"position_m": [30.0, 0.0, 0.0], "velocity_mps": [3.0, 0.0, 0.0]},
             "rcs_m2": 0.01}
    clutter = {"type": "static", "range_m": 45.0, "rcs_m2": 10.0}
    path, truth = simulate(tmp_path, scene_mapping(radar, [mover, clutter], noise={"snr_db": 10.0}))
    row = process_capture(path, ProcessParams(max_targets=1)).rows[0]
    assert row["body_velocity_mps_status"] == "ok"
    assert row["body_velocity_mps"] == pytest.approx(3.0, abs=0.05)


def test_a_target_crossing_many_bins_is_one_detection(tmp_path):
    """A pigeon-sized bird approaching at 9.7 m/s for 2.5 s at X band with 100 MHz (1.5 m bins) crosses ~16
    bins: its mean moving power peaks at several bins along the path, and the track followed from each peak is
    the same one. One target, not four; its range extent is the path flown (about 52 to 28 m)."""
    radar = dict(f_start_hz=9.8e9, f_stop_hz=9.9e9, ramp_up_s=352.8e-6, chirp_period_s=440.9e-6,
                 sample_rate_hz=362854.0, n_samples=128, n_chirps=5625, n_channels=1)
    bird = {"type": "bird", "wingbeat_hz": 5.3, "upper_arm_m": 0.145, "forearm_m": 0.158, "body_rcs_m2": 0.017,
            "wing_rcs_m2": 0.0097, "motion": {"position_m": [49.87, -7.0, 10.2], "velocity_mps": [-9.73, 3.0, 0.0]}}
    path, _ = simulate(tmp_path, scene_mapping(radar, [bird], noise={"moving_snr_db": 11.2}, seed=1469921155))
    with open_capture(path) as reader:
        stats = ranging.gate_statistics(reader, window="hann", zero_pad=1, min_range_m=1.0, max_range_m=200.0,
                                        chunk_chirps=256)
    test = selection.detection_test(stats, false_alarm_probability=1e-3)
    assert len(selection.detect(stats, test, max_targets=4, zero_pad=1)) > 1  # the peaks along the path
    rows = process_capture(path, ProcessParams()).rows
    assert len(rows) == 1
    assert rows[0]["range_min_m"] < 32.0 and rows[0]["range_max_m"] > 48.0
