"""Figures a radar engineer reads without help: range profile, spectrogram, Doppler power spectrum, folder summary.

Conventions, the same as the tables': Doppler in Hz with the paper's sign (Eq. 2: positive
approaching), range rate in m/s positive receding, both named on the axes; powers in dB relative
to the receiver noise in the same bin (0 dB: the noise floor); every mark in a legend; panels placed
in inches with room for their titles, tick labels and secondary axes, and legend panels as wide as their
legends measure, so nothing is cut (matplotlib's constrained layout, which did the same, took a third of the
drawing time). The Doppler axis shows the occupied band (``FigureParams``) and says
which part of the unambiguous span ``-PRF/2 .. PRF/2`` that is.
"""

import io
from pathlib import Path

import numpy as np
from matplotlib import rc_context
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from mdpipe.params import FigureParams
from mdpipe.physics.radar import doppler_hz, range_rate_from_doppler_mps
from mdpipe.process import combs, spectral
from mdpipe.process.classify import DRONE_SPREAD_MPS
from mdpipe.process.doppler import noise_level_per_bin
from mdpipe.process.wingbeat import MAX_WINGBEAT_HZ, MIN_WINGBEAT_HZ
from mdpipe.report.tables import atomic_write

DYNAMIC_RANGE_DB = 60.0      # colour scale: this far below the strongest cell, at most
NOISE_SHOWN_DB = -10.0       # ... and no further below the noise
DOPPLER_MARGIN = 0.25        # auto Doppler limits: the occupied band widened by this share on each side
MIN_DOPPLER_VIEW_BINS = 40   # auto Doppler limits: at least this many spectrum bins wide
SPECTROGRAM_TURNS = 8        # a drone's spectrogram shows this many rotor turns: the flashes stay readable
CHOPPING_TICKS = 5           # chopping lines marked up to k = +-5 about the body Doppler
MAX_LISTED = 6               # summary: captures without a target listed by name, at most
DOPPLER_LABEL = "Doppler (Hz), + approaching"
RANGE_RATE_LABEL = "range rate (m/s), + receding"
POWER_LABEL = "dB re noise per bin"
LEGEND = dict(fontsize=7, loc="upper left", bbox_to_anchor=(0, 1), borderaxespad=0.0, frameon=False)
ROW_HEIGHT_IN = 3.9        # one target's panel row
EDGE_IN = 0.08             # blank border round every figure
LEFT_ROOM_IN = 1.0         # left of a plot: tick labels (up to 7 characters) and the axis label
BOTTOM_ROOM_IN = 0.6       # below a plot: tick labels and the axis label
SIDE_ROOM_IN = 0.8         # beside a plot: a secondary axis' tick labels and label
TOP_AXIS_ROOM_IN = 0.55    # above a plot: a secondary axis' tick labels and label
TITLE_PAD_IN = 0.1         # between a title and what it stands on
COLORBAR_IN = 0.15         # a colour bar's width; SIDE_ROOM_IN right of it holds its labels
LEGEND_GAP_IN = 0.25       # between a plot's last label and its legend panel
SUMMARY_STRIP_IN = 1.2     # summary: the strip of rows without a periodicity ...
SUMMARY_GAP_IN = 0.35      # ... and the room between it and the plot (their tick labels)
DPI = 110                  # figures are drawn, measured and saved at this resolution
MINOR_LOG_SUBS = (2.0, 5.0)  # minor ticks of a log axis, per decade
MIN_PLOT_SHARE = 0.45      # a plot keeps at least this share of the figure's width, however long its legend
TEXT_RC = {"text.hinting": "no_hinting"}  # glyphs unhinted: hinting took a sixth of a figure's drawing time
PNG_COMPRESS_LEVEL = 3     # zlib: as fast as its fastest (1) here, a figure 7-10 ms sooner and no larger than at 6


def _png(fig, description):
    """PNG bytes with no creation software or time and a description free of machine paths: reproducible.
    Text drawn as :func:`_key_width_in` measured it (``TEXT_RC``)."""
    buffer = io.BytesIO()
    with rc_context(TEXT_RC):
        fig.savefig(buffer, format="png", dpi=DPI, metadata={"Software": None, "Description": description},
                    pil_kwargs={"compress_level": PNG_COMPRESS_LEVEL})
    return buffer.getvalue()


def _save(fig, path, description):
    png = _png(fig, description)
    atomic_write(path, lambda tmp: Path(tmp).write_bytes(png))


def _figure(figsize):
    """A figure drawn by Agg at ``DPI``, outside pyplot (no global registry of figures to close)."""
    fig = Figure(figsize=figsize, dpi=DPI)
    FigureCanvasAgg(fig)
    return fig


def _name(path):
    return str(path).replace("\\", "/").rsplit("/", 1)[-1]


def _db(power, reference):
    return 10 * np.log10(np.maximum(power, np.finfo(float).tiny) / reference)


def _range_rate_axis(ax, wavelength_m, *, which):
    """The opposite axis in range rate (m/s, + receding), for a Doppler (Hz, + approaching) axis."""
    functions = (lambda f: range_rate_from_doppler_mps(f, wavelength_m=wavelength_m),
                 lambda v: doppler_hz(v, wavelength_m=wavelength_m))
    if which == "y":
        ax.secondary_yaxis("right", functions=functions).set_ylabel(RANGE_RATE_LABEL)
    else:
        ax.secondary_xaxis("top", functions=functions).set_xlabel(RANGE_RATE_LABEL)


def _key_axes(fig):
    """An empty panel beside a plot that holds its legend (the plot keeps its data clear); placed by
    :func:`_arrange`."""
    ax = fig.add_axes((0, 0, 1, 1))
    ax.axis("off")
    return ax


def _title(ax, text, fontsize):
    """Set ``ax``'s title; :func:`_arrange` places it (matplotlib's own placement measures every tick label
    of the axes and its twins at each draw: a fifth of a figure's drawing time)."""
    ax.set_title(text, fontsize=fontsize, y=1.0)


def _title_room_in(ax):
    """Height (in) taken above a plot by its title."""
    title = ax.title
    return (title.get_text().count("\n") + 1) * title.get_fontsize() * 1.25 / 72 + TITLE_PAD_IN


def _key_width_in(fig, keys):
    """Width (in) of the widest legend or note in the legend panels ``keys``."""
    renderer = fig.canvas.get_renderer()
    parts = [part for key in keys for part in (key.get_legend(), *key.texts) if part is not None]
    with rc_context(TEXT_RC):
        return max((part.get_window_extent(renderer).width / fig.dpi for part in parts), default=0.0)


def _arrange(fig, rows, *, right_in=0.0, top_in=0.0, colorbars=None, left_in=LEFT_ROOM_IN, bottom_in=BOTTOM_ROOM_IN):
    """Place one row of ``(plot axes, legend panel)`` per entry of ``rows``, top to bottom, each row an equal
    share of the figure's height: the plot after ``left_in`` of room for its labels, with ``right_in`` beside it
    (a secondary axis, a colour bar from ``colorbars``: one per row) and ``top_in`` above its title; the legend
    panels as wide as their widest legend, flush right (or right after the plot's room when the plot
    would keep less than ``MIN_PLOT_SHARE`` of the width)."""
    width_in, height_in = fig.get_size_inches()
    row_in = height_in / len(rows)
    key_in = _key_width_in(fig, [key for _, key in rows])
    plot_right_in = max(width_in - EDGE_IN - key_in - LEGEND_GAP_IN - right_in, EDGE_IN + left_in + MIN_PLOT_SHARE * width_in)
    for i, (ax, key) in enumerate(rows):
        top = height_in - i * row_in - EDGE_IN - top_in - _title_room_in(ax)
        bottom = height_in - (i + 1) * row_in + bottom_in
        x0 = EDGE_IN + left_in
        ax.set_position((x0 / width_in, bottom / height_in, (plot_right_in - x0) / width_in, (top - bottom) / height_in))
        ax.title.set_y(1 + top_in / (top - bottom))
        key.set_position(((plot_right_in + right_in + LEGEND_GAP_IN) / width_in, bottom / height_in, key_in / width_in,
                          (top - bottom) / height_in))
        if colorbars is not None:
            colorbars[i].set_position(((plot_right_in + SIDE_ROOM_IN) / width_in, bottom / height_in,
                                       COLORBAR_IN / width_in, (top - bottom) / height_in))


def _target_panels(result):
    """A figure with one row per target, a plot and its legend panel: (fig, [(ax, legend panel, analysis, row)])."""
    n = len(result.analyses)
    fig = _figure(figsize=(11, ROW_HEIGHT_IN * n))
    return fig, [(fig.add_subplot(n, 1, i + 1), _key_axes(fig), analysis, row)
                 for i, (analysis, row) in enumerate(zip(result.analyses, result.rows))]


def _noise_per_bin(result, n_window):
    """The receiver noise in one bin of an ``n_window``-chirp Hann spectrum of a target (V^2): the 0 dB of the figures."""
    return max(noise_level_per_bin(result.noise_power, n_window), np.finfo(float).tiny)


def _lines(draw, values, label, **style):
    """One line per value (``ax.axvline`` or ``ax.axhline``), one legend entry for them all."""
    for i, value in enumerate(values):
        draw(value, label=None if i else label, **style)


def _body_label(row):
    return f"body Doppler, mean ({round(row['body_doppler_hz'], 1) + 0.0:.1f} Hz)"  # + 0.0: no "-0.0"


def _panel_title(result, row, middle, limits_text):
    where = "CW, no range" if row["range_m"] is None else f"at {row['range_m']:.4g} m"
    return (f"{_name(result.path)}, target {row['target']} {where}: {row['class']}\n{middle}\n"
            f"Doppler: {limits_text}")


def _doppler_view_hz(analysis, row, noise_power, prf_hz, options):
    """Doppler limits (Hz) of a target's spectrogram and spectrum, and a phrase saying what they are.

    ``auto``: where the dwell spectrum (smoothed as the analysis smooths it) stands 10 dB above the
    noise per bin, widened by a quarter on each side and holding the body Doppler, the paper's extent
    and the flash edges; the whole span when that band is aliased or empty. ``full``: the span.
    """
    half_span = prf_hz / 2
    span_text = f"+-{half_span:.5g} Hz = 1/(2 Tp)"
    if isinstance(options.doppler_limits, tuple):
        low, high = options.doppler_limits
        return (low, high), f"{low:.4g} to {high:.4g} Hz (given) of the unambiguous {span_text}"
    spectrum = analysis.spectrum
    if options.doppler_limits == "auto" and noise_power > 0:
        band = spectral.occupied_band(spectrum, noise_level_per_bin(noise_power, len(spectrum.f_hz)),
                                      smooth_hz=max(prf_hz / 200, 4 * spectrum.resolution_hz))
        if not band.aliased and np.isfinite(band.low_hz):
            marks = [band.low_hz, band.high_hz, *(analysis.paper_extent_hz or ()), *(analysis.flash_edges_hz or ())]
            if row["body_doppler_hz"] is not None:
                marks.append(row["body_doppler_hz"])
            low, high = min(marks), max(marks)
            margin = max(DOPPLER_MARGIN * (high - low), MIN_DOPPLER_VIEW_BINS / 2 * spectrum.resolution_hz)
            low, high = max(low - margin, -half_span), min(high + margin, half_span)
            if high - low < 0.9 * prf_hz:
                return (low, high), f"{low:.4g} to {high:.4g} Hz (occupied band) of the unambiguous {span_text}"
    return (-half_span, half_span), f"the whole unambiguous span {span_text}"


def _mark_span(ax, limits, prf_hz, *, which):
    """Shade what lies beyond the unambiguous span, when the view reaches past it."""
    half_span = prf_hz / 2
    span = ax.axvspan if which == "x" else ax.axhspan
    drawn = False
    for start, stop in ((limits[0], -half_span), (half_span, limits[1])):
        if start < stop:
            span(start, stop, color="0.6", alpha=0.4, hatch="//", lw=0,
                 label=None if drawn else f"beyond the unambiguous span +-{half_span:.5g} Hz")
            drawn = True


def range_figure(result, path):
    """Static and moving (MTI) power against range as steps, the detection threshold over the searched gate."""
    stats, radar, process = result.stats, result.params, result.process
    noise = max(result.noise_power, np.finfo(float).tiny)
    fig = _figure(figsize=(9, 4.2))
    ax, key = fig.add_subplot(), _key_axes(fig)
    ax.plot(stats.range_m, _db(stats.static_power, noise), drawstyle="steps-mid", lw=1,
            label="static: power of the slow-time mean")
    ax.plot(stats.range_m, _db(stats.moving_power, noise), drawstyle="steps-mid", lw=1,
            label="moving: power about the slow-time mean (MTI)")
    gate = stats.gate_range_m
    farthest = max([d.range_m for d in result.detections], default=gate[-1] / 3)
    x_max = min(stats.range_m[-1], max(3 * farthest, 20 * radar.range_bin_m))
    ax.set_xlim(0, x_max)
    step = stats.range_m[1] - stats.range_m[0]
    edges = (gate[0] - step / 2, gate[-1] + step / 2)  # outer edges of the gate's outer bins
    ax.axvspan(0, edges[0], color="0.85", lw=0, zorder=0, label=f"not searched (gate {gate[0]:.3g}-{gate[-1]:.4g} m)")
    if edges[1] < x_max:
        ax.axvspan(edges[1], x_max, color="0.85", lw=0, zorder=0)
    if result.detection_test is not None:  # the band test's threshold on the mean over Doppler; lines per cell
        level = 10 * np.log10(result.detection_test.band_threshold)
        ax.hlines(level, edges[0], min(edges[1], x_max), color="C3", ls="--", lw=1,
                  label=f"band-test threshold: noise + {level:.2g} dB\n(false alarms "
                        f"{process.false_alarm_probability:g} per capture; Doppler lines tested per cell)")
    else:
        ax.plot([], [], " ", label=f"range chosen with --range-m {process.range_m:g} (no detection)")
    for index, d in enumerate(result.detections):
        level = _db(stats.moving_power[d.bin], noise)
        ax.plot(d.range_m, level, "v", color=f"C{index + 4}", ms=8, ls="none",
                label=f"target {index}: {d.range_m:.4g} m, SNR {d.snr_db:.1f} dB")
    ax.set_xlabel("range (m)")
    ax.set_ylabel(f"power per chirp and RX ({POWER_LABEL})")
    found = f"{len(result.detections)} target(s)" if result.detections else "no target above the threshold"
    _title(ax, f"{_name(result.path)}: range profile ({radar.range_bin_m:.3g} m bins),\nmean over the whole "
           f"{radar.duration_s(stats.n_chirps):.3g} s dwell; {found}", fontsize=9)
    key.legend(*ax.get_legend_handles_labels(), **LEGEND)
    ax.grid(alpha=0.3)
    _arrange(fig, [(ax, key)])
    _save(fig, path, f"range profile of {_name(result.path)}")


def _time_view_s(spec, row):
    """Time limits of a spectrogram and what they are: a drone's first turns, else the whole dwell."""
    dwell = f"{row['dwell_s']:.3g} s dwell"
    rate = row["rotation_rate_hz"]
    if rate is not None and spec.t_s[0] + SPECTROGRAM_TURNS / rate < spec.t_s[-1]:
        stop = spec.t_s[0] + SPECTROGRAM_TURNS / rate
        return (spec.t_s[0], stop), f"{spec.t_s[0]:.3g}-{stop:.3g} s of the {dwell} ({SPECTROGRAM_TURNS} rotor turns)"
    return (spec.t_s[0], spec.t_s[-1]), f"the whole {dwell}"


def spectrogram_figure(result, path, options=FigureParams()):
    """One panel per target: Doppler against time (dB re noise per bin), flash edges and body Doppler marked."""
    fig, panels = _target_panels(result)
    prf = result.params.prf_hz
    colorbars = []
    for ax, key, analysis, row in panels:
        spec = analysis.spectrogram
        level = _db(spec.power, _noise_per_bin(result, len(spec.f_hz)))
        top = float(level.max())
        mesh = ax.pcolormesh(spec.t_s, spec.f_hz, level, shading="nearest", cmap="viridis",
                             vmin=max(top - DYNAMIC_RANGE_DB, NOISE_SHOWN_DB), vmax=top, rasterized=True)
        colorbars.append(fig.add_axes((0, 0, 1, 1)))
        fig.colorbar(mesh, cax=colorbars[-1]).set_label(POWER_LABEL)
        limits, limits_text = _doppler_view_hz(analysis, row, result.noise_power, prf, options)
        _mark_span(ax, limits, prf, which="y")
        if analysis.flash_edges_hz is not None:
            _lines(ax.axhline, analysis.flash_edges_hz, f"flash edges: +-tip Doppler ({row['tip_doppler_hz']:.4g} Hz)",
                   color="r", ls="--", lw=1.0)
        if row["body_doppler_hz"] is not None:
            ax.axhline(row["body_doppler_hz"], color="C1", ls=":", lw=1.2,
                       label=_body_label(row))
        times, time_text = _time_view_s(spec, row)
        ax.set_xlim(*times)
        ax.set_ylim(*limits)
        ax.set_xlabel("time from the start of the capture (s)")
        ax.set_ylabel(DOPPLER_LABEL)
        _range_rate_axis(ax, row["wavelength_m"], which="y")
        _title(ax, _panel_title(result, row, f"time: {time_text}; Hann window {spec.window_s * 1e3:.3g} ms, "
                                f"hop {spec.hop_s * 1e3:.3g} ms", limits_text), fontsize=8.5)
        handles, labels = ax.get_legend_handles_labels()
        if handles:
            key.legend(handles, labels, **LEGEND)
        else:
            key.text(0, 1, "no flash edges or body line\nmeasured for this target", fontsize=7, va="top")
    _arrange(fig, [(ax, key) for ax, key, _, _ in panels], right_in=2 * SIDE_ROOM_IN + COLORBAR_IN,
             colorbars=colorbars)
    _save(fig, path, f"spectrograms of {_name(result.path)}")


def _chopping_ticks(ax, row, limits):
    """Short ticks at the top at body Doppler + k f_chop, |k| <= CHOPPING_TICKS, within the view."""
    centre = row["body_doppler_hz"] or 0.0
    lines = centre + row["chopping_freq_hz"] * np.arange(-CHOPPING_TICKS, CHOPPING_TICKS + 1)
    lines = lines[(lines >= limits[0]) & (lines <= limits[1])]
    ax.vlines(lines, 0.9, 1.0, transform=ax.get_xaxis_transform(), color="C1", lw=1.5,
              label=f"chopping lines: body Doppler + k x {row['chopping_freq_hz']:.4g} Hz, |k| <= {CHOPPING_TICKS}")


def spectrum_figure(result, path, options=FigureParams()):
    """One panel per target: dwell power spectrum (dB re noise per bin) and every measured mark on it."""
    fig, panels = _target_panels(result)
    prf = result.params.prf_hz
    for ax, key, analysis, row in panels:
        spectrum = analysis.spectrum
        reference = _noise_per_bin(result, len(spectrum.f_hz))
        level = _db(spectrum.power, reference)
        ax.plot(spectrum.f_hz, level, lw=0.6, color="C0",
                label=f"dwell power spectrum (Hann, {len(spectrum.f_hz)} chirps, {spectrum.resolution_hz:.3g} Hz bins)")
        ax.axhline(0.0, color="0.4", lw=0.8, label="receiver noise per bin (0 dB)")
        if analysis.paper_extent_hz is not None and not row["aliased"]:  # the rule is applied to 0.25 s segments
            _lines(ax.axvline, analysis.paper_extent_hz,
                   f"paper extent: 0.25 s segments above their mean + {row['threshold_db']:g} dB, median "
                   f"(BW {row['doppler_bw_hz']:.4g} Hz)", color="C3", lw=1)
        if analysis.flash_edges_hz is not None:
            _lines(ax.axvline, analysis.flash_edges_hz, f"flash edges: +-tip Doppler "
                   f"(BW {row['doppler_bw_spectrogram_hz']:.4g} Hz)", color="C2", ls="--", lw=1)
        if row["body_doppler_hz"] is not None:
            ax.axvline(row["body_doppler_hz"], color="C4", ls="-.", lw=1,
                       label=_body_label(row))
        limits, limits_text = _doppler_view_hz(analysis, row, result.noise_power, prf, options)
        _mark_span(ax, limits, prf, which="x")
        if row["chopping_freq_hz"] is not None:
            _chopping_ticks(ax, row, limits)
        ax.set_xlim(*limits)
        bottom = max(float(level.max()) - DYNAMIC_RANGE_DB - 20, NOISE_SHOWN_DB)
        ax.set_ylim(bottom, float(level.max()) + 8)
        ax.set_xlabel(DOPPLER_LABEL)
        ax.set_ylabel(f"power ({POWER_LABEL})")
        _range_rate_axis(ax, row["wavelength_m"], which="x")
        state = "aliased: bandwidth withheld" if row["aliased"] else "not aliased"
        _title(ax, _panel_title(result, row, f"power spectrum over the whole {row['dwell_s']:.3g} s dwell ({state})",
                                limits_text), fontsize=8.5)
        ax.grid(alpha=0.3)
        key.legend(*ax.get_legend_handles_labels(), **LEGEND)
    _arrange(fig, [(ax, key) for ax, key, _, _ in panels], top_in=TOP_AXIS_ROOM_IN)
    _save(fig, path, f"Doppler power spectra of {_name(result.path)}")


def _label(row):
    aliased = " (aliased: at least)" if row["aliased"] in (True, "True") else ""
    return f"{_name(row['file']).removesuffix('.h5')} #{int(row['target'])}{aliased}"


def _plain(value, _position=None):
    """A log axis' tick label as a plain number (0.05, 1, 300): read at a glance, and drawn without mathtext."""
    return f"{value:g}"


def _numbers(rows, key):
    """``row[key]`` of every row as floats, NaN where empty or null (the text cells of a gathered table, or
    numbers)."""
    return np.array([np.nan if row.get(key) in (None, "") else float(row[key]) for row in rows], dtype=float)


SUMMARY_DESCRIPTION = "mdpipe folder summary"


def summary_figure(rows, path):
    """Draw :func:`summary` into ``path``."""
    _save(summary(rows), path, SUMMARY_DESCRIPTION)


def summary_png(rows):
    """:func:`summary` as PNG bytes, the same as :func:`summary_figure` writes."""
    return _png(summary(rows), SUMMARY_DESCRIPTION)


def summary(rows):
    """Every target of a folder: micro-Doppler half-width (m/s) against its periodicity (Hz), with the class
    regions (a figure).

    ``rows``: dicts holding ``file``, ``target``, ``class``, ``aliased``, ``chopping_freq_hz``,
    ``wingbeat_freq_hz`` and ``micro_doppler_halfwidth_mps``, as numbers or as the text of the tables
    (:func:`mdpipe.report.tables.gather`). The regions are those of :mod:`mdpipe.process.classify`: drone
    above ``DRONE_SPREAD_MPS`` or with a blade line comb (chopping frequencies searched from
    ``combs.MIN_CHOP_HZ`` to ``combs.MAX_CHOP_HZ``, whatever the blade count); bird with a wingbeat (searched
    from ``MIN_WINGBEAT_HZ`` to ``MAX_WINGBEAT_HZ``) below it. Rows without a periodicity sit in a strip
    of their own at their half-width; rows without a target are listed by file.
    """
    fig = _figure(figsize=(11, 6))
    strip = fig.add_subplot()
    ax = fig.add_axes((0, 0, 1, 1), sharey=strip)
    key = _key_axes(fig)
    chopping = _numbers(rows, "chopping_freq_hz")
    rate = np.where(np.isnan(chopping), _numbers(rows, "wingbeat_freq_hz"), chopping)
    width = _numbers(rows, "micro_doppler_halfwidth_mps")
    has_rate, has_width = ~np.isnan(rate), ~np.isnan(width)
    chop = (combs.MIN_CHOP_HZ, combs.MAX_CHOP_HZ)
    x_lim = (min(0.1, rate[has_rate].min() / 2) if has_rate.any() else 0.1, max(3000.0, 2 * rate[has_rate].max(initial=0)))
    y_lim = (min(0.05, width[has_width].min() / 2) if has_width.any() else 0.05,
             max(200.0, 2 * width[has_width].max(initial=0)))
    ax.axhspan(DRONE_SPREAD_MPS, y_lim[1], color="C0", alpha=0.08, lw=0, label=f"drone: half-width > {DRONE_SPREAD_MPS:g} m/s")
    ax.fill_between(chop, y_lim[0], DRONE_SPREAD_MPS, color="C0", alpha=0.16, lw=0,
                    label=f"drone: blade line comb, chopping {chop[0]:g}-{chop[1]:g} Hz")
    ax.fill_between((MIN_WINGBEAT_HZ, MAX_WINGBEAT_HZ), y_lim[0], DRONE_SPREAD_MPS, color="C2", alpha=0.16, lw=0,
                    label=f"bird: wingbeat {MIN_WINGBEAT_HZ:g}-{MAX_WINGBEAT_HZ:g} Hz, half-width <= {DRONE_SPREAD_MPS:g} m/s")
    ax.axhline(DRONE_SPREAD_MPS, color="k", ls="--", lw=1, label=f"half-width threshold {DRONE_SPREAD_MPS:g} m/s")
    strip.axhline(DRONE_SPREAD_MPS, color="k", ls="--", lw=1)
    markers = {"drone": ("^", "C0"), "bird": ("o", "C2"), "none": ("x", "C3")}
    no_target = []
    for label, (marker, colour) in markers.items():
        chosen = np.array([row["class"] == label for row in rows], dtype=bool)
        placed = chosen & has_rate
        alone = chosen & ~has_rate & has_width
        ax.scatter(rate[placed], width[placed], marker=marker, color=colour, zorder=3,
                   label=f"{label} ({int(chosen.sum())})")
        strip.scatter(np.zeros(int(alone.sum())), width[alone], marker=marker, color=colour, zorder=3)
        for i in np.flatnonzero(placed):
            ax.annotate(_label(rows[i]), (rate[i], width[i]), xytext=(4, 3),
                        textcoords="offset points", fontsize=7)
        for i in np.flatnonzero(alone):
            strip.annotate(_label(rows[i]), (0, width[i]), xytext=(0, 5), textcoords="offset points",
                           fontsize=6.5, ha="center")
        no_target += [_name(rows[i]["file"]) for i in np.flatnonzero(chosen & ~has_width)]
    ax.set_xscale("log")
    ax.set_yscale("log")
    for axis in (ax.xaxis, ax.yaxis):  # minor ticks and grid at 2 and 5 only: each tick is an artist to draw
        axis.set_minor_locator(LogLocator(subs=MINOR_LOG_SUBS))
        axis.set_major_formatter(FuncFormatter(_plain))  # 0.1, 1, 10: no mathtext (a quarter of the drawing)
        axis.set_minor_formatter(NullFormatter())
    ax.set_xlim(*x_lim)
    ax.set_ylim(*y_lim)
    strip.set_xlim(-1, 1)
    strip.set_xticks([])
    strip.set_xlabel("no periodicity")
    strip.set_ylabel("micro-Doppler half-width (m/s)")
    strip.grid(alpha=0.3, axis="y", which="both")
    ax.tick_params(labelleft=False)
    ax.set_xlabel("periodicity: chopping frequency or wingbeat (Hz)")
    _title(ax, f"{len(rows)} rows from {len({row['file'] for row in rows})} captures: class regions of "
           "mdpipe.process.classify", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    key.legend(*ax.get_legend_handles_labels(), **LEGEND)
    listed = ", ".join(no_target[:MAX_LISTED]) + (f" and {len(no_target) - MAX_LISTED} more" if len(no_target) > MAX_LISTED else "")
    fig.supxlabel(f"no moving target ({len(no_target)}): {listed or 'none'}", fontsize=8, x=EDGE_IN / 11,
                  y=EDGE_IN / 6, ha="left", va="bottom")
    _arrange(fig, [(ax, key)], left_in=LEFT_ROOM_IN + SUMMARY_STRIP_IN + SUMMARY_GAP_IN,
             bottom_in=BOTTOM_ROOM_IN + 0.25)
    x0, y0, w, h = ax.get_position().bounds
    strip.set_position((x0 - (SUMMARY_STRIP_IN + SUMMARY_GAP_IN) / 11, y0, SUMMARY_STRIP_IN / 11, h))
    return fig
