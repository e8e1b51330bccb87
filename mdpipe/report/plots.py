"""Figures a radar engineer expects: range profile, spectrogram, Doppler power spectrum, folder summary.

Doppler axes are in Hz with m/s on the opposite axis (paper sign: approaching positive).
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from mdpipe import __version__  # noqa: E402
from mdpipe.physics.radar import doppler_hz, range_rate_from_doppler_mps  # noqa: E402
from mdpipe.report.tables import atomic_write  # noqa: E402

DYNAMIC_RANGE_DB = 60.0


def _save(fig, path, description):
    def write(tmp):
        fig.savefig(tmp, format="png", dpi=110, metadata={"Software": f"mdpipe {__version__}",
                                                            "Description": description})
    atomic_write(path, write)
    plt.close(fig)


def _db(power, floor):
    return 10 * np.log10(np.maximum(power, floor))


def _velocity_axis(ax, wavelength_m, *, which):
    forward = lambda f: -range_rate_from_doppler_mps(f, wavelength_m=wavelength_m)  # noqa: E731
    inverse = lambda v: doppler_hz(-v, wavelength_m=wavelength_m)  # noqa: E731
    if which == "y":
        ax.secondary_yaxis("right", functions=(forward, inverse)).set_ylabel("approach speed (m/s)")
    else:
        ax.secondary_xaxis("top", functions=(forward, inverse)).set_xlabel("approach speed (m/s)")


def range_figure(result, path):
    """Static (slow-time mean) and moving (MTI) power against range, with the gate and detections."""
    stats, params = result.stats, result.params
    fig, ax = plt.subplots(figsize=(8, 4))
    floor = max(stats.moving_power.max(), stats.static_power.max()) * 10 ** (-DYNAMIC_RANGE_DB / 10) + 1e-30
    ax.plot(stats.range_m, _db(stats.static_power, floor), label="static (slow-time mean)")
    ax.plot(stats.range_m, _db(stats.moving_power, floor), label="moving (MTI)")
    gate = stats.gate_range_m
    ax.axvspan(gate[0], gate[-1], color="0.9", zorder=0, label="search gate")
    for d in result.detections:
        ax.axvline(d.range_m, color="r", ls="--", lw=1)
        ax.annotate(f"{d.range_m:.1f} m\n{d.snr_db:.0f} dB", (d.range_m, ax.get_ylim()[1]), va="top", fontsize=8)
    farthest = max([d.range_m for d in result.detections], default=gate[-1] / 3)
    ax.set_xlim(0, min(stats.range_m[-1], max(3 * farthest, 20 * params.range_bin_m)))
    ax.set_xlabel("range (m)")
    ax.set_ylabel("power per chirp (dB V$^2$)")
    ax.set_title(f"Range profile ({params.range_bin_m:.3g} m bins)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    _save(fig, path, f"range profile of {result.path}")


def spectrogram_figure(result, path):
    """One panel per target: Doppler against time, flash edges marked when measured."""
    analyses, rows = result.analyses, result.rows
    fig, axes = plt.subplots(len(analyses), 1, figsize=(9, 3.6 * len(analyses)), squeeze=False)
    for ax, analysis, row in zip(axes[:, 0], analyses, rows):
        spec = analysis.spectrogram
        floor = spec.power.max() * 10 ** (-DYNAMIC_RANGE_DB / 10) + 1e-30
        mesh = ax.pcolormesh(spec.t_s, spec.f_hz, _db(spec.power, floor), shading="auto", cmap="viridis")
        fig.colorbar(mesh, ax=ax, pad=0.12).set_label("dB V$^2$")
        if analysis.flash_edges_hz is not None:
            for edge in analysis.flash_edges_hz:
                ax.axhline(edge, color="w", ls="--", lw=0.8)
        if row["rotation_rate_hz"] is not None:  # eight turns: the flashes stay readable
            ax.set_xlim(spec.t_s[0], min(spec.t_s[-1], spec.t_s[0] + 8 / row["rotation_rate_hz"]))
        ax.set_xlabel("time (s)")
        ax.set_ylabel("Doppler (Hz)")
        _velocity_axis(ax, row["wavelength_m"], which="y")
        ax.set_title(f"target {row['target']} at {row['range_m']:.1f} m: {row['class']}; "
                     f"window {spec.window_s * 1e3:.3g} ms, hop {spec.hop_s * 1e3:.3g} ms", fontsize=9)
    _save(fig, path, f"spectrograms of {result.path}")


def spectrum_figure(result, path):
    """One panel per target: dwell power spectrum, the paper's threshold and extent, flash edges, lines."""
    fig, axes = plt.subplots(len(result.analyses), 1, figsize=(9, 3.6 * len(result.analyses)), squeeze=False)
    for ax, analysis, row in zip(axes[:, 0], result.analyses, result.rows):
        spectrum = analysis.spectrum
        floor = spectrum.power.max() * 10 ** (-(DYNAMIC_RANGE_DB + 20) / 10) + 1e-30
        ax.plot(spectrum.f_hz, _db(spectrum.power, floor), lw=0.6, color="C0")
        threshold = 10 * np.log10(np.mean(spectrum.power)) + row["threshold_db"]
        ax.axhline(threshold, color="C3", ls=":", lw=1, label=f"mean + {row['threshold_db']:g} dB")
        if analysis.paper_extent_hz is not None and not row["aliased"]:
            for edge in analysis.paper_extent_hz:
                ax.axvline(edge, color="C3", lw=1)
        if analysis.flash_edges_hz is not None:
            for edge in analysis.flash_edges_hz:
                ax.axvline(edge, color="C2", ls="--", lw=1)
            ax.plot([], [], color="C2", ls="--", label="flash edges (tip Doppler)")
        if row["chopping_freq_hz"] is not None:
            centre = row["body_doppler_hz"] or 0.0
            lines = centre + row["chopping_freq_hz"] * np.arange(-8, 9)
            ax.plot(lines, np.full(lines.shape, ax.get_ylim()[1]), "v", color="C1", ms=4,
                    label=f"chopping lines, {row['chopping_freq_hz']:.1f} Hz apart")
        ax.set_xlabel("Doppler (Hz)")
        ax.set_ylabel("power (dB V$^2$)")
        _velocity_axis(ax, row["wavelength_m"], which="x")
        state = "aliased" if row["aliased"] else "not aliased"
        ax.set_title(f"target {row['target']}: power spectrum over {row['dwell_s']:.3g} s ({state})", fontsize=9)
        ax.legend(fontsize=7, loc="lower right")
        ax.grid(alpha=0.3)
    _save(fig, path, f"Doppler power spectra of {result.path}")


def summary_figure(features, path):
    """Every target of a folder: micro-Doppler half-width (m/s) against its periodicity rate (Hz), by class."""
    fig, ax = plt.subplots(figsize=(7, 5))
    rate = features["chopping_freq_hz"].fillna(features["wingbeat_freq_hz"])
    for label, marker in (("drone", "^"), ("bird", "o"), ("none", "x")):
        chosen = features["class"] == label
        ax.scatter(rate[chosen].fillna(0.1), features.loc[chosen, "micro_doppler_halfwidth_mps"].fillna(0.1),
                   marker=marker, label=f"{label} ({int(chosen.sum())})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("periodicity: chopping or wingbeat frequency (Hz)")
    ax.set_ylabel("micro-Doppler half-width (m/s)")
    ax.set_title(f"{len(features)} targets")
    ax.legend()
    ax.grid(alpha=0.3, which="both")
    _save(fig, path, "mdpipe folder summary")
