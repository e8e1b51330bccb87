"""Simulation benchmark: full-size FIMI capture against a bare h5py write, and the cost of each shortcut.

Prints three tables:
1. full size (configs/fimi.yaml: 19,712 chirps x 2048 samples x 16 RX, 1.3 GB of int16): wall time and
   peak RSS of ``mdpipe simulate`` and of a bare h5py write of the same datasets, and their ratio
   (medians over --repeats runs, alternating);
2. one 1024-chirp x 128-sample frame of the FIMI rotors: time of each model choice;
3. the error each fidelity shortcut costs on that frame against the exact model (every sample evaluated).
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from mdpipe.simulate.scene import load_scene_mapping, scene_from_mapping  # noqa: E402
from mdpipe.simulate.synth import noise_free_if, plan_targets  # noqa: E402

H5_WRITE = r"""
import sys, time, h5py, numpy as np
path, chirps, samples, channels, rows = sys.argv[1], *map(int, sys.argv[2:6])
block = np.random.default_rng(0).integers(-2000, 2000, (rows, samples), dtype=np.int16)
start = time.perf_counter()
with h5py.File(path, "w") as h5:
    sets = [h5.create_dataset(f"Chn{c + 1}", (chirps, samples), np.int16, chunks=(64, samples)) for c in range(channels)]
    for first in range(0, chirps, rows):
        n = min(rows, chirps - first)
        for ds in sets:
            ds[first:first + n] = block[:n]
print(time.perf_counter() - start)
"""


def child(argv):
    """Wall time and peak RSS (MB) of one child process.

    A wrapper process runs it, so the RSS counter (the largest child ever, per process) holds that
    child alone.
    """
    wrapper = ("import resource, subprocess, sys, time; s = time.perf_counter(); "
               "subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL); "
               "print(time.perf_counter() - s, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024)")
    out = subprocess.run([sys.executable, "-c", wrapper, *argv], check=True, capture_output=True, text=True).stdout
    wall, rss = out.split()
    return float(wall), float(rss)


def full_size(workdir, repeats):
    config = ROOT / "configs" / "fimi.yaml"
    scene = scene_from_mapping(load_scene_mapping(config))
    r = scene.radar
    target = Path(workdir) / "bench_fimi.h5"
    baseline = Path(workdir) / "bench_h5py.h5"
    sim_times, write_times = [], []
    sim_rss = write_rss = 0.0
    try:
        for _ in range(repeats):  # alternating, so both see the same machine
            wall, rss = child([sys.executable, "-c", H5_WRITE, str(baseline), str(r.n_chirps),
                               str(r.n_samples), str(r.n_channels), "512"])
            write_times.append(wall)
            write_rss = max(write_rss, rss)
            baseline.unlink()
            wall, rss = child([str(Path(sys.executable).parent / "mdpipe"), "simulate", "--config",
                               str(config), "-o", str(target)])
            sim_times.append(wall)
            sim_rss = max(sim_rss, rss)
            size_gb = target.stat().st_size / 1e9
            target.unlink()
    finally:
        for p in (target, baseline):
            if p.exists():
                p.unlink()
    sim, write = statistics.median(sim_times), statistics.median(write_times)
    print(f"\n## Full size: {r.n_chirps} chirps x {r.n_samples} samples x {r.n_channels} RX ({size_gb:.2f} GB), "
          f"median of {repeats}, {os.cpu_count()} cores")
    print("| step | wall time (s) | peak RSS (MB) |")
    print("|---|---|---|")
    print(f"| h5py write of the same datasets (process) | {write:.2f} | {write_rss:.0f} |")
    print(f"| mdpipe simulate configs/fimi.yaml (process) | {sim:.2f} | {sim_rss:.0f} |")
    print(f"| ratio simulate / write | {sim / write:.2f} (target <= 4) | |")
    return {"simulate_s": sim, "h5py_write_s": write, "ratio": sim / write, "simulate_peak_rss_mb": sim_rss}


def frame_scene(**fidelity):
    data = load_scene_mapping(ROOT / "configs" / "fimi.yaml")
    data["radar"].update(n_samples=128, sample_rate_hz=2.5e6, n_chirps=1024, n_channels=1)
    data["targets"] = [t for t in data["targets"] if t["type"] == "multirotor"]
    data["fidelity"] = fidelity
    return data


def frame_signal(data):
    scene = scene_from_mapping(data)
    plans = plan_targets(scene)
    start = time.perf_counter()
    x = noise_free_if(plans, 0, scene.radar.n_chirps, radar=scene.radar.params)
    return time.perf_counter() - start, x.astype(np.float64), plans[0].model


def frame_table(repeats, *, quiet=False):
    variants = [
        ("exact: every sample evaluated (reference)", {"in_chirp_motion": "exact"}, None),
        ("auto (default): Chebyshev nodes + migration", {}, None),
        ("stop-and-hop: 1 node per chirp", {"in_chirp_motion": "off"}, None),
        ("no range migration", {"range_migration": "off"}, None),
        ("point blades Q=16 (Eq. 1)", {}, 16),
        ("point blades Q=64 (Eq. 1)", {}, 64),
        ("point blades Q=256 (Eq. 1)", {}, 256),
    ]
    reference = None
    rows = []
    for label, fidelity, points in variants:
        data = frame_scene(**fidelity)
        if points is not None:
            data["targets"][0]["rotors"]["points_per_blade"] = points
        times = []
        for _ in range(repeats):
            elapsed, x, model = frame_signal(data)
            times.append(elapsed)
        if reference is None:
            reference = x
        error = np.sqrt(np.mean((x - reference) ** 2) / np.mean(reference ** 2))
        rows.append((label, statistics.median(times) * 1e3, error, model))
    if quiet:
        return [{"model": r[0], "time_ms": r[1], "rel_rms_error": r[2]} for r in rows]
    print(f"\n## One FIMI rotor frame: 1024 chirps x 128 samples, 4 rotors x 2 blades, 76 GHz "
          f"(median of {repeats})")
    print("| model | time (ms) | nodes/chirp | rel. RMS error vs exact | bound |")
    print("|---|---|---|---|---|")
    for label, ms, error, model in rows:
        bound = model.interpolation_error_bound if model.range_migration else model.migration_error_bound
        print(f"| {label} | {ms:.1f} | {model.nodes_per_chirp} | {error:.2e} | {bound:.1e} |")
    return [{"model": r[0], "time_ms": r[1], "rel_rms_error": r[2]} for r in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workdir", default=tempfile.gettempdir(), help="where the 1.3 GB files go")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--skip-full", action="store_true", help="only the frame tables")
    parser.add_argument("--json", type=Path, help="also write the numbers here")
    args = parser.parse_args()
    results = {"frame": frame_table(max(args.repeats, 5))}
    if not args.skip_full:
        results["full_size"] = full_size(args.workdir, args.repeats)
    if args.json:
        args.json.write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
