"""Detection: the empirical false-alarm rate on noise-only captures and the lowest per-sample SNR detected.

False alarms: many noise-only X-band captures (seeds 0..n-1) of two kinds: 4000 chirps, one channel
(every chirp probed in pass 1) and 32768 chirps, four channels (an eighth probed); a false alarm is
a capture with any detection, at the default probability per capture
(:data:`mdpipe.process.selection.FALSE_ALARM_PROBABILITY`) and at 0.1 (where a rate is measurable
with a few hundred captures).

SNR limit: a gull (2.5 Hz wingbeat, flying away at 4 m/s, 4 kHz PRF) and a quadcopter (90 rev/s,
12 cm blades, 10 kHz PRF) at X band over 3 s and 0.25 s dwells, per-sample SNR (the scene's
``snr_db``) stepped down by 2 dB; detected = a detection within one bin of the truth's range bin.
The limit is the lowest SNR down to which every seed of every step was detected.
"""

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from mdpipe.params import ProcessParams  # noqa: E402
from mdpipe.process import selection  # noqa: E402
from mdpipe.process.pipeline import process_capture  # noqa: E402
from mdpipe.simulate.run import simulate_to_file  # noqa: E402
from mdpipe.simulate.scene import scene_from_mapping  # noqa: E402

XBAND = dict(f_start_hz=9.79e9, f_stop_hz=9.81e9, ramp_up_s=12.8e-6, chirp_period_s=25e-6,
             sample_rate_hz=5.0e6, n_samples=64, n_chirps=4000, n_channels=1)
GULL = {"type": "bird", "motion": {"position_m": [30.0, 0.0, 3.0], "velocity_mps": [4.0, 0.0, 0.0]},
        "wingbeat_hz": 2.5, "upper_arm_m": 0.375, "forearm_m": 0.375, "wing_rcs_m2": 0.05, "body_rcs_m2": 0.05}
QUAD = {"type": "multirotor", "motion": {"position_m": [40.0, 0.0, 0.0], "velocity_mps": [-2.0, 0, 0]},
        "body_rcs_m2": 0.01, "rotors": {"count": 4, "arm_m": 0.2, "blade_length_m": 0.12, "root_m": 0.01,
                                        "rev_per_s": [90, -90, 90, -90], "phase_deg": [0, 30, 65, 100],
                                        "blade_rcs_m2": 0.01}}
NOISE_KINDS = {"4000 chirps, 1 RX": dict(n_chirps=4000, n_channels=1),
               "32768 chirps, 4 RX": dict(n_chirps=32768, n_channels=4)}
TARGETS = {"bird": (GULL, 250e-6), "drone": (QUAD, 100e-6)}


def run(mapping, path):
    truth = simulate_to_file(scene_from_mapping(mapping), path, scene_yaml="")
    return process_capture(path, ProcessParams()), truth


def false_alarms(work, n_seeds, probabilities):
    rows = []
    for kind, radar in NOISE_KINDS.items():
        start, alarms = time.perf_counter(), dict.fromkeys(probabilities, 0)
        for seed in range(n_seeds):
            result, _ = run({"radar": XBAND | radar, "targets": [], "noise": {"sigma_v": 1e-3}, "seed": seed},
                            work / "noise.h5")
            for p in probabilities:
                test = selection.detection_test(result.stats, false_alarm_probability=p)
                alarms[p] += bool(selection.detect(result.stats, test, max_targets=4))
        seconds = (time.perf_counter() - start) / n_seeds
        rows += [(kind, p, n_seeds, alarms[p], seconds) for p in probabilities]
    return rows


def snr_limit(work, target, chirp_period_s, dwell_s, snrs, seeds):
    limit = None
    for snr in snrs:
        hits = 0
        for seed in seeds:
            radar = XBAND | {"chirp_period_s": chirp_period_s, "n_chirps": int(round(dwell_s / chirp_period_s))}
            mapping = {"radar": radar, "targets": [target], "noise": {"snr_db": float(snr)}, "seed": seed}
            result, truth = run(mapping, work / "target.h5")
            hits += any(abs(d.bin - truth["targets"][0]["range_bin"]) <= 1 for d in result.detections)
        if hits < len(seeds):
            break
        limit = snr
    return limit


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=200, help="noise-only captures per kind")
    parser.add_argument("--snr-seeds", type=int, default=3, help="captures per SNR step")
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp())
    print(f"{'noise-only captures':<22} {'stated':>7} {'n':>5} {'false alarms':>13} {'rate':>8} {'s/capture':>10}")
    for kind, p, n, alarms, seconds in false_alarms(work, args.seeds, (selection.FALSE_ALARM_PROBABILITY, 0.1)):
        print(f"{kind:<22} {p:>7g} {n:>5} {alarms:>13} {alarms / n:>8.4f} {seconds:>10.3f}")
    print(f"\n{'target':<8} {'dwell (s)':>9} {'lowest SNR detected (dB per IF sample)':>40}")
    for name, (target, period) in TARGETS.items():
        for dwell in (3.0, 0.25):
            limit = snr_limit(work, target, period, dwell, np.arange(10, -41, -2), range(args.snr_seeds))
            print(f"{name:<8} {dwell:>9g} {'none' if limit is None else f'{limit:g}':>40}")


if __name__ == "__main__":
    main()
