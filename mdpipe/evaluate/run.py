"""Simulate, process and score every drawn scene, on ``jobs`` processes."""

import os
import shutil
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import yaml
from threadpoolctl import threadpool_limits

from mdpipe.errors import MdpipeError
from mdpipe.evaluate import captures, scoring
from mdpipe.params import ProcessParams

SCENES_DIR = "scenes"
CAPTURES_DIR = "captures"


def process_params(process):
    """:class:`ProcessParams` for a scene's ``process`` keywords, and whether the blade count was given
    (``given``) or left to the echo (``auto``)."""
    return ProcessParams(**process), "auto" if process.get("n_blades") is None else "given"


def write_scene_yaml(path, draw):
    """The drawn scene as a scene YAML with the command lines that rerun it."""
    options = ""
    if draw.process.get("n_blades") is not None:
        options += f" --blades {draw.process['n_blades']}"
    if "elevation_deg" in draw.process:
        options += f" --elevation-deg {draw.process['elevation_deg']:g}"
    header = [f"# family {draw.family}, band {draw.band}. Rerun:",
              f"#   mdpipe simulate --config {path.name} -o {draw.name}.h5",
              f"#   mdpipe process {draw.name}.h5{options}"]
    path.write_text("\n".join(header) + "\n" + yaml.safe_dump(draw.scene, sort_keys=False), encoding="utf-8")


def score_scene(draw, scene, truth, rows, *, process):
    """Scored records of one scene: its subject target (or, without one, the capture's first row) and
    every other detection, which should not exist (expected class none, nothing estimable).

    ``truth`` is what :func:`mdpipe.simulate.run.simulate_to_file` returns (the ``/Truth`` expected
    features with its ``simulation`` block).
    """
    radar = truth["radar"]
    base = scoring.Physics(kind="none", expected_class="none", dwell_s=radar["duration_s"],
                           prf_hz=1.0 / scene.radar.chirp_period_s)
    subject = next((i for i, t in enumerate(scene.targets) if t.kind != "static"), None)
    if subject is None:
        detected = [r for r in rows if r.get("range_m") is not None]
        physics, match, extra, track = base, (detected[0] if detected else None), detected[1:], None
    else:
        track = truth["targets"][subject]
        physics = scoring.physics_of(subject, track, scene=scene,
                                     noise_sigma_v=truth["simulation"]["noise_sigma_v"], process=process)
        match, extra = scoring.match_rows(rows, range_min_m=track["range_m"]["min"],
                                          range_max_m=track["range_m"]["max"],
                                          range_mean_m=track["range_m"]["mean"],
                                          tolerance_m=max(3 * radar["range_bin_m"], 1.0))
    records = [{"target": "subject", "kind": physics.kind, "blade_profile": track and track.get("blade_profile"),
                "true_range_m": track and track["range_m"]["mean"],
                "range_m": match and match["range_m"], "micro_line_snr_db": physics.micro_line_snr_db,
                "micro_bin_share": physics.micro_bin_share,
                "body_line_snr_db": physics.body_line_snr_db, **scoring.score_row(physics, match)}]
    ghost = scoring.Physics(kind="ghost", expected_class="none", dwell_s=base.dwell_s, prf_hz=base.prf_hz)
    for i, row in enumerate(extra):
        scored = scoring.score_row(ghost, row)
        scored.update({f"{feature}_why": "no_target" for feature in scoring.FEATURES})
        records.append({"target": f"extra{i}", "kind": "ghost", "true_range_m": None, "range_m": row["range_m"],
                        **scored})
    return records


def run_scene(draw, out_dir, keep_captures=False, reuse_dir=None):
    """Simulate, process and score one drawn scene (:func:`mdpipe.evaluate.sweep.draw_scene` has had the
    simulator accept it); a list of record dicts (see :func:`score_scene`).

    With ``reuse_dir`` (a folder :func:`mdpipe.evaluate.captures.check_reusable` accepted) the scene's capture kept
    there is processed instead, where it was simulated from this very scene (:func:`captures.kept_truth`); its
    ``simulate_s`` is 0 and ``reused`` True; a kept ``/Truth`` that cannot be scored raises :class:`MdpipeError`
    naming the file.

    A capture the processing fails on (any exception: the benchmark measures the processing, it does
    not stop at its first failure) is recorded with the error and counts as a wrong class.
    """
    from mdpipe.process.pipeline import process_capture
    from mdpipe.simulate.run import simulate_to_file
    from mdpipe.simulate.scene import scene_from_mapping, scene_to_yaml

    out_dir = Path(out_dir)
    write_scene_yaml(out_dir / SCENES_DIR / f"{draw.name}.yaml", draw)
    capture = out_dir / CAPTURES_DIR / f"{draw.name}.h5"
    scene = scene_from_mapping(draw.scene)
    params, blades_source = process_params(draw.process)
    common = {"scene": draw.name, "family": draw.family, "band": draw.band,
              "wavelength_m": scene.radar.params.wavelength_m, "prf_hz": scene.radar.params.prf_hz,
              "n_chirps": scene.radar.n_chirps, "dwell_s": scene.radar.params.duration_s(scene.radar.n_chirps),
              "n_blades_given": draw.process.get("n_blades"), "n_blades_source": blades_source,
              "elevation_given": "elevation_deg" in draw.process}
    scene_yaml = scene_to_yaml(draw.scene)
    kept = reuse_dir and captures.kept_truth(Path(reuse_dir) / capture.name, scene_yaml)
    if kept:
        capture = Path(reuse_dir) / capture.name  # read in place, never removed
    with threadpool_limits(limits=1):
        start = time.perf_counter()
        truth = kept or simulate_to_file(scene, capture, scene_yaml=scene_yaml)
        simulated = start if kept else time.perf_counter()
        try:
            rows, error = process_capture(capture, params).rows, ""
        except Exception as exc:  # noqa: BLE001 - the benchmark records a failing capture and goes on
            rows, error = [], f"{type(exc).__name__}: {exc}"
        processed = time.perf_counter()
    if kept and keep_captures:
        shutil.copyfile(capture, out_dir / CAPTURES_DIR / capture.name)
    elif not kept and not keep_captures:
        os.remove(capture)
    timing = {"simulate_s": simulated - start, "process_s": processed - simulated, "reused": bool(kept),
              "error": error}
    try:
        scored = score_scene(draw, scene, truth, rows, process=draw.process)
    except Exception as exc:  # noqa: BLE001 - a kept file's truth, whatever fails in it, is named
        if not kept:
            raise
        raise MdpipeError(f"{capture}: its /Truth cannot be scored ({type(exc).__name__}: {exc}); delete the file to "
                          "have its scene simulated anew") from None
    records = [{**common, **record, **timing} for record in scored]
    if error:  # a capture that could not be processed counts as a wrong class
        records[0].update(measured_class="error", class_ok=False)
    return records


def run_all(draws, out_dir, *, jobs=1, keep_captures=False, reuse_dir=None):
    """Records of every drawn scene, in scene order; ``jobs`` worker processes.

    ``out_dir/scenes/`` and ``out_dir/captures/`` are emptied of scene and capture files first, so that they hold
    exactly this run's; kept captures are marked with the digest of the simulator's code taken as the run starts,
    where the code still has it as the run ends (:func:`captures.mark_simulator`).
    ``reuse_dir``: another run's kept captures, processed again where they are this sweep's scenes (checked first:
    :func:`captures.check_reusable`).
    """
    out_dir = Path(out_dir)
    # the code that simulates this run, and must have simulated the captures it reuses
    digest = captures.simulator_digest() if keep_captures or reuse_dir is not None else None
    if reuse_dir is not None:
        captures.check_reusable(reuse_dir, out_dir / CAPTURES_DIR, digest)
    for sub in (SCENES_DIR, CAPTURES_DIR):
        (out_dir / sub).mkdir(parents=True, exist_ok=True)
    stale = list((out_dir / SCENES_DIR).glob("*.yaml")) + list((out_dir / CAPTURES_DIR).glob("*.h5"))
    for path in stale:  # scenes.csv will describe this run's scenes only
        path.unlink()
    (out_dir / CAPTURES_DIR / captures.SIMULATOR_FILE).unlink(missing_ok=True)
    args = [(draw, out_dir, keep_captures, reuse_dir) for draw in draws]
    if jobs == 1:
        results = [run_scene(*a) for a in args]
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            results = list(pool.map(run_scene, *zip(*args)))
    if keep_captures:
        captures.mark_simulator(out_dir / CAPTURES_DIR, digest)
    else:
        try:
            (out_dir / CAPTURES_DIR).rmdir()
        except OSError:
            pass
    return [record for records in results for record in records]
