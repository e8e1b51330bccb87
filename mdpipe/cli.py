"""The ``mdpipe`` command line: thin click commands that parse, call the library and write."""

import contextlib
import json
import signal
import sys
from pathlib import Path

import click

from mdpipe import __version__
from mdpipe.errors import MdpipeError
from mdpipe.io import open_capture
from mdpipe.io.radarlog import ATTRIBUTES
from mdpipe.params import RANGE_WINDOWS, FigureParams, ProcessParams

PROGRESS_MIN_SAMPLES = 1 << 25


class InputError(click.ClickException):
    """Bad input named in one line; exit code 2."""

    exit_code = 2


class BladeCount(click.ParamType):
    """``auto`` (None) or a whole number of blades >= 1."""

    name = "auto|N"

    def convert(self, value, param, ctx):
        if value is None or value == "auto":
            return None
        try:
            count = int(value)
        except (TypeError, ValueError):
            count = 0
        if count < 1 or str(count) != str(value).strip():
            self.fail(f"{value!r} is neither auto nor a whole number of blades >= 1", param, ctx)
        return count


class Group(click.Group):
    """Turns :class:`MdpipeError` into a one-line message and exit code 2, with no traceback."""

    def invoke(self, ctx):
        try:
            return super().invoke(ctx)
        except MdpipeError as exc:
            raise InputError(str(exc)) from None


@contextlib.contextmanager
def terminate_as_exit():
    """Inside, SIGTERM unwinds like Ctrl-C (``SystemExit(143)``), so temporary files are removed on the way out."""
    def handler(signum, frame):
        raise SystemExit(128 + signum)

    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def attribute_overrides(func):
    """Options that supply or replace a capture's chirp attributes (``--tp 64e-6`` ...)."""
    for name, (_field, meaning, _example) in reversed(ATTRIBUTES.items()):
        kind = int if name in ("N", "NrChn") else float
        func = click.option(f"--{name.lower()}", name, type=kind, default=None,
                            help=f"Use this {meaning} instead of the file's {name!r} attribute.")(func)
    frame_counter = click.option(
        "--frame-counter", type=click.Choice(["auto", "yes", "no"]), default="auto", show_default=True,
        help="Whether sample 0 of every chirp is a frame counter to drop.")
    allow_external = click.option(
        "--allow-external", is_flag=True,
        help="Trusted files only: read samples that an HDF5 external link, virtual dataset or external raw "
             "storage keeps in other files (refused by default).")
    return allow_external(frame_counter(func))


def reader_options(options):
    """``frame_counter``, ``overrides`` and ``allow_external`` for :func:`mdpipe.io.open_capture` from the
    :func:`attribute_overrides` options."""
    overrides = {name: options[name] for name in ATTRIBUTES if options[name] is not None}
    return {"frame_counter": {"auto": "auto", "yes": True, "no": False}[options["frame_counter"]],
            "overrides": overrides, "allow_external": options["allow_external"]}


def open_with_overrides(path, options):
    """Open ``path`` with the values of the :func:`attribute_overrides` options in ``options``."""
    return open_capture(path, **reader_options(options))


@click.group(cls=Group)
@click.version_option(__version__, prog_name="mdpipe")
def main():
    """Radar micro-Doppler analysis of drones and birds from Radarlog FMCW captures."""


@main.command()
@click.option("--config", "config_path", required=True, type=click.Path(dir_okay=False, path_type=Path),
              help="Scene YAML (see configs/).")
@click.option("-o", "--out", "out_path", type=click.Path(dir_okay=False, path_type=Path),
              help="Output capture [default: <config name>.h5 here].")
@click.option("--seed", type=int, help="Random seed (noise).")
@click.option("--chirps", type=click.IntRange(min=1), help="Override radar.n_chirps.")
@click.option("--channels", type=click.IntRange(1, 16), help="Override radar.n_channels.")
@click.option("--snr-db", type=float, help="Override noise: per-sample SNR of the moving targets, dB.")
@click.option("--force", is_flag=True, help="Replace an existing output file (never the config itself).")
@click.option("--max-memory-gb", type=click.FloatRange(min=0, min_open=True), default=2.0, show_default=True,
              help="Refuse a scene whose planned memory exceeds this (GiB).")
def simulate(config_path, out_path, seed, chirps, channels, snr_db, force, max_memory_gb):
    """Simulate the scene in CONFIG and write a Radarlog capture with its expected answer.

    The capture is written under a hidden temporary name beside the output and renamed when complete;
    on an error, Ctrl-C or SIGTERM nothing is left behind.
    """
    from mdpipe.simulate.plausibility import scene_warnings
    from mdpipe.simulate.run import check_output, simulate_to_file
    from mdpipe.simulate.scene import load_scene_mapping, scene_from_mapping, scene_to_yaml

    data = load_scene_mapping(config_path)
    if isinstance(data, dict) and isinstance(data.get("radar"), dict):
        if chirps is not None:
            data["radar"]["n_chirps"] = chirps
        if channels is not None:
            data["radar"]["n_channels"] = channels
    if isinstance(data, dict):
        if seed is not None:
            data["seed"] = seed
        if snr_db is not None:
            data["noise"] = {"snr_db": snr_db}
    scene = scene_from_mapping(data)
    for warning in scene_warnings(scene):
        click.echo(f"warning: {warning}", err=True)
    out_path = out_path or Path(config_path.stem + ".h5")
    if out_path.exists() and config_path.exists() and out_path.samefile(config_path):
        raise InputError(f"{out_path}: is the config file itself; choose another -o")
    radar = scene.radar
    total = radar.n_chirps * radar.n_samples * radar.n_channels
    yaml_text = scene_to_yaml(data)
    options = dict(overwrite=force, max_memory_gb=max_memory_gb)
    check_output(scene, out_path, **options)  # before the progress bar shows
    try:
        with terminate_as_exit():
            if total >= PROGRESS_MIN_SAMPLES:
                with click.progressbar(length=radar.n_chirps, label=f"simulating {out_path.name}",
                                       file=sys.stderr) as bar:
                    truth = simulate_to_file(scene, out_path, scene_yaml=yaml_text, progress=bar.update, **options)
            else:
                truth = simulate_to_file(scene, out_path, scene_yaml=yaml_text, **options)
    except FileExistsError:
        raise InputError(f"{out_path}: appeared while simulating; pass --force to replace it") from None
    except OSError as exc:
        raise InputError(f"{out_path}: cannot be written ({exc.strerror or exc})") from None
    sim = truth["simulation"]
    click.echo(f"wrote {out_path}: {radar.n_chirps} chirps x {radar.n_samples} samples x {radar.n_channels} RX, "
               f"noise sigma {sim['noise_sigma_v']:.3g} V, {sim['clipped_samples']} samples clipped")


def _format_truth(expected):
    lines = []
    for t in expected.get("targets", []):
        head = f"  {t['name']} ({t['kind']}): range {t['range_m']['mean']:.2f} m (bin {t['range_bin']}), " \
               f"range rate {t['range_rate_mps']['mean']:+.2f} m/s"
        lines.append(head)
        if t["kind"] == "multirotor":
            lines.append(f"    {t['n_rotors']} rotors x {t['n_blades']} blades, r = {t['blade_length_m']} m, "
                         f"beta = {t['elevation_deg']} deg, {t['rotation_rate_hz']:.2f} rev/s, "
                         f"chopping {t['chopping_freq_hz']:.1f} Hz, flash period {t['flash_period_s'] * 1e3:.3f} ms")
            lines.append(f"    Eq. 6 bandwidth {t['doppler_bw_hz']:.0f} Hz ({t['doppler_bw_mps']:.2f} m/s), "
                         f"tip Doppler +-{t['tip_doppler_hz']:.0f} Hz, aliased: {t['aliased']}")
        elif t["kind"] == "bird":
            lines.append(f"    wingbeat {t['wingbeat_freq_hz']:.3g} Hz, micro-Doppler spread "
                         f"{t['micro_doppler_spread_hz']:.1f} Hz, aliased: {t['aliased']}")
        model = t["model"]
        lines.append(f"    model: {model['nodes_per_chirp']} node(s) per chirp "
                     f"({model['in_chirp_cycles']:.3g} cycles in a ramp), range migration "
                     f"{'on' if model['range_migration'] else 'off'} ({model['travel_bins']:.3g} bins)")
    return lines


@main.command()
@click.argument("capture", type=click.Path(dir_okay=False, path_type=Path))
@attribute_overrides
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of text.")
def info(capture, as_json, **options):
    """Print the layout, parameters and derived quantities of CAPTURE (and its truth, if simulated)."""
    with open_with_overrides(capture, options) as cap:
        p, n = cap.params, cap.n_chirps
        derived = {
            "range_bin_m": p.range_bin_m, "max_range_m": p.max_range_m, "wavelength_m": p.wavelength_m,
            "doppler_span_hz": p.doppler_span_hz, "velocity_span_mps": p.velocity_span_mps,
            "duration_s": p.duration_s(n), "n_chirps": n, "n_channels": p.n_channels, "n_samples": p.n_samples,
        }
        if as_json:
            from mdpipe.report.tables import finite_json

            click.echo(json.dumps(finite_json({"file": str(capture), "layout": cap.layout.describe(),
                                               "params": p.__dict__, "derived": derived,
                                               "truth": cap.truth and cap.truth["expected"],
                                               "warnings": cap.warnings}), allow_nan=False))
            return
        click.echo(f"{capture}")
        click.echo(f"  layout: {cap.layout.describe()}")
        click.echo(f"  chirp: {p.f_start_hz / 1e9:.4f}-{p.f_stop_hz / 1e9:.4f} GHz "
                   f"({p.bandwidth_hz / 1e6:.4g} MHz) in {p.ramp_up_s * 1e6:.4g} us, Tp {p.chirp_period_s * 1e6:.4g} us, "
                   f"fs {p.sample_rate_hz / 1e6:.4g} MHz, N {p.n_samples}, FuSca {p.full_scale_v_per_lsb:.4g} V/LSB")
        click.echo(f"  capture: {n} chirps x {p.n_channels} RX = {derived['duration_s']:.4g} s")
        click.echo(f"  range bin {p.range_bin_m:.4g} m, max range {p.max_range_m:.5g} m")
        click.echo(f"  Doppler span {p.doppler_span_hz:.6g} Hz (+-{p.doppler_span_hz / 2:.6g} Hz) = "
                   f"{p.velocity_span_mps:.4g} m/s at lambda {p.wavelength_m * 1e3:.4g} mm")
        for warning in cap.warnings:
            click.echo(f"  note: {warning}")
        if cap.truth:
            try:
                lines = _format_truth(cap.truth["expected"])
            except (KeyError, TypeError, ValueError, IndexError) as exc:
                lines = [f"  (not in the simulator's form: {type(exc).__name__} {exc}; see info --json)"]
            click.echo("  truth (simulated):")
            for line in lines:
                click.echo(line)


@main.command()
@click.argument("captures", nargs=-1, required=True, type=click.Path(dir_okay=False, path_type=Path))
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path), default=Path("."),
              show_default=True, help="Folder for tables and figures.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object per target on stdout.")
@click.option("--no-figures", is_flag=True, help="Write the tables only.")
@click.option("--range-m", type=click.FloatRange(min=0, min_open=True), help="Analyse this range instead of detecting.")
@click.option("--min-range-m", type=float, default=ProcessParams.min_range_m, show_default=True)
@click.option("--max-range-m", type=float, default=ProcessParams.max_range_m, show_default=True)
@click.option("--max-targets", type=click.IntRange(min=1), default=ProcessParams.max_targets, show_default=True)
@click.option("--elevation-deg", type=click.FloatRange(-90, 90), default=None,
              help="Elevation beta of the rotor plane (Eq. 6) [not given: 0 assumed, and blade_length_m_status says so].")
@click.option("--blades", "n_blades", type=BladeCount(), default="auto", show_default=True,
              help="Blades per rotor (N), or auto: measured where the echo tells it, else assumed and said so.")
@click.option("--threshold-db", type=float, default=ProcessParams.threshold_db, show_default=True,
              help="The paper's bandwidth rule: spectrum above its mean by this much.")
@click.option("--range-window", type=click.Choice(RANGE_WINDOWS), default=ProcessParams.range_window, show_default=True)
@click.option("--zero-pad", type=click.IntRange(1, 16), default=ProcessParams.zero_pad, show_default=True)
@click.option("--stft-window-s", type=click.FloatRange(min=0, min_open=True), help="Spectrogram window [from physics].")
@click.option("--stft-hop-s", type=click.FloatRange(min=0, min_open=True), help="Spectrogram hop [window / 4].")
@click.option("--max-memory-gb", type=click.FloatRange(min=0, min_open=True), default=ProcessParams.max_memory_gb,
              show_default=True, help="Refuse a capture whose planned memory exceeds this (GiB).")
@click.option("--doppler-limits", default="auto", show_default=True,
              help="Doppler axis of the figures: auto (the occupied band), full (+-PRF/2) or LOW,HIGH in Hz.")
@attribute_overrides
def process(captures, out_dir, as_json, no_figures, doppler_limits, **options):
    """Detect targets in each CAPTURE, measure their micro-Doppler features, call drone / bird / none.

    Writes <stem>.features.csv, <stem>.run.json and <stem>_range.png, _spectrogram.png, _spectrum.png
    into --out. A capture that cannot be processed is reported on one line and in <stem>.error.txt;
    the others go on; the exit code is 2 if any failed.
    """
    from mdpipe.process.pipeline import process_capture
    from mdpipe.report import tables

    reader = reader_options(options)
    params = ProcessParams(**{k: v for k, v in options.items() if k in ProcessParams.__dataclass_fields__})
    figure_params = FigureParams.from_text(doppler_limits)
    out_dir.mkdir(parents=True, exist_ok=True)
    failed = 0
    for capture in captures:
        stem = out_dir / capture.stem
        try:
            result = process_capture(capture, params, **reader)
            tables.write_features_csv(result.rows, stem.with_name(stem.name + tables.FEATURES_SUFFIX))
            tables.write_run_json(stem.with_name(stem.name + ".run.json"), capture=capture, params=params,
                                  layout=result.layout, radar=result.params)
            if not no_figures:
                from mdpipe.report import plots

                plots.range_figure(result, stem.with_name(stem.name + "_range.png"))
                if result.analyses:
                    plots.spectrogram_figure(result, stem.with_name(stem.name + "_spectrogram.png"), figure_params)
                    plots.spectrum_figure(result, stem.with_name(stem.name + "_spectrum.png"), figure_params)
            error_file = stem.with_name(stem.name + tables.ERROR_SUFFIX)
            if error_file.exists():
                error_file.unlink()
        except (MdpipeError, OSError) as exc:
            failed += 1
            message = str(exc) if str(capture) in str(exc) else f"{capture}: {exc}"
            click.echo(f"Error: {message}", err=True)
            tables.write_error(stem.with_name(stem.name + tables.ERROR_SUFFIX), capture, message)
            continue
        for row in result.rows:
            if as_json:
                click.echo(json.dumps(tables.json_record(row)))
            else:
                click.echo(_summary_line(row), err=as_json)
    if failed:
        raise click.exceptions.Exit(2)


def _summary_line(row):
    if row["range_m"] is None:
        return f"{row['file']}: none ({row['notes']})"
    parts = [f"{row['file']}: {row['class']} at {row['range_m']:.1f} m, SNR {row['snr_db']:.1f} dB"]
    for key, label, unit, scale in (("chopping_freq_hz", "chopping", "Hz", 1), ("rotation_rate_hz", "rotor", "rev/s", 1),
                                    ("blade_length_m", "blade", "cm", 100), ("doppler_bw_hz", "BW", "Hz", 1),
                                    ("wingbeat_freq_hz", "wingbeat", "Hz", 1), ("body_velocity_mps", "v", "m/s", 1)):
        if row.get(key) is not None:
            parts.append(f"{label} {row[key] * scale:.4g} {unit}")
    if row.get("aliased"):
        parts.append("aliased")
    return ", ".join(parts)


@main.command()
@click.argument("folder", type=click.Path(exists=True, file_okay=False, path_type=Path))
@click.option("--no-figure", is_flag=True)
def summarize(folder, no_figure):
    """Gather every <stem>.features.csv under FOLDER into FOLDER/features.csv (and summary.png).

    Captures that failed (their <stem>.error.txt) are listed, one line each; the exit code is then 1.
    """
    from mdpipe.report import tables

    features, errors = tables.summarize(folder)
    tables.atomic_write(folder / "features.csv", lambda tmp: features.to_csv(tmp, index=False))
    if not no_figure and len(features):
        from mdpipe.report import plots

        plots.summary_figure(features, folder / "summary.png")
    counts = features["class"].value_counts().to_dict() if len(features) else {}
    click.echo(f"{folder / 'features.csv'}: {len(features)} target rows from "
               f"{features['file'].nunique() if len(features) else 0} captures "
               f"({', '.join(f'{k} {v}' for k, v in sorted(counts.items())) or 'none'}); {len(errors)} failed")
    for _, error in errors.iterrows():
        click.echo(f"failed: {error['error']}")
    if len(errors):
        raise click.exceptions.Exit(1)


@main.command()
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path), default=Path("reports"),
              show_default=True)
@click.option("--configs", "configs_dir", type=click.Path(exists=True, file_okay=False, path_type=Path),
              default=Path("configs/paper"), show_default=True)
def paper(out_dir, configs_dir):
    """Reproduce the paper's Tables IV and V: paper_tables.csv, paper_tables.md and figures in --out."""
    import tempfile

    from mdpipe.report import paper as reproduction
    from mdpipe.report.tables import atomic_write

    figures = out_dir / "paper_figures"
    figures.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        table = reproduction.reproduce(configs_dir, work_dir=work, figures_dir=figures,
                                       progress=lambda text: click.echo(text, err=True))
    atomic_write(out_dir / "paper_tables.csv", lambda tmp: table.to_csv(tmp, index=False))
    atomic_write(out_dir / "paper_tables.md", lambda tmp: Path(tmp).write_text(reproduction.markdown(table)))
    click.echo(f"wrote {out_dir / 'paper_tables.csv'}, {out_dir / 'paper_tables.md'} and {figures}/")


@main.command()
@click.argument("sweep_path", metavar="SWEEP", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--out", "out_dir", required=True, type=click.Path(file_okay=False, path_type=Path),
              help="Folder for scenes/, scenes.csv and summary.md.")
@click.option("-j", "--jobs", type=click.IntRange(min=1), default=1, show_default=True, help="Worker processes.")
@click.option("--limit", type=click.IntRange(min=1), help="Run only the first LIMIT scenes of the sweep.")
@click.option("--keep-captures", is_flag=True, help="Keep the simulated captures in OUT/captures/.")
def evaluate(sweep_path, out_dir, jobs, limit, keep_captures):
    """Draw the scenes of SWEEP, simulate, process and score them against their truth.

    Writes OUT/scenes/<scene>.yaml (each rerunnable with mdpipe simulate + process), OUT/scenes.csv
    (one row per scene x target: truth, value, status, error, verdict per feature) and OUT/summary.md,
    which is also printed: class confusion, per-feature coverage and errors, confidently wrong values.
    """
    import time

    from mdpipe.evaluate import run, summary, sweep
    from mdpipe.report.tables import atomic_write

    start = time.perf_counter()
    draws = sweep.draw_scenes(sweep.load_sweep(sweep_path), limit=limit)
    prepared = run.prepare(draws)
    out_dir.mkdir(parents=True, exist_ok=True)
    frame = summary.records_frame(run.run_all(prepared, out_dir, jobs=jobs, keep_captures=keep_captures))
    text = summary.report(frame, title=f"mdpipe evaluate {sweep_path}",
                          wall_s=time.perf_counter() - start, jobs=jobs)
    atomic_write(out_dir / "scenes.csv", lambda tmp: frame.to_csv(tmp, index=False))
    atomic_write(out_dir / "summary.md", lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
    click.echo(text)
