"""Every figure kind, rendered from small captures: nothing outside the canvas, no two panels overlapping.

A figure is checked as drawn: after ``fig.canvas.draw()`` every visible artist's extent (clipped to
its clip box, as it is painted) must lie on the canvas, and the tight bounding boxes of any two
axes (panel with its ticks, labels, title and secondary axes; colour bars) must not intersect.
"""

import copy
from pathlib import Path

import matplotlib
import numpy as np
import pytest

from conftest import XBAND, scene_mapping, simulate
from mdpipe.errors import ParameterError
from mdpipe.params import FigureParams, ProcessParams
from mdpipe.process import classify
from mdpipe.process.pipeline import process_capture
from mdpipe.report import plots

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ("phantom4_xband", "fimi_1rx", "gull_flyby", "clutter_only")
TOLERANCE_PX = 1.0
QUAD = {"type": "multirotor", "name": "quad", "motion": {"position_m": [40.0, 0.0, 0.0], "velocity_mps": [-2.0, 0, 0]},
        "body_rcs_m2": 0.01, "rotors": {"count": 4, "arm_m": 0.2, "blade_length_m": 0.12, "root_m": 0.01,
                                        "rev_per_s": [90, -90, 90, -90], "phase_deg": [0, 30, 65, 100],
                                        "blade_rcs_m2": 0.01}}


def drawn_extents(fig, renderer):
    """(description, window extent) of every visible artist as painted: clipped to its clip box.

    An axis counts as one artist (its ticks, tick labels and label as drawn: ticks outside the view
    exist but are not painted).
    """
    found = []

    def walk(artist):
        hidden = isinstance(artist, matplotlib.axes.Axes) and not artist.axison  # ax.axis("off"): not drawn
        for child in artist.get_children():
            if not child.get_visible() or child is fig.patch:
                continue
            if isinstance(child, matplotlib.text.Text) and not child.get_text():
                continue
            if hidden and isinstance(child, (matplotlib.axis.Axis, matplotlib.spines.Spine)):
                continue
            if isinstance(child, matplotlib.axes.Axes):  # its parts are checked one by one
                walk(child)
                continue
            bbox = child.get_tightbbox(renderer)
            if bbox is not None and (bbox.width > 0 or bbox.height > 0):
                text = child.get_text() if isinstance(child, matplotlib.text.Text) else ""
                found.append((f"{type(child).__name__} {text!r}".strip(), bbox))
            if not isinstance(child, matplotlib.axis.Axis):
                walk(child)

    walk(fig)
    return found


def layout_problems(fig):
    """Artists off the canvas and overlapping pairs of axes, as lists of descriptions."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    canvas = fig.bbox
    outside = [f"{name}: {bbox.bounds}" for name, bbox in drawn_extents(fig, renderer)
               if bbox.x0 < canvas.x0 - TOLERANCE_PX or bbox.y0 < canvas.y0 - TOLERANCE_PX
               or bbox.x1 > canvas.x1 + TOLERANCE_PX or bbox.y1 > canvas.y1 + TOLERANCE_PX]
    boxes = [(ax, ax.get_tightbbox(renderer)) for ax in fig.axes]
    overlaps = []
    for i, (a, box_a) in enumerate(boxes):
        for b, box_b in boxes[i + 1:]:
            width = min(box_a.x1, box_b.x1) - max(box_a.x0, box_b.x0)
            height = min(box_a.y1, box_b.y1) - max(box_a.y0, box_b.y0)
            if width > TOLERANCE_PX and height > TOLERANCE_PX:
                overlaps.append(f"{a.get_title() or a.get_label()!r} and {b.get_title() or b.get_label()!r}")
    return outside, overlaps


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """The bundled samples (drone X band, drone 76 GHz aliased, bird, nothing) and a two-drone scene."""
    found = {name: process_capture(ROOT / "data_samples" / f"{name}.h5", ProcessParams()) for name in SAMPLES}
    far = copy.deepcopy(QUAD)
    far["motion"] = {"position_m": [70.0, 0.0, 0.0]}
    far["body_rcs_m2"] = 0.1
    far["rotors"].update(rev_per_s=[60, -60, 60, -60], blade_rcs_m2=0.1)
    path, _ = simulate(tmp_path_factory.mktemp("two"), scene_mapping(XBAND | {"n_chirps": 3000}, [QUAD, far],
                                                                    noise={"snr_db": 10.0}))
    found["two_drones"] = process_capture(path, ProcessParams())
    return found


def test_the_captures_cover_every_case(results):
    """Drone, bird, none, aliased and a two-target capture: the figures below see every case."""
    classes = {name: [row["class"] for row in result.rows] for name, result in results.items()}
    assert classes["phantom4_xband"] == ["drone"] and classes["gull_flyby"] == ["bird"]
    assert classes["clutter_only"] == ["none"] and not results["clutter_only"].analyses
    assert results["fimi_1rx"].rows[0]["aliased"] is True
    assert classes["two_drones"] == ["drone", "drone"]


def check(fig):
    outside, overlaps = layout_problems(fig)
    plt.close(fig)
    assert not outside, f"{len(outside)} artist(s) outside the canvas: {outside}"
    assert not overlaps, f"{len(overlaps)} overlapping pair(s) of axes: {overlaps}"


@pytest.mark.parametrize("name", SAMPLES + ("two_drones",))
@pytest.mark.parametrize("kind", ["range", "spectrogram", "spectrum"])
def test_capture_figures_fit_the_canvas(results, name, kind, monkeypatch):
    result = results[name]
    if kind != "range" and not result.analyses:
        pytest.skip("no target: only the range figure is drawn")
    figures = []
    monkeypatch.setattr(plots, "_save", lambda fig, path, description: figures.append(fig))
    getattr(plots, f"{kind}_figure")(result, "unused.png")
    check(figures[0])


@pytest.mark.parametrize("limits", ["full", "-500,800"])
def test_doppler_limits_keep_the_layout(results, limits, monkeypatch):
    figures = []
    monkeypatch.setattr(plots, "_save", lambda fig, path, description: figures.append(fig))
    options = FigureParams.from_text(limits)
    plots.spectrum_figure(results["two_drones"], "unused.png", options)
    plots.spectrogram_figure(results["gull_flyby"], "unused.png", options)
    for fig in figures:
        check(fig)


def test_summary_figure_fits_the_canvas(results, monkeypatch):
    rows = [row for result in results.values() for row in result.rows]
    figures = []
    monkeypatch.setattr(plots, "_save", lambda fig, path, description: figures.append(fig))
    plots.summary_figure(rows, "unused.png")
    strip, main = figures[0].axes[:2]
    placed = np.concatenate([c.get_offsets() for c in main.collections
                             if isinstance(c, matplotlib.collections.PathCollection)])
    with_rate = [r for r in rows if (r["chopping_freq_hz"] or r["wingbeat_freq_hz"]) is not None]
    assert len(placed) == len(with_rate) == 5  # 2 + 1 + 2 drones/birds; the clutter row is not invented a point
    assert sorted(t.get_text() for t in main.texts) == sorted(
        ["phantom4_xband #0", "fimi_1rx #0 (aliased: at least)", "gull_flyby #0", "capture #0", "capture #1"])
    assert [line.get_ydata()[0] for line in main.lines] == [classify.DRONE_SPREAD_MPS]
    assert figures[0].get_supxlabel() == "no moving target (1): clutter_only.h5"
    check(figures[0])


def test_the_check_finds_a_title_off_the_canvas():
    """The check itself: a title pushed above the figure and two panels on top of each other are caught."""
    fig, (a, b) = plt.subplots(2, 1, figsize=(4, 3))
    a.set_title("a title far too long to fit a narrow figure " * 3)
    b.set_position(a.get_position())
    outside, overlaps = layout_problems(fig)
    plt.close(fig)
    assert any("far too long" in item for item in outside)
    assert len(overlaps) == 1


def test_png_bytes_are_reproducible(results, tmp_path):
    """The same result gives the same PNG bytes, with no software version or machine path inside (make paper)."""
    first, second = tmp_path / "a" / "x_spectrum.png", tmp_path / "b" / "x_spectrum.png"
    for path in (first, second):
        path.parent.mkdir()
        plots.spectrum_figure(results["phantom4_xband"], path)
    data = first.read_bytes()
    assert data == second.read_bytes()
    assert b"Software" not in data and b"matplotlib" not in data.lower()
    assert str(ROOT).encode() not in data and b"Doppler power spectra of phantom4_xband.h5" in data


def test_auto_doppler_view_holds_the_blades_and_zooms(results):
    """Phantom 4 (Table I config 7): tips at +-2 Omega r / lambda = +-3757 Hz inside a view narrower than the
    +-12.5 kHz span; the aliased FIMI gets the whole span; given limits are kept as given."""
    result = results["phantom4_xband"]
    (low, high), text = plots._doppler_view_hz(result.analyses[0], result.rows[0], result.noise_power,
                                               result.params.prf_hz, FigureParams())
    tip_hz = 2 * (2 * np.pi * 70.0) * 0.13 / result.rows[0]["wavelength_m"]
    assert tip_hz == pytest.approx(3757, abs=2)
    assert low < -tip_hz and high > tip_hz and high - low < 0.6 * result.params.prf_hz
    assert "(occupied band) of the unambiguous +-12500 Hz" in text
    fimi = results["fimi_1rx"]
    limits, text = plots._doppler_view_hz(fimi.analyses[0], fimi.rows[0], fimi.noise_power, fimi.params.prf_hz,
                                          FigureParams())
    assert limits == (-fimi.params.prf_hz / 2, fimi.params.prf_hz / 2) and text.startswith("the whole unambiguous")
    limits, _ = plots._doppler_view_hz(fimi.analyses[0], fimi.rows[0], fimi.noise_power, fimi.params.prf_hz,
                                       FigureParams.from_text("-500,800"))
    assert limits == (-500.0, 800.0)


@pytest.mark.parametrize("text, message", [
    ("wide", r"--doppler-limits 'wide': give auto, full or LOW,HIGH in Hz \(e.g. -500,800\)"),
    ("1,2,3", r"--doppler-limits '1,2,3'"),
    ("800,-500", r"doppler_limits=\(800, -500\) must have LOW < HIGH within \+-1e\+07 Hz"),
    ("nan,5", r"must have LOW < HIGH within"),
    ("-1e308,1e308", r"must have LOW < HIGH within \+-1e\+07 Hz"),
])
def test_doppler_limits_refused(text, message):
    with pytest.raises(ParameterError, match=message):
        FigureParams.from_text(text)


def test_cli_doppler_limits(tmp_path, monkeypatch):
    """`process --doppler-limits` reaches the figures' Doppler axes; a bad value is one line and no files."""
    from click.testing import CliRunner

    from mdpipe.cli import main

    capture = str(ROOT / "data_samples" / "gull_flyby.h5")
    bad = CliRunner().invoke(main, ["process", capture, "--out", str(tmp_path / "bad"), "--doppler-limits", "wide"])
    assert bad.exit_code != 0 and bad.output.strip().splitlines() == [
        "Error: --doppler-limits 'wide': give auto, full or LOW,HIGH in Hz (e.g. -500,800)"]
    assert not (tmp_path / "bad").exists()
    figures = {}
    monkeypatch.setattr(plots, "_save", lambda fig, path, description: figures.update({Path(path).name: fig}))
    good = CliRunner().invoke(main, ["process", capture, "--out", str(tmp_path), "--doppler-limits=-500,800"])
    assert good.exit_code == 0
    assert figures["gull_flyby_spectrum.png"].axes[0].get_xlim() == (-500.0, 800.0)
    assert figures["gull_flyby_spectrogram.png"].axes[0].get_ylim() == (-500.0, 800.0)
    for fig in figures.values():
        plt.close(fig)
