"""mdpipe on I/Q recordings of CW radars it did not make: the scenes of benchmarks/offmodel (``make offmodel``)
recorded by a CW radar at the scene's PRF (benchmarks/offmodel/cw.py), through an anti-alias filter (a sound card's
or an SDR's: micro-Doppler beyond half the rate cut off) or sampled without one (folded, flashes shorter than a
sample caught only where a sample falls), processed as a user would (the blade count and elevation given where the
scene says so) and scored as ``make offmodel`` scores the FMCW captures of the same scenes (``bench_offmodel.score``,
its tolerances and its rules of what is measurable).

The SNR per I/Q sample is the FMCW capture's per slow-time sample, so that the two differ by what range adds: the
noise read from empty range bins, a range track, the ramp's parts and range sides, the in-bin share. Rendering all
380 scenes both ways takes about 15 min of one core; the recordings are kept in --workdir and reused.
"""

import argparse
import os
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent / "offmodel"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_offmodel  # noqa: E402
import cw  # noqa: E402
import scenes  # noqa: E402

KINDS = ("filtered", "sampled")
KEPT = ("class", "aliased", "snr_db", "notes", "rotor_rates_hz", "mains_hum_hz", *bench_offmodel.FEATURES,
        *(f + "_status" for f in bench_offmodel.FEATURES))
HUM_ORDERS = 39  # mains hum: the grid's 50 Hz and its harmonics to the 39th, each 1 / k of the fundamental


def record(sid, workdir, kind):
    """Scene ``sid`` recorded by a CW radar (``kind``: filtered or sampled) into ``workdir`` (reused when there);
    returns (path, scene, truth)."""
    scene = scenes.scene(sid)
    objects, truth = scenes.build(scene)
    path = Path(workdir) / f"s{sid:03d}_{kind}.h5"
    if not path.exists():
        samples, fs, fc, noise = cw.iq(scene, objects, truth, scene["seed"], filtered=kind == "filtered")
        partial = path.with_suffix(".part")
        cw.write(partial, samples, fs, fc, noise)
        os.replace(partial, path)
    return path, scene, truth


def with_hum(path, hum_db, *, seed):
    """The recording at ``path`` with mains hum added in I only (a sound card's pick-up: 50 Hz and its harmonics to
    the ``HUM_ORDERS``-th under 0.45 of the sample rate, each 1 / k of the fundamental, which stands ``hum_db`` over
    the noise power per sample; phases drawn with ``seed``), written beside it (reused when there); returns its
    path."""
    import h5py
    import numpy as np

    out = path.with_name(f"{path.stem}_hum{hum_db:g}.h5")
    if out.exists():
        return out
    with h5py.File(path, "r") as h5:
        samples, fs, fc, noise = h5["IQ"][...], h5.attrs["fs"], h5.attrs["fc"], h5.attrs["noise_power_v2"]
    t_s = np.arange(len(samples)) / fs
    phases = np.random.default_rng(seed).uniform(0, 2 * np.pi, HUM_ORDERS)
    amplitude = np.sqrt(noise * 10 ** (hum_db / 10))
    orders = range(1, min(HUM_ORDERS, int(0.45 * fs / 50.0)) + 1)  # the pick-up is analogue: filtered as the echo is
    hum = sum(amplitude / k * np.cos(2 * np.pi * 50.0 * k * t_s + phases[k - 1]) for k in orders)
    partial = out.with_suffix(".part")
    cw.write(partial, samples + hum.reshape((-1,) + (1,) * (samples.ndim - 1)), fs, fc, noise)
    os.replace(partial, out)
    return out


def run_scene(sid, workdir, kind="filtered", hum_db=None, mains_hz="auto"):
    """Record scene ``sid`` (or reuse it), with mains hum ``hum_db`` over its noise if given, and process it (hum
    searched as ``mains_hz`` says): (sid, description, truth, row, classes), as ``bench_offmodel.run_scene`` returns
    for the FMCW capture."""
    from mdpipe.params import ProcessParams
    from mdpipe.process.pipeline import process_capture

    path, scene, truth = record(sid, workdir, kind)
    if hum_db is not None:
        path = with_hum(path, hum_db, seed=sid)
    given = {"mains_hz": mains_hz}
    if scene["given_blades"]:
        given["n_blades"] = truth["nbl"]
    if scene["given_el"] and scene["kind"] == "drone":
        given["elevation_deg"] = truth["beta"]
    row = process_capture(str(path), ProcessParams(**given)).rows[0]
    return sid, scenes.describe(scene, truth), truth, {k: row.get(k) for k in KEPT}, [row["class"]]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workdir", required=True, help="where the recordings are written (and reused)")
    parser.add_argument("--scenes", default=f"0-{bench_offmodel.N_SCENES - 1}", help="scene ids, e.g. 0-379")
    parser.add_argument("--kinds", default=",".join(KINDS), help="filtered, sampled or both")
    parser.add_argument("-j", "--jobs", type=int, default=2)
    parser.add_argument("--hum-db", type=float, default=None,
                        help="add mains hum (50 Hz and harmonics, in I only) this far over the noise to each recording")
    parser.add_argument("--mains-hz", default="auto", help="mdpipe's --mains-hz (none: hum not searched)")
    args = parser.parse_args()
    Path(args.workdir).mkdir(parents=True, exist_ok=True)
    ids = bench_offmodel.parse_ids(args.scenes)
    for kind in args.kinds.split(","):
        with ProcessPoolExecutor(args.jobs) as pool:
            results = sorted(pool.map(run_scene, ids, [args.workdir] * len(ids), [kind] * len(ids),
                                      [args.hum_db] * len(ids), [args.mains_hz] * len(ids)), key=lambda r: r[0])
        hum = "" if args.hum_db is None else f", mains hum {args.hum_db:g} dB over the noise added"
        hum += "" if args.mains_hz == "auto" else f", --mains-hz {args.mains_hz}"
        print(f"## CW recordings, {kind}{hum}: {len(results)} scenes of benchmarks/offmodel\n")
        bench_offmodel.report(results)
        given, right = undersampled(results)
        print(f"\nrotation given `undersampled` (the span too narrow for the tips): {given}, of them within "
              f"{bench_offmodel.TOLERANCE['rotation_rate_hz']:.0%}: {right}")
        found = sum(row["mains_hum_hz"] is not None for _, _, _, row, _ in results)
        print(f"mains hum found (`mains_hum_hz`): {found} of {len(results)}\n")
    return 0


def undersampled(results):
    """How many rotation rates ``results`` give as `undersampled`, and how many of those lie within the tolerance."""
    rows = [(row, truth) for _, _, truth, row, _ in results
            if row["rotation_rate_hz_status"] == "undersampled" and row["rotation_rate_hz"] is not None]
    right = sum(not bench_offmodel.wrong("rotation_rate_hz", row["rotation_rate_hz"], truth) for row, truth in rows)
    return len(rows), right


if __name__ == "__main__":
    sys.exit(main())
