"""Blade count and rotation where the blade count is not given, on echoes of the independent simulator
(benchmarks/offmodel): six kinds of multirotor scene, six draws each, built to tell whether the echo's line pattern
reads N right and where it is fooled.

- `unequal_aliased`: 4-6 rotors of 2 blades 0.5-2.5 % apart, one blade of each 1.5-1.9x the other, tips folded once
  (PRF 1.1-1.7 times the tip Doppler): the comb lines the turn rate, every second line standing out.
- `odd_aliased`: 4-6 rotors of 3 equal blades, tips folded once: flash times at twice the chopping comb.
- `unequal_drifting`: as `unequal_aliased`, unaliased (PRF 2.3-3 times the tip Doppler).
- `even_phased`: 4 rotors of 2 equal blades at exactly one rate, 45 deg apart: their phases cancel all but every
  fourth chopping line, as far as their echoes are alike.
- `odd_phased_aliased`, `odd_phased`: 2 rotors of 3 equal blades at exactly one rate, 60 deg apart (their chopping
  half a period apart: every second chopping line cancels as far as their echoes are alike), folded once or not.

Processed as a user would without `--blades` (the elevation given). Prints, per kind, how many rotation rates are
given `ok`, how many of those lie within 2 % of the rotors' mean, the confidently wrong ones (`ok`, off by more), and
how many are withheld or given under an assumed N; then every scene's row. The captures are kept in --workdir and
reused (about 3 min with -j 2 to simulate them all).
"""

import argparse
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "offmodel"))
import echo  # noqa: E402
import scenes  # noqa: E402

KINDS = ("unequal_aliased", "odd_aliased", "unequal_drifting", "even_phased", "odd_phased_aliased", "odd_phased")
DRAWS = 6
TOLERANCE = 0.02  # a rotation rate within this share of the rotors' mean is right


def scene(kind, draw):
    """The offmodel scene of ``kind``, draw ``draw`` (a dict for :func:`scenes.build`)."""
    rng = np.random.default_rng(10000 * KINDS.index(kind) + draw)
    band = str(rng.choice(["X", "K", "77"], p=[0.45, 0.4, 0.15]))
    lam_m = scenes.C / scenes.BANDS[band]
    blade_m = float(rng.uniform(0.08, 0.16))
    rate_hz = float(rng.uniform(40, 80)) / (2 * np.pi * blade_m)  # tips at 40-80 m/s
    beta_deg = float(rng.uniform(0, 35))
    n_blades = 3 if kind.startswith("odd") else 2
    if kind in ("unequal_aliased", "odd_aliased", "unequal_drifting"):
        n_rotors = int(rng.choice([4, 6]))
        spread = float(rng.uniform(0.005, 0.025))
        rates_hz = list(rate_hz * (1 + spread * np.linspace(-0.5, 0.5, n_rotors)))
        rng.shuffle(rates_hz)
        phases_rad = list(rng.uniform(0, 2 * np.pi, n_rotors))
    elif kind == "even_phased":
        n_rotors, rates_hz = 4, [rate_hz] * 4
        phases_rad = [k * np.pi / 4 + 0.1 for k in range(4)]
    else:
        n_rotors, rates_hz = 2, [rate_hz] * 2
        phases_rad = [0.2, 0.2 + np.pi / 3]
    gains = [1.0, float(rng.uniform(1.5, 1.9))] if kind.startswith("unequal") else [1.0] * n_blades
    tip_hz = 2 * 2 * np.pi * max(rates_hz) * blade_m * np.cos(np.deg2rad(beta_deg)) / lam_m
    prf_hz = float(rng.uniform(1.1, 1.7) if kind.endswith("aliased") else rng.uniform(2.3, 3.0)) * tip_hz
    ramp_s = min(30e-6, 0.9 / prf_hz)
    dwell_s = min(float(rng.uniform(0.3, 0.8)), 12000 / prf_hz)
    radar = scenes.make_radar(band, 150e6, 64, ramp_s, prf_hz, dwell_s, 1)
    position_m = np.array([float(rng.uniform(10, 25)), 0.0, 0.0])
    arm_m = 0.12 + 0.5 * blade_m
    rotors = [dict(offset=[arm_m * np.cos(2 * np.pi * k / n_rotors + np.pi / 4),
                           arm_m * np.sin(2 * np.pi * k / n_rotors + np.pi / 4), 0.0],
                   rate=float(rates_hz[k]), phase=float(phases_rad[k]),
                   pitch_deg=float(rng.uniform(-2, 2)), roll_deg=float(rng.uniform(-2, 2))) for k in range(n_rotors)]
    trajectory = echo.body_traj(position_m, np.zeros(3), 0.03, 0.8, rng.normal(size=3), 0.4)
    profile = str(rng.choice(["uniform", "tapered:0.6", "tipbright", "rough"]))
    drone = dict(kind="drone", traj=None, traj_fn=trajectory, body_amp=1.0, rotors=rotors, nbl=n_blades, r=blade_m,
                 beta=beta_deg, profile=profile, blade_amp=1.0, gains=gains)
    return dict(kind="drone", band=band, radar=radar, targets=[drone], snr=float(rng.choice([20.0, 10.0])),
                given_blades=False, given_el=True, clutter=False, seed=5000 + draw)


def run_scene(kind, draw, workdir):
    """Simulate (or reuse) and process one scene; (kind, draw, truth, the target's row)."""
    from mdpipe.params import ProcessParams
    from mdpipe.process.pipeline import process_capture

    path = Path(workdir) / f"{kind}_{draw}.h5"
    truth = scenes.capture(scene(kind, draw), str(path))
    row = process_capture(str(path), ProcessParams(elevation_deg=truth["beta"])).rows[0]
    keep = ("class", "rotation_rate_hz", "rotation_rate_hz_status", "chopping_freq_hz", "chopping_freq_hz_status",
            "n_blades", "n_blades_source")
    return kind, draw, truth, {k: row.get(k) for k in keep}


def verdict(truth, row):
    """right / wrong (given `ok`, within TOLERANCE of the mean rate or not) / withheld (a status, or no value)."""
    rate_hz = row["rotation_rate_hz"]
    if rate_hz is None or row["rotation_rate_hz_status"] != "ok":
        return "withheld"
    return "right" if abs(rate_hz / truth["rate"] - 1) <= TOLERANCE else "wrong"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workdir", required=True, help="where the captures are written (and reused)")
    parser.add_argument("-j", "--jobs", type=int, default=2)
    args = parser.parse_args()
    Path(args.workdir).mkdir(parents=True, exist_ok=True)
    jobs = [(kind, draw) for kind in KINDS for draw in range(DRAWS)]
    with ProcessPoolExecutor(args.jobs) as pool:
        results = list(pool.map(run_scene, *zip(*jobs), [args.workdir] * len(jobs)))
    print(f"{len(results)} multirotor scenes of benchmarks/offmodel, the blade count not given\n")
    print("| kind | scenes | rotation `ok` | right (2 %) | wrong | withheld or assumed N | N measured (right) |")
    print("|---|---|---|---|---|---|---|")
    for kind in KINDS:
        mine = [(truth, row) for k, _, truth, row in results if k == kind]
        verdicts = [verdict(truth, row) for truth, row in mine]
        measured = [(truth, row) for truth, row in mine if row["n_blades_source"] == "measured"]
        measured_right = sum(row["n_blades"] == truth["nbl"] for truth, row in measured)
        print(f"| `{kind}` | {len(mine)} | {len(mine) - verdicts.count('withheld')} | {verdicts.count('right')} | "
              f"{verdicts.count('wrong')} | {verdicts.count('withheld')} | {len(measured)} ({measured_right}) |")
    print()
    for kind, draw, truth, row in results:
        rate_hz = row["rotation_rate_hz"]
        shown = "-" if rate_hz is None else f"{rate_hz:.2f}"
        print(f"  {kind} {draw}: {truth['band']} N {truth['nbl']} at {truth['rate']:.2f} rev/s, PRF / tip Doppler "
              f"{truth['prf'] / truth['tip_hz']:.2f}: {row['class']}, rotation {shown} "
              f"({row['rotation_rate_hz_status']}), N {row['n_blades']} ({row['n_blades_source']}): "
              f"{verdict(truth, row)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
