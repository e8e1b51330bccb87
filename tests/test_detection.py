"""Range-Doppler detection: thresholds from the Gamma statistics of averaged noise powers.

Known answers: gamma_isf equals scipy's inverse regularised upper gamma function; on noise-only
captures the Doppler cells and band means follow the Gamma laws the thresholds are set from, and
(slow) alarms come at the stated false-alarm probability per capture; the integration gain
(threshold excess over the noise ~ 1/sqrt(looks)); a bird and a drone at -10 dB per IF sample
over 3 s at X band are found (a fixed 12 dB on the mean moving power missed both); a static
scatterer 40 dB stronger than a drone leaves no trace in the Doppler cells.
"""

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
from scipy.special import gammainccinv
from scipy.stats import norm

from conftest import RADARLOG_SMALL, XBAND, scene_mapping, simulate
from mdpipe.io import open_capture
from mdpipe.params import ProcessParams
from mdpipe.process import ranging, selection
from mdpipe.process.cfar import gamma_isf, normal_isf
from mdpipe.process.pipeline import process_capture

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from bench_detection import GULL, QUAD  # noqa: E402  (the scenes the benchmark sweeps in SNR)


@pytest.mark.parametrize("shape", [1, 2, 7, 64, 1000, 2000, 2001, 30000])
@pytest.mark.parametrize("p", [0.5, 1e-3, 1e-7])
def test_gamma_isf_matches_scipy(shape, p):
    tolerance = 1e-9 if shape <= 2000 else 1e-4  # exact sum, then Wilson-Hilferty
    assert gamma_isf(shape, p) == pytest.approx(gammainccinv(shape, p), rel=tolerance)


@pytest.mark.parametrize("p", [0.3, 1e-3, 1e-12])
def test_normal_isf_matches_scipy(p):
    assert normal_isf(p) == pytest.approx(norm.isf(p), rel=1e-9)


def noise_test(tmp_path, seed, *, p, radar=XBAND, **changes):
    path, _ = simulate(tmp_path, scene_mapping(radar | changes, [], noise={"sigma_v": 1e-3}, seed=seed), "noise.h5")
    with open_capture(path) as reader:
        stats = ranging.gate_statistics(reader, max_range_m=reader.params.max_range_m)
    return stats, selection.detection_test(stats, false_alarm_probability=p)


def test_noise_cells_follow_the_gamma_law(tmp_path):
    """On noise only, each Doppler cell over the estimated noise level is Gamma(n)/n (n = blocks x channels = 4)
    and each bin's band mean Gamma(m)/m: the share above the 1 % quantile of each law is 1 %. 20 captures of
    53 gate bins: 270,000 cells (sd of the share < 0.05 %) and ~1000 band means (sd 0.3 %)."""
    cells, bands = [], []
    for seed in range(20):
        stats, test = noise_test(tmp_path, seed, p=1e-3, radar=RADARLOG_SMALL)
        gain, _ = selection.block_noise_response(stats.doppler_power.shape[1])
        threshold = gamma_isf(test.looks, 0.01) / test.looks
        cells.append((stats.doppler_power[:, 1:] / gain[1:] / test.noise_cell > threshold).ravel())
        bands.append(test.band > gamma_isf(test.band_looks, 0.01) / test.band_looks)
    assert np.mean(np.concatenate(cells)) == pytest.approx(0.01, abs=0.001)
    assert np.mean(np.concatenate(bands)) == pytest.approx(0.01, abs=0.007)


@pytest.mark.slow
def test_false_alarms_at_the_default_probability(tmp_path):
    """p = 1e-3 per capture: 300 noise-only captures expect 0.3 alarms; 3 or more has probability 0.004."""
    count = 0
    for seed in range(300):
        path, _ = simulate(tmp_path, scene_mapping(XBAND | {"n_chirps": 4000}, [], noise={"sigma_v": 1e-3},
                                                   seed=1000 + seed), "noise.h5")
        count += bool(process_capture(path, ProcessParams()).detections)
    assert count <= 2


def test_threshold_falls_with_integration(tmp_path):
    """The band threshold's excess over the noise is z / sqrt(m) for m looks (Wilson-Hilferty to first order):
    four times the blocks halve it, to within the quantile's skew (and the p / bins spread)."""
    _, short = noise_test(tmp_path, 1, p=1e-3, n_chirps=2048)
    _, long = noise_test(tmp_path, 2, p=1e-3, n_chirps=8192)
    assert (short.band_threshold - 1) / (long.band_threshold - 1) == pytest.approx(2.0, rel=0.1)
    assert long.line_threshold < short.line_threshold


@pytest.mark.parametrize("target, chirp_period_s", [(GULL, 250e-6), (QUAD, 100e-6)], ids=["bird", "drone"])
def test_minus_10_db_per_sample_over_3_s_is_detected(tmp_path, target, chirp_period_s):
    radar = XBAND | {"chirp_period_s": chirp_period_s, "n_chirps": int(round(3.0 / chirp_period_s))}
    path, truth = simulate(tmp_path, scene_mapping(radar, [target], noise={"snr_db": -10.0}))
    result = process_capture(path, ProcessParams())
    assert [abs(d.bin - truth["targets"][0]["range_bin"]) <= 1 for d in result.detections] == [True]


def test_static_scatterer_40_db_over_a_drone_is_not_detected(tmp_path):
    drone_power = 0.01 + 8 * 0.01  # body and blades' flash RCS, at 40 m
    tree_rcs = 1e4 * drone_power * (20.0 / 40.0) ** 4  # +40 dB at the receiver from 20 m
    mapping = scene_mapping(XBAND | {"chirp_period_s": 100e-6, "n_chirps": 4000},
                            [QUAD, {"type": "static", "range_m": 20.0, "rcs_m2": tree_rcs}], noise={"snr_db": 0.0})
    path, truth = simulate(tmp_path, mapping)
    result = process_capture(path, ProcessParams())
    stats, drone_bin = result.stats, truth["targets"][0]["range_bin"]
    assert 10 * np.log10(stats.static_power.max() / stats.moving_power[drone_bin]) > 35
    assert [d.bin for d in result.detections] == [truth["targets"][0]["range_bin"]]


def test_a_last_chunk_of_one_chirp_is_left_out_of_the_doppler_cells(tmp_path):
    """513 chirps read in chunks of 256: the last holds one chirp, whose Hann window is all zeros. Only the two full
    blocks are averaged into the Doppler cells, and nothing divides by the empty window (no warning)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        stats, _ = noise_test(tmp_path, 0, p=1e-3, n_chirps=513)
    assert stats.doppler_blocks == 2 and np.all(np.isfinite(stats.doppler_power))
