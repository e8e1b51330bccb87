"""mdpipe on echoes it did not make: the scenes of benchmarks/offmodel (an FMCW simulator written apart from
mdpipe's, blades as strips of points lambda / 8 apart, tapered, tip-bright or rough, rotors equal or apart, tilts,
imbalance, bodies, flapping birds, clutter, 4 bands, SNR -5 to 20 dB per IF sample), processed as a user would
(the blade count and elevation given where the scene says so), scored against the scene's truth.

Prints the class confusion, each feature's coverage (scenes where the simple rules below say it is measurable,
values given `ok`, and of those within tolerance), the rotation's coverage per band, and every confidently wrong value:
`ok` but off by more than the tolerance (rotation and chopping 2 %, blade length 5 %, wingbeat 3 %, body velocity
0.3 m/s), or given for a quantity the target does not have (a rotor rate of a bird). Measurable: a drone at SNR >= 0
dB holding 3 turns of its slowest rotor, chopping under PRF / 2 (rotation: N given; blade length also beta given <= 45
deg and the tips unaliased); a body that moves, its Doppler under PRF / 2; a bird at SNR >= 0 dB beating 3 times.

Simulating all 380 scenes takes about 30 min of one core; the captures are kept in --workdir and a capture found
there is reused (delete them after changing benchmarks/offmodel).
"""

import argparse
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent / "offmodel"))
import scenes  # noqa: E402

TOLERANCE = {"rotation_rate_hz": 0.02, "chopping_freq_hz": 0.02, "blade_length_m": 0.05, "wingbeat_freq_hz": 0.03}
BODY_TOLERANCE_MPS = 0.3
FEATURES = ("rotation_rate_hz", "chopping_freq_hz", "blade_length_m", "body_velocity_mps", "wingbeat_freq_hz")
TRUTH_KEY = {"rotation_rate_hz": "rate", "chopping_freq_hz": "chop", "blade_length_m": "r",
             "body_velocity_mps": "body_v", "wingbeat_freq_hz": "wb"}
N_SCENES = 380


def run_scene(sid, workdir):
    """Simulate scene ``sid`` (or reuse its capture in ``workdir``), process it; (sid, description, truth, the row
    nearest the scene's target in range, the class of every row)."""
    from mdpipe.params import ProcessParams
    from mdpipe.process.pipeline import process_capture

    scene = scenes.scene(sid)
    path = Path(workdir) / f"s{sid:03d}.h5"
    truth = scenes.capture(scene, str(path))
    given = {}
    if scene["given_blades"]:
        given["n_blades"] = truth["nbl"]
    if scene["given_el"] and scene["kind"] == "drone":
        given["elevation_deg"] = truth["beta"]
    rows = process_capture(str(path), ProcessParams(**given)).rows
    near = [r for r in rows if r.get("range_m") is not None]
    row = min(near, key=lambda r: abs(r["range_m"] - truth.get("range0", 0.0))) if near else rows[0]
    keep = ["class", *FEATURES, *(f + "_status" for f in FEATURES)]
    return sid, scenes.describe(scene, truth), truth, {k: row.get(k) for k in keep}, [r.get("class") for r in rows]


def measurable(truth):
    """Which features the scene's truth says can be measured (the module's simple rules)."""
    kind, prf_hz = truth["kind"], truth["prf"]
    loud = truth["snr"] >= 0
    body_hz = abs(2 * truth.get("body_v", 0.0) / truth["lam"])
    out = dict.fromkeys(FEATURES, False)
    if kind == "drone":
        rotation = truth["given_blades"] and loud and truth["dwell"] * min(truth["rates"]) >= 3 \
            and truth["chop"] < prf_hz / 2
        out.update(rotation_rate_hz=rotation, chopping_freq_hz=loud and truth["chop"] < prf_hz / 2,
                   blade_length_m=rotation and truth["given_el"] and truth["beta"] <= 45
                   and truth["tip_hz"] + body_hz < prf_hz / 2)
    out["body_velocity_mps"] = kind != "none" and truth.get("body_moves", False) and loud and body_hz < prf_hz / 2
    out["wingbeat_freq_hz"] = kind == "bird" and loud and truth["wb"] * truth["dwell"] >= 3
    return out


def wrong(feature, value, truth):
    """Whether a value given `ok` is confidently wrong against ``truth`` (None: the target has no such quantity)."""
    expected = truth.get(TRUTH_KEY[feature])
    if expected is None:
        return feature != "body_velocity_mps"
    if feature == "body_velocity_mps":
        return abs(value - expected) > BODY_TOLERANCE_MPS
    return abs(value / expected - 1) > TOLERANCE[feature]


def _added(counts, more):
    """Counts added element by element."""
    return [a + b for a, b in zip(counts, more)]


def score(results):
    """(confusion counts, coverage per feature [measurable, ok, ok and right], the rotation's coverage per band (the
    description's first word), confidently wrong entries)."""
    confusion = {}
    coverage = {f: [0, 0, 0] for f in FEATURES}
    rotation_by_band = {}
    bad = []
    for sid, description, truth, row, classes in results:
        measured = row["class"] if truth["kind"] != "none" else ("none" if set(classes) <= {"none"} else "drone")
        confusion[(truth["kind"], measured)] = confusion.get((truth["kind"], measured), 0) + 1
        if measured != truth["kind"]:
            bad.append((sid, "class", measured, truth["kind"], description))
        can = measurable(truth)
        for feature in FEATURES:
            value, status = row[feature], row[feature + "_status"]
            confident = value is not None and status == "ok" and not isinstance(value, list)
            off = confident and wrong(feature, value, truth)
            if can[feature]:
                counts = [1, int(confident), int(confident and not off)]
                coverage[feature] = _added(coverage[feature], counts)
                if feature == "rotation_rate_hz":
                    band = description.split()[0]
                    rotation_by_band[band] = _added(rotation_by_band.get(band, [0, 0, 0]), counts)
            if off:
                bad.append((sid, feature, value, truth.get(TRUTH_KEY[feature]), description))
    return confusion, coverage, rotation_by_band, bad


def parse_ids(text):
    ids = []
    for part in text.split(","):
        first, _, last = part.partition("-")
        ids.extend(range(int(first), int(last or first) + 1))
    return ids


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workdir", required=True, help="where the captures are written (and reused)")
    parser.add_argument("--scenes", default=f"0-{N_SCENES - 1}", help="scene ids, e.g. 0-379 or 31,112,124")
    parser.add_argument("-j", "--jobs", type=int, default=2)
    parser.add_argument("--rows", type=Path, help="also write each scene's row and truth here (CSV): two versions "
                        "of mdpipe compared scene by scene")
    args = parser.parse_args()
    if args.rows and not args.rows.parent.is_dir():
        parser.error(f"--rows {args.rows}: its folder does not exist; make it first")
    Path(args.workdir).mkdir(parents=True, exist_ok=True)
    ids = parse_ids(args.scenes)
    with ProcessPoolExecutor(args.jobs) as pool:
        results = sorted(pool.map(run_scene, ids, [args.workdir] * len(ids)), key=lambda r: r[0])
    print(f"{len(results)} scenes of benchmarks/offmodel\n")
    report(results)
    if args.rows:
        write_rows(results, args.rows)
    return 0


def write_rows(results, path):
    """One CSV row per scene: its id, description, the truth of each feature (``truth_<feature>``), whether the simple
    rules call it measurable, and the class, value and status read; written whole or not at all."""
    import pandas as pd

    from mdpipe.report.tables import atomic_write

    rows = []
    for sid, description, truth, row, classes in results:
        can = measurable(truth)
        rows.append({"scene": sid, "description": description, "kind": truth["kind"],
                     "classes": " ".join(map(str, classes)),
                     **{f"truth_{f}": truth.get(TRUTH_KEY[f]) for f in FEATURES},
                     **{f"measurable_{f}": can[f] for f in FEATURES}, **row})
    atomic_write(path, lambda tmp: pd.DataFrame(rows).to_csv(tmp, index=False))


def report(results):
    """Print the tables of :func:`score` of ``results`` and every confidently wrong entry."""
    confusion, coverage, rotation_by_band, bad = score(results)
    kinds = ("drone", "bird", "none")
    print("| expected (rows), measured (columns) | " + " | ".join(kinds) + " |")
    print("|---|" + "---|" * len(kinds))
    for kind in kinds:
        print(f"| {kind} | " + " | ".join(str(confusion.get((kind, m), 0)) for m in kinds) + " |")
    print("\n| feature | measurable | given ok | ok and within tolerance |\n|---|---|---|---|")
    for feature, (can, given, right) in coverage.items():
        print(f"| `{feature}` | {can} | {given} ({given / max(can, 1):.0%}) | {right} ({right / max(can, 1):.0%}) |")
    print("\n| `rotation_rate_hz` by band | measurable | given ok | ok and within tolerance |\n|---|---|---|---|")
    by_frequency = sorted(rotation_by_band.items(), key=lambda item: scenes.BANDS.get(item[0], float("inf")))
    for band, (can, given, right) in by_frequency:
        print(f"| {band} | {can} | {given} ({given / max(can, 1):.0%}) | {right} ({right / max(can, 1):.0%}) |")
    values = [b for b in bad if b[1] != "class"]
    print(f"\nconfidently wrong: {len(values)} values, {len(bad) - len(values)} wrong classes")
    for sid, what, value, expected, description in bad:
        shown = value if isinstance(value, str) or value is None else f"{value:.4g}"
        truth_shown = expected if isinstance(expected, str) or expected is None else f"{expected:.4g}"
        print(f"  s{sid:03d} {what}: {shown} for {truth_shown} ({description})")


if __name__ == "__main__":
    sys.exit(main())
