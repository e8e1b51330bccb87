"""Speed against error: every choice that trades time for accuracy, swept one at a time from the defaults.

Simulation choices (blade model, in-chirp motion) are measured where they matter, on a FIMI rotor
frame at 76 GHz, as the relative RMS error of the IF against the exact model (every sample
evaluated; benchmarks/bench_simulate.py). Processing choices use three known-answer scenes: Table I
configs 7 (Phantom 4, beta = 0, 0.2 s) and 1 (80 rev/s, tips over 43 rotation harmonics: 5.4 Doppler
bins a side of a quarter chopping period, the flash edges read in longer frames; 0.08 s) at X band, and
a gull flying past (3 s); the errors are those of rotation
rate, blade length, spectrogram bandwidth (against Eq. 6) and wingbeat against the truth in the
files, the worst over the drone scenes. Times are medians over several runs. Writes
reports/bench.csv and reports/bench.png (time against the largest error, one panel per choice,
the default starred), prints the table and says whether each default is on its sweep's Pareto
front (within 10 % in time and in error, a point does not dominate).
"""

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from mdpipe.params import ProcessParams  # noqa: E402
from mdpipe.process.pipeline import process_capture  # noqa: E402
from mdpipe.simulate.run import simulate_to_file  # noqa: E402
from mdpipe.simulate.scene import load_scene_mapping, scene_from_mapping  # noqa: E402

DRONE_CHIRPS = 5000
DRONE_CONFIGS = ("table1_config7.yaml", "table1_config1.yaml")
TOLERANCE = 0.1


def drone_scene(name, chirps=DRONE_CHIRPS):
    data = load_scene_mapping(ROOT / "configs" / "paper" / name)
    data["radar"]["n_chirps"] = chirps
    return data


def bird_scene():
    return load_scene_mapping(ROOT / "configs" / "samples" / "gull_flyby.yaml")


def timed(function, repeats):
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def rel(measured, expected):
    return None if measured is None or not expected else abs(measured / expected - 1)


def drone_errors(rows_truths):
    """Worst error over the drone scenes for each feature (None if any scene withheld it)."""
    out = {}
    for key, truth_key, name in (("rotation_rate_hz", "rotation_rate_hz", "rotation_err"),
                                 ("blade_length_m", "blade_length_m", "blade_err"),
                                 ("doppler_bw_spectrogram_hz", "doppler_bw_hz", "bw_err")):
        values = [rel(row.get(key), truth.get(truth_key)) for row, truth in rows_truths]
        out[name] = None if any(v is None for v in values) else max(values)
    return out


def simulate(mapping, path):
    return simulate_to_file(scene_from_mapping(mapping), path, scene_yaml="")


def process(path, **params):
    return process_capture(path, ProcessParams(**params)).rows[0]


def simulation_sweeps(repeats):
    from bench_simulate import frame_table

    rows = []
    for entry in frame_table(repeats, quiet=True):
        label = entry["model"]
        if label.startswith("exact"):
            continue
        choice = "blade model" if "point blades" in label else "in-chirp and migration model"
        rows.append({"stage": "simulate", "choice": choice, "value": label.split(":")[0].replace(" (default)", ""),
                     "default": label.startswith("auto"), "time_s": entry["time_ms"] / 1e3,
                     "signal_err": entry["rel_rms_error"]})
    closed = next(r for r in rows if r["default"])
    rows.append({**closed, "choice": "blade model", "value": "closed form"})
    return rows


def processing_sweeps(work, repeats):
    drones = []  # (capture, truth, elevation): each scene is processed with its own beta, as a user would
    for name in DRONE_CONFIGS:
        path = work / name.replace(".yaml", ".h5")
        truth = simulate(drone_scene(name), path)["targets"][0]
        drones.append((path, truth, truth["elevation_deg"]))
    bird_path = work / "bird.h5"
    bird_truth = simulate(bird_scene(), bird_path)["targets"][0]
    sweeps = [("flash-edge window (chopping periods)", "edge_window_periods", [0.125, 0.25, 0.5, 1.0], 0.25),
              ("flash-edge hop (of the window)", "edge_hop_fraction", [0.0625, 0.125, 0.25, 0.5], 0.125),
              ("precision", "dtype", ["float32", "float64"], "float32"),
              ("range bins computed", "range_bins", ["in-use", "all"], "in-use")]
    rows = []
    for choice, key, values, default in sweeps:
        for value in values:
            seconds, first = timed(lambda: process(drones[0][0], elevation_deg=drones[0][2], **{key: value}), repeats)
            results = [(first, drones[0][1])] + [(process(p, elevation_deg=beta, **{key: value}), t)
                                                 for p, t, beta in drones[1:]]
            bird_row = process(bird_path, **{key: value})
            rows.append({"stage": "process", "choice": choice, "value": str(value), "default": value == default,
                         "time_s": seconds, **drone_errors(results),
                         "wingbeat_err": rel(bird_row.get("wingbeat_freq_hz"), bird_truth["wingbeat_freq_hz"])})
    for chirps in (1250, 2500, 5000):  # dwell: how long the capture is; not a choice with a default
        results, seconds = [], None
        for name in DRONE_CONFIGS:
            path = work / f"dwell{chirps}.h5"
            truth = simulate(drone_scene(name, chirps), path)["targets"][0]
            elapsed, row = timed(lambda: process(path, elevation_deg=truth["elevation_deg"]), repeats)
            seconds = seconds or elapsed
            results.append((row, truth))
        rows.append({"stage": "process", "choice": "dwell (chirps at 25 kHz)", "value": str(chirps),
                     "default": False, "time_s": seconds, **drone_errors(results)})
    return rows


SNR_DB = (30.0, 20.0, 10.0, 5.0, 0.0, -5.0, -10.0, -15.0, -20.0)
TOLERANCES = {"rotation_rate_hz": 0.005, "blade_length_m": 0.03, "wingbeat_freq_hz": 0.03}


def snr_breakdown(work):
    """Per feature, the lowest per-sample SNR down to which it is right at every step (and what happens below).

    Drone: Table I config 7 (Phantom 4, X band, 0.2 s); bird: the gull sample scene (3 s). Each
    value counts as right within the known-answer tolerances (0.5 % rotation, 3 % blade length and
    wingbeat); below the breakdown it is withheld (with its reason) or, if ever, wrong.
    """
    rows = []
    for scene, mapping, features in (("drone", drone_scene("table1_config7.yaml"), ("rotation_rate_hz", "blade_length_m")),
                                     ("bird", bird_scene(), ("wingbeat_freq_hz",))):
        for snr in SNR_DB:
            mapping["noise"] = {"snr_db": snr}
            path = work / f"snr_{scene}.h5"
            truth = simulate(mapping, path)["targets"][0]
            row = process(path)
            for feature in features:
                value = row.get(feature)
                verdict = "withheld" if value is None else (
                    "right" if rel(value, truth[feature]) <= TOLERANCES[feature] else "wrong")
                rows.append({"scene": scene, "feature": feature, "snr_db_per_sample": snr, "snr_db_bin": row["snr_db"],
                             "class": row["class"], "verdict": verdict})
    return pd.DataFrame(rows)


def worst_error(row):
    """The largest relative error of a row; a feature withheld counts as 100 %."""
    if row["stage"] == "simulate":
        return row["signal_err"]
    keys = ("rotation_err", "blade_err", "bw_err", "wingbeat_err") if "wingbeat_err" in row else \
        ("rotation_err", "blade_err", "bw_err")
    return max(1.0 if row.get(k) is None or not np.isfinite(row[k]) else row[k] for k in keys)


def _clearly_less(a, b, floor):
    return a < b * (1 - TOLERANCE) and b - a > floor


def on_front(group):
    """Whether each point is on the Pareto front: no other point is clearly faster (by 10 %) and not clearly
    less accurate, or clearly more accurate and not clearly slower."""
    t, e = group["time_s"].to_numpy(), group["worst_err"].to_numpy()

    def dominates(j, i):
        not_worse = not _clearly_less(e[i], e[j], 1e-4) and not _clearly_less(t[i], t[j], 0.0)
        return not_worse and (_clearly_less(t[j], t[i], 0.0) or _clearly_less(e[j], e[i], 1e-4))
    return [not any(dominates(j, i) for j in range(len(t)) if j != i) for i in range(len(t))]


def plot(table, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    choices = list(dict.fromkeys(table["choice"]))
    fig, axes = plt.subplots(2, (len(choices) + 1) // 2, figsize=(4.2 * ((len(choices) + 1) // 2), 7), squeeze=False)
    for ax, choice in zip(axes.ravel(), choices):
        group = table[table["choice"] == choice]
        for _, r in group.iterrows():
            ax.scatter(r["time_s"], max(r["worst_err"], 1e-6), marker="*" if r["default"] else "o",
                       s=160 if r["default"] else 40, color="C3" if r["default"] else "C0")
            ax.annotate(r["value"], (r["time_s"], max(r["worst_err"], 1e-6)), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
        from matplotlib.ticker import NullFormatter

        times, worst = group["time_s"], group["worst_err"].clip(lower=1e-6)
        if times.max() > 3 * times.min():
            ax.set_xscale("log")
        if worst.max() > 3 * worst.min():
            ax.set_yscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set_title(f"{choice} ({group['stage'].iloc[0]})", fontsize=9)
        ax.set_xlabel("median time (s)")
        ax.set_ylabel("largest relative error")
        ax.grid(alpha=0.3, which="both")
    for ax in axes.ravel()[len(choices):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "reports")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        rows = simulation_sweeps(args.repeats) + processing_sweeps(Path(work), args.repeats)
    table = pd.DataFrame(rows)
    table["worst_err"] = [worst_error(r) for r in rows]
    table["pareto"] = np.concatenate([on_front(g) for _, g in table.groupby("choice", sort=False)])
    table.to_csv(args.out / "bench.csv", index=False)
    plot(table, args.out / "bench.png")
    with tempfile.TemporaryDirectory() as work:
        snr = snr_breakdown(Path(work))
    snr.to_csv(args.out / "snr_breakdown.csv", index=False)
    print("| stage | choice | value | median time (s) | signal | rotation | blade length | BW vs Eq. 6 | wingbeat | Pareto |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    fmt = lambda v: "" if v is None or (isinstance(v, float) and np.isnan(v)) else f"{100 * v:.2g} %"  # noqa: E731
    for _, r in table.iterrows():
        star = " (default)" if r["default"] else ""
        print(f"| {r['stage']} | {r['choice']} | {r['value']}{star} | {r['time_s']:.3g} | {fmt(r.get('signal_err'))} | "
              f"{fmt(r.get('rotation_err'))} | {fmt(r.get('blade_err'))} | {fmt(r.get('bw_err'))} | "
              f"{fmt(r.get('wingbeat_err'))} | {'yes' if r['pareto'] else 'no'} |")
    print("\n| feature | breakdown: lowest SNR per sample (dB) right all the way down | below it | wrong values |")
    print("|---|---|---|---|")
    for (scene, feature), group in snr.groupby(["scene", "feature"], sort=False):
        group = group.sort_values("snr_db_per_sample", ascending=False)
        right = group["verdict"].eq("right").cumprod().astype(bool)
        lowest = group.loc[right, "snr_db_per_sample"].min() if right.any() else None
        below = ", ".join(sorted(set(group.loc[~right, "verdict"]))) or "-"
        print(f"| {scene}: {feature} | {lowest if lowest is not None else 'none'} | {below} | "
              f"{int(group['verdict'].eq('wrong').sum())} |")
    defaults = table[table["default"]]
    off = defaults[~defaults["pareto"]]
    print(f"\ndefaults on their Pareto front: {len(defaults) - len(off)} of {len(defaults)}"
          + ("" if off.empty else f" (not: {', '.join(off['choice'])})"))


if __name__ == "__main__":
    main()
