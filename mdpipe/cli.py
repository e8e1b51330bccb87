"""The ``mdpipe`` command line: thin click commands that parse, call the library and write.

Exit codes, the same in every command: 0 all good, 1 a usage error (a bad option, input or output folder),
2 a capture (or config) failed, 130 interrupted (Ctrl-C; 143 for SIGTERM).
"""

import json
import os
import signal
import sys
import threading
import time
from pathlib import Path

import click

from mdpipe import __version__
from mdpipe.errors import MdpipeError, one_line
from mdpipe.io import open_capture
from mdpipe.io.radarlog import ATTRIBUTES
from mdpipe.params import MAINS_CHOICES, MAX_BLADES, RANGE_WINDOWS, FigureParams, ProcessParams, transmit_cycle

PROGRESS_MIN_SAMPLES = 1 << 25
EXIT_USAGE, EXIT_FAILED, EXIT_INTERRUPTED, EXIT_TERMINATED = 1, 2, 130, 128 + signal.SIGTERM
EXIT_BROKEN_PIPE = 128 + signal.SIGPIPE


class InputError(click.ClickException):
    """Bad input named in one line; exit code 2."""

    exit_code = EXIT_FAILED


class UsageError(click.ClickException):
    """A bad option value, input or output folder, named in one line; exit code 1."""

    exit_code = EXIT_USAGE


class Terminated(BaseException):
    """SIGTERM, raised where the program is so that its clean-ups run as for Ctrl-C."""


_STOPS = []  # the stop signals received during a command


def _stop(signum, frame):
    """SIGINT raises KeyboardInterrupt, SIGTERM :class:`Terminated`, where the program is; both are recorded,
    because an exception raised inside a weakref callback or a finalizer is swallowed there."""
    _STOPS.append(signum)
    raise KeyboardInterrupt() if signum == signal.SIGINT else Terminated()


def _stop_recorded():
    """Raise the first stop signal :func:`_stop` recorded whose exception a callback swallowed, if any (the main
    thread only: a handler runs there)."""
    if _STOPS and threading.current_thread() is threading.main_thread():
        raise KeyboardInterrupt() if _STOPS[0] == signal.SIGINT else Terminated()


def _unraisable(previous):
    """A ``sys.unraisablehook`` that keeps quiet about a stop signal's exception swallowed in a callback
    (:func:`_stop` recorded it; the command ends with it) and passes anything else to ``previous``."""
    def hook(unraisable):
        if not isinstance(unraisable.exc_value, (KeyboardInterrupt, Terminated)):
            previous(unraisable)
    return hook


class BladeCount(click.ParamType):
    """``auto`` (None) or a whole number of blades from 1 to ``MAX_BLADES``."""

    name = "auto|N"

    def convert(self, value, param, ctx):
        if value is None or value == "auto":
            return None
        try:
            count = int(value)
        except (TypeError, ValueError):
            count = 0
        if not 1 <= count <= MAX_BLADES or str(count) != str(value).strip():
            self.fail(f"{value!r} is neither auto nor a whole number of blades from 1 to {MAX_BLADES}", param, ctx)
        return count


class Group(click.Group):
    """One exit-code convention: usage errors 1, :class:`MdpipeError` 2 (one line, no traceback), Ctrl-C 130,
    SIGTERM 143, stdout closed by its reader 141 (as SIGPIPE), silently."""

    def make_context(self, *args, **kwargs):
        try:
            return super().make_context(*args, **kwargs)
        except click.UsageError as exc:
            exc.exit_code = EXIT_USAGE
            raise

    def invoke(self, ctx):
        main_thread = threading.current_thread() is threading.main_thread()
        if main_thread:
            _STOPS.clear()
            previous = {signum: signal.signal(signum, _stop) for signum in (signal.SIGINT, signal.SIGTERM)}
            previous_hook, sys.unraisablehook = sys.unraisablehook, _unraisable(sys.unraisablehook)
        try:
            result = super().invoke(ctx)
            _stop_recorded()  # a stop whose exception a callback swallowed after the last capture
            return result
        except click.UsageError as exc:
            exc.exit_code = EXIT_USAGE
            raise
        except MdpipeError as exc:
            raise InputError(str(exc)) from None
        except (click.ClickException, click.exceptions.Exit, click.exceptions.Abort):
            raise
        except BrokenPipeError:  # whoever read stdout stopped (`mdpipe info x.h5 | head -1`): nothing left to say
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # (nor at exit, when stdout is flushed)
            raise click.exceptions.Exit(EXIT_BROKEN_PIPE) from None
        except Exception as exc:  # OSError outside any one capture's work (writing a summary, a folder that
            # vanished), an input nobody foresaw, or a bug: one line all the same
            raise InputError(one_line(exc)) from None
        except KeyboardInterrupt:
            click.echo("Interrupted.", err=True)
            raise click.exceptions.Exit(EXIT_INTERRUPTED) from None
        except Terminated:
            click.echo("Terminated.", err=True)
            raise click.exceptions.Exit(EXIT_TERMINATED) from None
        finally:
            if main_thread:
                for signum, handler in previous.items():
                    signal.signal(signum, handler)
                sys.unraisablehook = previous_hook


def attribute_overrides(func):
    """Options that supply or replace a capture's chirp attributes (``--tp 64e-6`` ...)."""
    for name, (_field, meaning, _example) in reversed(ATTRIBUTES.items()):
        kind = int if name in ("N", "NrChn") else float
        also = " (of an I/Q recording: its I/Q sample rate)" if name == "fs" else ""
        func = click.option(f"--{name.lower()}", name, type=kind, default=None,
                            help=f"Use this {meaning} instead of the file's {name!r} attribute{also}.")(func)
    func = click.option("--carrier-hz", "carrier_hz", type=float, default=None,
                        help="Carrier frequency of an I/Q (CW) recording (Hz): a WAV holds none; replaces an HDF5 "
                             "recording's 'fc'.")(func)
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
    overrides = {name: options[name] for name in (*ATTRIBUTES, "carrier_hz") if options[name] is not None}
    return {"frame_counter": {"auto": "auto", "yes": True, "no": False}[options["frame_counter"]],
            "overrides": overrides, "allow_external": options["allow_external"]}


def open_with_overrides(path, options):
    """Open ``path`` with the values of the :func:`attribute_overrides` options in ``options``."""
    return open_capture(path, **reader_options(options))


@click.group(cls=Group)
@click.version_option(__version__, prog_name="mdpipe")
def main():
    """Radar micro-Doppler analysis of drones and birds from Radarlog FMCW captures."""


def run():
    """The ``mdpipe`` console script: :func:`main`, then the process ends without the interpreter's teardown.

    With numpy, h5py, matplotlib and pandas loaded, that teardown (every module's objects freed one by one,
    for a process about to end) took 0.15-0.35 s of a 2 s batch. Python's atexit handlers still run and
    the standard streams are flushed. What is skipped needs nothing done: every file mdpipe writes (HDF5
    ones included) is closed, and renamed into place, and every pool it starts is shut down, before
    :func:`main` returns (a thread that may still run then only imports modules).
    """
    import atexit

    try:
        main()
        code = 0
    except SystemExit as exc:
        code = exc.code
    if code is not None and not isinstance(code, int):
        print(code, file=sys.stderr)
        code = 1
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe: nothing more can reach it
            pass
    os._exit(code or 0)


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
    from mdpipe.io.iq import is_iq_recording

    if is_iq_recording(capture):
        _iq_info(capture, as_json, options)
        return
    with open_with_overrides(capture, options) as cap:
        p, n = cap.params, cap.n_chirps
        cycle = transmit_cycle(cap.tx_sequence or (1,))
        derived = {
            "range_bin_m": p.range_bin_m, "max_range_m": p.max_range_m, "wavelength_m": p.wavelength_m,
            "doppler_span_hz": p.doppler_span_hz, "velocity_span_mps": p.velocity_span_mps,
            "duration_s": p.duration_s(n), "n_chirps": n, "n_channels": p.n_channels, "n_samples": p.n_samples,
            "tx_sequence": list(cap.tx_sequence), "transmit_cycle": cycle,
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
        if cycle > 1:
            one = p.every(cycle)
            click.echo(f"  transmitters in turn: TxSeq {list(cap.tx_sequence)}, a cycle of {cycle} chirps: each "
                       f"transmitter's chirps at {one.prf_hz:.6g} Hz, Doppler span +-{one.doppler_span_hz / 2:.6g} Hz "
                       "(what process reads)")
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


def _iq_info(path, as_json, options):
    """``mdpipe info`` of an I/Q (CW) recording: its layout, parameters and what they allow, its samples not read."""
    from mdpipe.io.iq import probe_iq

    reader = reader_options(options)
    params, n, layout = probe_iq(path, overrides=reader["overrides"], allow_external=reader["allow_external"])
    derived = {"wavelength_m": params.wavelength_m, "doppler_span_hz": params.doppler_span_hz,
               "velocity_span_mps": params.velocity_span_mps, "duration_s": params.duration_s(n), "n_samples": n,
               "n_channels": params.n_channels}
    if as_json:
        from mdpipe.report.tables import finite_json

        click.echo(json.dumps(finite_json({"file": str(path), "layout": layout.describe(), "params": params.__dict__,
                                           "derived": derived, "truth": None, "warnings": []}), allow_nan=False))
        return
    click.echo(f"{path}")
    click.echo(f"  layout: {layout.describe()}")
    click.echo(f"  CW carrier {params.carrier_hz / 1e9:.6g} GHz, I/Q at {params.sample_rate_hz:.6g} Hz, "
               f"FuSca {params.full_scale_v_per_lsb:.4g} V/count")
    click.echo(f"  recording: {n} samples x {params.n_channels} RX = {derived['duration_s']:.4g} s (no range)")
    click.echo(f"  Doppler span {params.doppler_span_hz:.6g} Hz (+-{params.doppler_span_hz / 2:.6g} Hz) = "
               f"{params.velocity_span_mps:.4g} m/s at lambda {params.wavelength_m * 1e3:.4g} mm")


def analysis_options(func):
    """The options of ``process`` and ``batch``, declared once: what to analyse, how, and what to write."""
    options = [
        click.option("--no-figures", is_flag=True, help="Write the tables only, no PNG figures."),
        click.option("--debug", is_flag=True, help="Print the traceback of every failed capture on stderr."),
        click.option("--range-m", type=click.FloatRange(min=0, min_open=True),
                     help="Analyse the target at this range (m) instead of detecting targets."),
        click.option("--min-range-m", type=click.FloatRange(min=0), default=ProcessParams.min_range_m,
                     show_default=True, help="Near edge of the range gate searched for targets (m)."),
        click.option("--max-range-m", type=click.FloatRange(min=0, min_open=True), default=ProcessParams.max_range_m,
                     show_default=True, help="Far edge of the range gate searched for targets (m)."),
        click.option("--max-targets", type=click.IntRange(min=1), default=ProcessParams.max_targets,
                     show_default=True, help="Most targets reported per capture, strongest first."),
        click.option("--false-alarm-probability", type=click.FloatRange(0, 1, min_open=True, max_open=True),
                     default=ProcessParams.false_alarm_probability, show_default=True,
                     help="Probability that receiver noise alone gives a detection in a capture (range-Doppler CFAR)."),
        click.option("--elevation-deg", type=click.FloatRange(-90, 90), default=None,
                     help="Elevation beta of the rotor plane (Eq. 6), for the blade length [not given: 0 assumed, "
                          "and blade_length_m_status says so]."),
        click.option("--blades", "n_blades", type=BladeCount(), default="auto", show_default=True,
                     help="Blades per rotor (N), or auto: measured where the echo tells it (blade imbalance, odd-N "
                          "flash doubling), else assumed and said so in n_blades_source."),
        click.option("--threshold-db", type=float, default=ProcessParams.threshold_db, show_default=True,
                     help="The paper's bandwidth rule: the spectrum above its mean by this much (dB)."),
        click.option("--range-window", type=click.Choice(RANGE_WINDOWS), default=ProcessParams.range_window,
                     show_default=True, help="Window of the range FFT."),
        click.option("--zero-pad", type=click.IntRange(1, 16), default=ProcessParams.zero_pad, show_default=True,
                     help="Zero-padding factor of the range FFT (range bins this many times finer; more memory)."),
        click.option("--stft-window-s", type=click.FloatRange(min=0, min_open=True),
                     help="Window of the spectrogram figure (s), rounded to whole chirps; a window outside 8 chirps "
                          "to half the dwell is adjusted and the notes say so [from the target's physics]."),
        click.option("--stft-hop-s", type=click.FloatRange(min=0, min_open=True),
                     help="Hop of the spectrogram figure (s), rounded to whole chirps [window / 4]."),
        click.option("--doppler-limits", default="auto", show_default=True,
                     help="Doppler axis of the figures: auto (the occupied band), full (+-PRF/2) or LOW,HIGH in Hz."),
        click.option("--max-memory-gb", type=click.FloatRange(min=0, min_open=True),
                     default=ProcessParams.max_memory_gb, show_default=True,
                     help="Refuse a capture whose planned memory exceeds this (GiB)."),
        click.option("--mains-hz", type=click.Choice(MAINS_CHOICES), default=ProcessParams.mains_hz, show_default=True,
                     help="Mains hum (lines at the grid's harmonics) searched in each echo and taken out: at 50 and 60 "
                          "Hz, one of them, or none (a receiver on batteries; a rotor held at a multiple of the grid's "
                          "rate, whose lines hum's would be)."),
        click.option("--transmitters", default=ProcessParams.transmitters, show_default=True, metavar="AUTO|N",
                     help="Transmitters the chirps take in turn (a MIMO radar's time-division cycle): auto (the "
                          "file's TxSeq attribute, else found on the static echoes) or N; the first one's chirps are "
                          "read, every N-th (1: every chirp as one sequence)."),
    ]
    func = attribute_overrides(func)
    for option in reversed(options):
        func = option(func)
    return func


def _jobs(inputs, out_dir, options, *, figures):
    """One :class:`mdpipe.batch.unit.Job` per capture named by ``inputs`` (files or folders)."""
    from mdpipe.batch.inputs import find_captures
    from mdpipe.batch.unit import Job

    try:
        params = ProcessParams(**{k: v for k, v in options.items() if k in ProcessParams.__dataclass_fields__})
        figure_params = FigureParams.from_text(options["doppler_limits"]) if figures else None
        captures = find_captures(inputs, wav=options.get("carrier_hz") is not None)
    except MdpipeError as exc:
        raise UsageError(str(exc)) from None
    reader = reader_options(options)
    return [Job(str(c.path), c.key, None if out_dir is None else str(out_dir), params, reader, figure_params)
            for c in captures]


def _run(jobs, *, on_outcome, debug, progress=None, **kwargs):
    """Run ``jobs`` with :func:`mdpipe.batch.runner.run`, failures one line each on stderr (and their
    tracebacks with ``debug``); usage problems of OUT or the scheduler become exit code 1."""
    from mdpipe.batch import runner

    def report(outcome):
        if progress is not None:
            progress.clear()
        if outcome.failed and outcome.status != "up to date":
            click.echo(f"Error: {outcome.message}", err=True)
            if debug and outcome.traceback:
                click.echo(outcome.traceback.rstrip("\n"), err=True)
        on_outcome(outcome)
        if progress is not None:
            progress.update(outcome)
        _stop_recorded()  # a stop whose exception a callback swallowed ends the run here, not after every capture

    def notify(text):
        if progress is not None:
            progress.clear()
        click.echo(text, err=True)
        if progress is not None:
            progress.draw()

    try:
        return runner.run(jobs, on_outcome=report, notify=notify, **kwargs)
    except MdpipeError as exc:
        raise UsageError(str(exc)) from None
    finally:
        if progress is not None:
            progress.clear()


@main.command()
@click.argument("captures", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path),
              help="Folder for the outputs, one folder OUT/<stem>/ per capture [default: . ; with --json "
                   "nothing is written unless --out is given].")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object per target on stdout.")
@analysis_options
def process(captures, out_dir, as_json, no_figures, debug, **options):
    """Detect targets in each CAPTURE (a file, or a folder searched for *.h5 and *.hdf5, and *.wav with
    --carrier-hz: docs/IQ_FORMAT.md), measure their micro-Doppler features, call drone / bird / none.

    Writes OUT/<stem>/ (for a folder, OUT/<path relative to it, less .h5>/) holding <stem>.features.csv,
    <stem>.run.json and the figures <stem>_range.png,
    _spectrogram.png, _spectrum.png, published together. A capture that cannot be processed is reported on
    one line and its folder holds only <stem>.error.txt; the others go on; the exit code is then 2.
    """
    if out_dir is None and not as_json:
        out_dir = Path(".")
    jobs = _jobs(captures, out_dir, options, figures=not no_figures)

    def show(outcome):
        for row in outcome.rows:
            click.echo(json.dumps(tables.json_record(row)) if as_json else _summary_line(row))

    from mdpipe.report import tables

    outcomes = _run(jobs, on_outcome=show, debug=debug)
    if any(o.failed for o in outcomes):
        raise click.exceptions.Exit(EXIT_FAILED)


def _summary_line(row):
    if row.get("target") is None and row["range_m"] is None:  # the `none` row of a capture without detections
        return f"{row['file']}: none ({row['notes']})"
    from mdpipe.report.tables import to_resolution

    snr = f"{row['snr_db']:.1f} dB" if row.get("snr_db") is not None else f"n/a ({row.get('snr_db_status')})"
    where = "(CW, no range)" if row["range_m"] is None else f"at {row['range_m']:.1f} m"
    parts = [f"{row['file']}: {row['class']} {where}, SNR {snr}"]
    for key, label, unit, scale in (("chopping_freq_hz", "chopping", "Hz", 1), ("rotation_rate_hz", "rotor", "rev/s", 1),
                                    ("blade_length_m", "blade", "cm", 100), ("doppler_bw_hz", "BW", "Hz", 1),
                                    ("wingbeat_freq_hz", "wingbeat", "Hz", 1)):
        if row.get(key) is not None:
            status = row.get(f"{key}_status", "ok")
            caveat = {"assumed_blades": f" (N = {row.get('n_blades')} assumed)",
                      "assumed_elevation": " (beta = 0 assumed)"}.get(status, "" if status == "ok" else f" ({status})")
            parts.append(f"{label} {row[key] * scale:.4g} {unit}{caveat}")
    if row.get("body_velocity_mps") is not None:  # to the Doppler resolution 1 / dwell, in m/s
        resolution_mps = row["wavelength_m"] / (2 * row["dwell_s"])
        parts.append(f"v {to_resolution(row['body_velocity_mps'], resolution_mps)} m/s")
    if row.get("aliased"):
        parts.append("aliased")
    return ", ".join(parts)


class Progress:
    """``[####....] done/total, failures, ETA`` on one line of a terminal."""

    WIDTH = 24

    def __init__(self, total, stream):
        self.total, self.stream, self.done, self.failed, self.started = total, stream, 0, 0, time.monotonic()
        self.draw()

    def update(self, outcome):
        self.done += 1
        self.failed += outcome.failed
        self.draw()

    def draw(self):
        filled = self.WIDTH * self.done // max(self.total, 1)
        eta = "?"
        if self.done:
            remaining_s = (time.monotonic() - self.started) / self.done * (self.total - self.done)
            eta = time.strftime("%H:%M:%S", time.gmtime(remaining_s))
        self.stream.write(f"\r[{'#' * filled}{'.' * (self.WIDTH - filled)}] {self.done}/{self.total}, "
                          f"{self.failed} failed, ETA {eta} ")
        self.stream.flush()

    def clear(self):
        self.stream.write("\r\033[K")
        self.stream.flush()


def _import_in_background(modules):
    """Import ``modules`` (what the folder's summary needs) in a thread while the captures are processed: this
    process otherwise waits idle, and would pay the imports at the end."""
    import importlib

    def load():
        for name in modules:
            try:
                importlib.import_module(name)
            except Exception:  # noqa: BLE001 - the summary's own import reports it
                return

    from mdpipe.batch import runner

    runner.start_thread(load)


def _gather(folder, *, figures, early=None, only=None):
    """Write FOLDER/features.csv (and summary.png) from its captures' tables; print it; return the failures.
    ``early``: a :class:`mdpipe.batch.summary.EarlySummary` whose figure is taken if drawn from these rows;
    ``only``: the capture folders to gather (a batch's own), the others named by their count."""
    from collections import Counter

    from mdpipe.report import tables

    columns, rows, errors = tables.gather(folder, only=only)
    tables.write_table(folder / tables.SUMMARY_TABLE, columns or list(tables.JSON_KEYS), rows)
    if figures and rows:
        png = None if early is None else early.png(rows)
        if png is not None:
            tables.atomic_write(folder / tables.SUMMARY_PNG, lambda tmp: Path(tmp).write_bytes(png))
        else:
            from mdpipe.report import plots

            plots.summary_figure(rows, folder / tables.SUMMARY_PNG)
    counts = Counter(row["class"] for row in rows)
    click.echo(f"{folder / tables.SUMMARY_TABLE}: {len(rows)} target rows from "
               f"{len({row['file'] for row in rows})} captures "
               f"({', '.join(f'{k} {v}' for k, v in sorted(counts.items())) or 'none'}); {len(errors)} failed")
    for _, error in errors:
        click.echo(f"failed: {error}")
    others = 0 if only is None else tables.folders_beyond(folder, only)
    if others:
        click.echo(f"{others} capture folder{'s' if others > 1 else ''} in {folder} {'are' if others > 1 else 'is'} "
                   f"not of this batch (earlier runs): left out of {tables.SUMMARY_TABLE} (mdpipe summarize {folder} "
                   "gathers every one)")
    return len(errors)


@main.command()
@click.argument("inputs", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("--out", "out_dir", required=True, type=click.Path(file_okay=False, path_type=Path),
              help="Output folder: OUT/<path relative to the folder given, less .h5>/ per capture, "
                   "OUT/features.csv, OUT/summary.png, OUT/manifest.json.")
@click.option("-j", "--jobs", "workers", type=click.IntRange(min=1), default=os.cpu_count() or 1,
              show_default="the number of CPUs", help="Captures processed at once (worker processes).")
@click.option("--scheduler", metavar="local|tcp://HOST:8786",
              help="Run on Dask: 'local' starts a LocalCluster of -j workers here; an address uses a running "
                   "`dask scheduler` whose workers see INPUT and OUT at the same paths "
                   "(pip install 'mdpipe[dask]').")
@analysis_options
def batch(inputs, out_dir, workers, scheduler, no_figures, debug, **options):
    """Process every capture in INPUT (files, or folders searched recursively for *.h5 and *.hdf5, and *.wav with
    --carrier-hz) into OUT.

    Each capture's outputs go to OUT/<its path relative to the folder given, less .h5>/, published whole; a capture
    is redone only when its size, mtime or content (SHA-256), mdpipe's version or the options changed
    (OUT/manifest.json). Ends with OUT/features.csv and OUT/summary.png. Exit code 0 all good, 2 some
    captures failed, 130 interrupted (what finished is kept; run again to finish).
    """
    if scheduler is not None and scheduler != "local" and "://" not in scheduler:
        raise UsageError(f"--scheduler {scheduler!r}: give 'local' or an address such as tcp://HOST:8786")
    jobs = _jobs(inputs, out_dir, options, figures=not no_figures)
    progress = Progress(len(jobs), sys.stderr) if sys.stderr.isatty() else None
    counts = {"done": 0, "failed": 0, "up to date": 0}
    early = None
    if not no_figures and scheduler is None and workers > 1 and len(jobs) > 1:  # a pool
        from mdpipe.batch.summary import EarlySummary

        early = EarlySummary(out_dir, jobs)

    def tally(outcome):
        counts["failed" if outcome.failed else outcome.status] += 1
        if early is not None:
            early.outcome(outcome)

    def summary(outcomes):
        if progress is not None:
            progress.clear()
        kept = sum(o.failed and o.status == "up to date" for o in outcomes)
        click.echo(f"{len(jobs)} captures: {counts['done']} processed, {counts['up to date']} up to date, "
                   f"{counts['failed']} failed" + (f" ({kept} of them unchanged since they failed)" if kept else ""))
        _gather(out_dir, figures=not no_figures, early=early, only=[job.folder for job in jobs])

    try:
        _run(jobs, on_outcome=tally, debug=debug, progress=progress, workers=workers, scheduler=scheduler,
             track=True, finish=summary, **({} if early is None else {"analysed": early.analysed}),
             started=lambda: None if no_figures else _import_in_background(["mdpipe.report.plots"]))
    except (KeyboardInterrupt, Terminated) as exc:
        click.echo(f"Interrupted after {sum(counts.values())} of {len(jobs)} captures; each capture is published "
                   "whole or not at all: run the same command again to finish.", err=True)
        raise click.exceptions.Exit(EXIT_TERMINATED if isinstance(exc, Terminated) else EXIT_INTERRUPTED) from None
    if counts["failed"]:
        raise click.exceptions.Exit(EXIT_FAILED)


@main.command()
@click.argument("folder", type=click.Path(exists=True, file_okay=False, path_type=Path))
@click.option("--no-figures", is_flag=True, help="Write the table only, no summary.png.")
def summarize(folder, no_figures):
    """Gather every <stem>.features.csv under FOLDER into FOLDER/features.csv (and summary.png).

    Captures that failed (their <stem>.error.txt) are listed, one line each; the exit code is then 2.
    """
    if _gather(folder, figures=not no_figures):
        raise click.exceptions.Exit(EXIT_FAILED)


@main.command()
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path), default=Path("reports"),
              show_default=True, help="Folder for the tables and figures.")
@click.option("--configs", "configs_dir", type=click.Path(exists=True, file_okay=False, path_type=Path),
              default=Path("configs/paper"), show_default=True, help="Folder of the Table I and II scene YAMLs.")
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
@click.option("--reuse-captures", "reuse_dir", type=click.Path(file_okay=False, path_type=Path),
              help="Process the captures another run kept (its OUT/captures/, made with --keep-captures by this "
              "simulator) instead of simulating the scenes they hold: a processing change scored on the same scenes, "
              "only processed.")
@click.option("--seed", type=click.IntRange(min=0), help="Draw with this seed instead of the sweep's: a fresh draw "
              "of the same distributions, scenes no estimator was tuned on.")
def evaluate(sweep_path, out_dir, jobs, limit, keep_captures, reuse_dir, seed):
    """Draw the scenes of SWEEP, simulate, process and score them against their truth.

    Writes OUT/scenes/<scene>.yaml (each rerunnable with mdpipe simulate + process), OUT/scenes.csv
    (one row per scene x target: truth, value, status, error, verdict per feature, a drone's blade profile) and
    OUT/summary.md, which is also printed: class confusion, per-feature coverage and errors, rotation coverage by band
    and blade profile, confidently wrong values, wrong classes.
    """

    from mdpipe.evaluate import run, summary, sweep
    from mdpipe.report.tables import atomic_write

    start = time.perf_counter()
    draws = sweep.draw_scenes(sweep.load_sweep(sweep_path), limit=limit, seed=seed)
    out_dir.mkdir(parents=True, exist_ok=True)
    records = run.run_all(draws, out_dir, jobs=jobs, keep_captures=keep_captures, reuse_dir=reuse_dir)
    frame = summary.records_frame(records)
    text = summary.report(frame, title=f"mdpipe evaluate {sweep_path}" + ("" if seed is None else f" --seed {seed}"),
                          wall_s=time.perf_counter() - start, jobs=jobs)
    atomic_write(out_dir / "scenes.csv", lambda tmp: frame.to_csv(tmp, index=False))
    atomic_write(out_dir / "summary.md", lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
    click.echo(text)
