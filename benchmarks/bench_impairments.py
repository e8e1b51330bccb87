"""Receiver impairments of real recordings: what they do to mdpipe's rows, and what it says of them.

ADC saturation first (samples clipped at the int16 full scale). Captures: the bundled samples and the first scenes of
the default sweep (``configs/sweeps/default.yaml``), simulated here. Each is processed as it is, then with its IF
samples scaled (the receiver gain raised) until a share ``s`` of them sits at the int16 full scale (clipped). Per
share, against the unclipped reading of the same capture:

* images: detections the unclipped capture does not hold (harmonics and intermodulation products of the IF); of
  those, the ones whose echo reads ``drone`` or ``bird`` (its class, or for one marked ``clipping_image``, the class
  its note names), the ones marked, and the ones left ``drone`` or ``bird`` (wrong classes);
* targets (detections of the unclipped capture) whose class changed;
* values of the targets (chopping, rotation rate, blade length, wingbeat, body velocity) more than 3 % (and 0.05 m/s)
  from the unclipped reading and still given ``ok`` (confidently moved).

Then, the same captures with the receiver gain 6 dB lower and another radar's chirps crossing ours (a burst every 37.3,
9.71 or 2.43 chirps; short or long, strong or weak), or a TX-RX leakage beat whose amplitude and phase drift, with a DC
offset, or the supply's 50 Hz ripple on the gain (each static echo then carries its Doppler lines about 0 Hz; read with
mains hum taken out, the default, and kept, ``--mains-hz none``), or every other chirp sent by a second transmitter
(a MIMO radar's time-division cycle, its feed 120 deg apart; read with the cycle searched, the default, and as one
sequence, ``--transmitters 1``) (``tests/hostile.py``): new detections, the ones read drone or bird, targets whose
class changed (of them, withheld as the impairment's echo), values moved.

Usage: ``python benchmarks/bench_impairments.py [--scenes 24] [--shares 0.001,0.01,0.03,0.1,0.3,0.5]``
(``make bench-impairments``).
"""

import argparse
import re
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

from threadpoolctl import threadpool_limits

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

import hostile  # noqa: E402

from mdpipe.evaluate.sweep import draw_scenes, load_sweep  # noqa: E402
from mdpipe.params import ProcessParams  # noqa: E402
from mdpipe.process.pipeline import process_capture  # noqa: E402
from mdpipe.process.saturation import image_ceiling_db  # noqa: E402
from mdpipe.simulate.run import simulate_to_file  # noqa: E402
from mdpipe.simulate.scene import scene_from_mapping  # noqa: E402

SAMPLES = {"fimi_1rx.h5": 2, "phantom4_xband.h5": 2, "gull_flyby.h5": None, "clutter_only.h5": None}
VALUES = ("chopping_freq_hz", "rotation_rate_hz", "blade_length_m", "wingbeat_freq_hz", "body_velocity_mps")
MOVED_SHARE, MOVED_FLOOR = 0.03, 0.05  # a value moved: off its unclipped reading by more than both
WITHHELD = ("clipping_image", "interference")  # statuses of an echo an impairment may have made


def captures(work, n_scenes):
    """(name, path, ProcessParams) of the bundled samples and of the first ``n_scenes`` default-sweep scenes."""
    out = [(name, ROOT / "data_samples" / name, ProcessParams(n_blades=blades)) for name, blades in SAMPLES.items()]
    for draw in draw_scenes(load_sweep(ROOT / "configs" / "sweeps" / "default.yaml"), limit=n_scenes):
        path = work / f"{draw.name}.h5"
        simulate_to_file(scene_from_mapping(draw.scene), path, scene_yaml="")
        out.append((draw.name, path, ProcessParams(**draw.process)))
    return out


def targets(rows):
    return [row for row in rows if row["range_m"] is not None]


HUM_KEPT = {"mains_hz": "none"}  # the processing told not to look for mains hum (as before mdpipe/process/mains.py)
IMPAIRMENTS = {  # name: (how the capture is impaired, what the processing is told besides the capture's own options)
    "another radar's chirps, a burst every 37.3 chirps": lambda path, out: hostile.interfered(path, out, 37.3),
    "another radar's chirps, a burst every 9.71 chirps": lambda path, out: hostile.interfered(path, out, 9.71),
    "the same, bursts of 24 samples": lambda path, out: hostile.interfered(path, out, 9.71, burst_samples=24),
    "the same, bursts of 0.04 of the full scale": lambda path, out: hostile.interfered(path, out, 9.71,
                                                                                       amplitude=1300.0),
    "another radar's chirps, a burst every 2.43 chirps": lambda path, out: hostile.interfered(path, out, 2.43),
    "TX-RX leakage drifting 1 % and 0.05 rad, DC offset": lambda path, out: hostile.leaking(path, out),
    "the supply's 50 Hz ripple on the gain, 1 % (its 2nd harmonic; 1st, 3rd, 4th weaker)":
        lambda path, out: hostile.rippled(path, out, 0.01),
    "the same ripple, the hum kept (`--mains-hz none`)": (lambda path, out: hostile.rippled(path, out, 0.01), HUM_KEPT),
    "the supply's ripple, 5 %": lambda path, out: hostile.rippled(path, out, 0.05),
    "the 5 % ripple, the hum kept (`--mains-hz none`)": (lambda path, out: hostile.rippled(path, out, 0.05), HUM_KEPT),
    "two transmitters in turn, TX 2's feed 120 deg and 0.8 times TX 1's": hostile.alternated,
    "the same, read as one sequence (`--transmitters 1`)": (hostile.alternated, {"transmitters": "1"}),
}


def add(totals, counts):
    """``counts`` (:func:`compare`) summed into ``totals``; the highest image level kept."""
    for key, value in counts.items():
        if key == "highest_image_db":
            found = [v for v in (value, totals.get(key)) if v is not None]
            totals[key] = max(found) if found else None
        else:
            totals[key] = totals.get(key, 0) + value


def compare(base, rows, bin_m):
    """Counts of one impaired reading against the clean one (``base``): see the module's list."""
    top = max((row["snr_db"] for row in targets(rows) if row["snr_db"] is not None), default=None)
    counts = {"highest_image_db": None}
    counts |= dict.fromkeys(("images", "image_classes", "image_classes_left", "marked", "class_changed", "moved_ok",
                             "values", "class_withheld"), 0)
    for row in targets(rows):
        match = [b for b in targets(base) if abs(b["range_m"] - row["range_m"]) <= 2 * bin_m]
        if not match:
            marked = row["chopping_freq_hz_status"] == "clipping_image"
            read = re.search(r"its echo read as (\w+)", row["notes"]).group(1) if marked else row["class"]
            counts["images"] += 1
            if row["snr_db"] is not None:
                level = row["snr_db"] - top
                highest = counts["highest_image_db"]
                counts["highest_image_db"] = level if highest is None else max(level, highest)
            counts["marked"] += marked
            counts["image_classes"] += read != "none"
            counts["image_classes_left"] += row["class"] != "none"
            continue
        unclipped = match[0]
        counts["class_changed"] += row["class"] != unclipped["class"]
        counts["class_withheld"] += row["class"] != unclipped["class"] and row["chopping_freq_hz_status"] in WITHHELD
        for key in VALUES:
            before, after = unclipped.get(key), row.get(key)
            if before is None or after is None:
                continue
            counts["values"] += 1
            if abs(after - before) > max(MOVED_SHARE * abs(before), MOVED_FLOOR):
                counts["moved_ok"] += row[f"{key}_status"] == "ok"
    return counts


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scenes", type=int, default=24, help="default-sweep scenes besides the bundled samples")
    parser.add_argument("--shares", default="0.001,0.01,0.03,0.1,0.3,0.5", help="shares of the samples clipped")
    args = parser.parse_args(argv)
    shares = [float(s) for s in args.shares.split(",")]
    start = time.perf_counter()
    totals = {share: {} for share in shares}
    others = {name: {} for name in IMPAIRMENTS}
    with tempfile.TemporaryDirectory() as tmp, threadpool_limits(limits=1):
        work = Path(tmp)
        items = captures(work, args.scenes)
        n_targets = 0
        for name, path, params in items:
            base = process_capture(path, params)
            n_targets += len(targets(base.rows))
            out = work / f"impaired_{name}"
            for share in shares:
                hostile.overdriven(path, out, share)
                add(totals[share], compare(base.rows, process_capture(out, params).rows, base.params.range_bin_m))
            for impairment, entry in IMPAIRMENTS.items():
                make, options = entry if isinstance(entry, tuple) else (entry, {})
                make(path, out)
                add(others[impairment], compare(base.rows, process_capture(out, replace(params, **options)).rows,
                                                base.params.range_bin_m))
            out.unlink()
    print(f"{len(items)} captures ({len(SAMPLES)} bundled samples, {args.scenes} default-sweep scenes), {n_targets} "
          f"targets unclipped; {time.perf_counter() - start:.0f} s\n")
    print("| share clipped | images | highest image, dB under its target (ceiling) | their echo reads drone/bird | "
          "marked `clipping_image` | left drone/bird | targets whose class changed | values moved >3 % given `ok` | "
          "values compared |")
    print("|---|---|---|---|---|---|---|---|---|")
    for share in shares:
        t = totals[share]
        highest = "-" if t["highest_image_db"] is None else f"{t['highest_image_db']:.1f}"
        print(f"| {share:g} | {t['images']} | {highest} ({image_ceiling_db(share):.1f}) | {t['image_classes']} | "
              f"{t['marked']} | {t['image_classes_left']} | {t['class_changed']} | {t['moved_ok']} | {t['values']} |")
    print("\n| impairment | new detections | read drone/bird | targets whose class changed (withheld as the "
          "impairment's) | values moved >3 % given `ok` | values compared |")
    print("|---|---|---|---|---|---|")
    for impairment, t in others.items():
        print(f"| {impairment} | {t['images']} | {t['image_classes_left']} | {t['class_changed']} "
              f"({t['class_withheld']}) | {t['moved_ok']} | {t['values']} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
