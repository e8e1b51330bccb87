"""Measurements on Doppler spectra: occupied band and aliasing, the paper's bandwidth rule, flash edges.

Frequencies are centred (``-PRF/2 .. PRF/2``), paper sign.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.process.doppler import noise_level_per_bin, spectrogram
from mdpipe.process.filters import least_squares_line, moving_average, robust_sigma

OCCUPIED_DB = 10.0        # micro-Doppler "present" this far above the noise level (smoothed) ...
LINE_DB = 15.0            # ... or in a single bin this far above it (noise: once in 5e13 bins)
EDGE_FRACTION = 0.02      # within 2 % of the span's ends counts as touching them
FILLED_FRACTION = 0.9     # a band over 90 % of the span has filled it
HALF_AMPLITUDE_DB = 20 * np.log10(2)  # 6.02 dB: half amplitude, the edge of a rect spectrum
FLASH_PERCENTILE = 80      # flash frames: local maxima of the frames' power in its top fifth (they tell whether the
                           # flashes fill the span) ...
EDGE_PERCENTILE = 50       # ... and edges are read on those in its top half: a point blade's grating flashes, off
                           # broadside, can outshine its broadside ones (:func:`broadside`)
EDGE_PLATEAU_DB = 15.0    # a flash whose edges are read stands this far above the noise (at 10 dB: +4 % spread)
EDGE_TIP_DB = 6.0         # ... its spectrum's trend at an edge this far, to read the edge against the trend
TREND_SHARES = (0.3, 0.8)  # a flash's plateau trend is fitted this far out from 0 Hz towards its edge
TIP_BRIGHT = 1.5          # ... and read above the plateau's median where it reaches this many times its amplitude
                          # there (tips brighter than the root: 2.0-2.3; uniform blades 1.0-1.2, their Doppler piling
                          # up towards the tips' over a long frame)
EDGE_PAD = 8              # flash frames transformed on this many times their bins (zero-padded): the half-amplitude
                          # crossing read on the spectrum, not interpolated between bins (a uniform blade whose tips
                          # span 7.6 bins a side read -1.6 %, now 0.0 %)
MAX_RIPPLE = 0.15         # a flash frame's plateau rippling more holds two flashes (:func:`plateau_ripple`; one
                          # flash, 15 dB over the noise: at most 0.15 in 9 frames of 10)
ONE_SIDED_SHARE = 0.8     # a flash edge this share of the frame's other edge (from 0 Hz) or more is a tip's
BROADSIDE_SPREAD = 0.08   # flash edges within this share of the widest ones are the broadside flashes'
                          # (:func:`broadside`; rotors 1-4 % apart in rate all count)
BROADSIDE_SHARE = 0.2     # ... the widest ones: the edge this share of the frames from the top (3 at least)


@dataclass(frozen=True)
class Band:
    """Occupied Doppler band of a spectrum: extent (Hz) with its single lines, fraction of the span, aliasing
    verdict and why, and the extent of the dense part (the smoothed spectrum over its threshold; NaN if none)."""

    low_hz: float
    high_hz: float
    fraction: float
    aliased: bool
    reason: str
    dense_low_hz: float = np.nan
    dense_high_hz: float = np.nan


def occupied_band(spectrum, noise_level, *, smooth_hz):
    """Where the spectrum (smoothed over ``smooth_hz``) stands ``OCCUPIED_DB`` above ``noise_level``, or
    a single bin of it ``LINE_DB`` above: the sparse line comb of rotors whose lines stand well out of
    the noise but whose average over the smoothing width does not (lines 200 Hz apart, 18 dB over the
    noise, average 6 dB over 70 Hz).

    Aliased when the band fills the span or reaches both of its ends: the micro-Doppler then wraps
    and its true extent is unknown.
    """
    f, power = spectrum.f_hz, spectrum.power
    width = max(1, int(round(smooth_hz / spectrum.resolution_hz)))
    envelope = moving_average(power, width, mode="wrap")
    occupied = envelope > noise_level * 10 ** (OCCUPIED_DB / 10)
    occupied_or_lines = occupied | (power > noise_level * 10 ** (LINE_DB / 10))
    if not occupied_or_lines.any():
        return Band(np.nan, np.nan, 0.0, False, "no Doppler band above the noise")
    fraction = float(occupied.mean())
    edge = max(1, int(EDGE_FRACTION * len(f)))
    touches = occupied_or_lines[:edge].any() and occupied_or_lines[-edge:].any()
    index = np.flatnonzero(occupied_or_lines)
    aliased = fraction >= FILLED_FRACTION or touches
    reason = ""
    if aliased:
        reason = (f"micro-Doppler fills {fraction:.0%} of the span 1/Tp = {f[-1] - f[0] + spectrum.resolution_hz:.0f} Hz"
                  if fraction >= FILLED_FRACTION else "micro-Doppler reaches both ends of the span 1/Tp")
    dense = np.flatnonzero(occupied)
    dense_extent = (float(f[dense[0]]), float(f[dense[-1]])) if len(dense) else (np.nan, np.nan)
    return Band(float(f[index[0]]), float(f[index[-1]]), fraction, bool(aliased), reason, *dense_extent)


def paper_extent(spectrum, *, threshold_db):
    """The paper's rule: the extent of the spectrum above its mean by ``threshold_db`` (None if nothing is)."""
    level = 10 * np.log10(np.mean(spectrum.power)) + threshold_db
    above = np.flatnonzero(10 * np.log10(spectrum.power + np.finfo(float).tiny) > level)
    if len(above) == 0:
        return None
    return float(spectrum.f_hz[above[0]]), float(spectrum.f_hz[above[-1]])


def _tip_edge(column, f_hz, index, step, *, plateau, noise_level, pad=1):
    """One side's Doppler edge of a flash frame ``column``, or None; ``index`` the outermost bin at a quarter of the
    ``plateau`` (a uniform blade's half amplitude) on the side ``step`` (-1 low, +1 high).

    A tapered blade's spectrum falls along its plateau with its reflectivity: a quarter of the median then
    lies inside the tips (-9 % for a tip reflectivity of 0.22); a blade brighter at its tips rises, and a quarter
    of the median lies outside them (+7 % for tips twice the root's, ``benchmarks/offmodel``).
    The side's amplitude trend, fitted between ``TREND_SHARES`` of the way from 0 Hz to the edge, gives the
    level at the edge; the edge is where the spectrum falls to a quarter of that, the two found in turn three
    times over. A trend above the plateau's median counts only where it reaches ``TIP_BRIGHT`` times its
    amplitude (at most the frame's peak): a uniform blade's Doppler piles up towards its tips' over a long
    frame, and read so its r fell 1.5-2 % short.
    Where that level is not ``EDGE_TIP_DB`` above the noise (or the side holds too few bins for a trend),
    the edge found so far stands (at first, the plateau's quarter). None when the spectrum stays above
    the level to the span's end. ``pad``: the column's bins per bin of its frame (zero-padded); the trend needs 4
    of the frame's bins.
    """
    centre = int(np.argmin(np.abs(f_hz)))
    amplitude = np.sqrt(np.maximum(np.nan_to_num(column), 0.0))
    peak = float(np.nanmax(column))
    level = plateau * 10 ** (-HALF_AMPLITUDE_DB / 10)
    edge_hz = _crossing(column, f_hz, index, step, level)
    for _ in range(3):
        inner = [centre + step * k for k in range(1, abs(index - centre) + 1)
                 if TREND_SHARES[0] <= k / abs(index - centre) <= TREND_SHARES[1]]
        if len(inner) < 4 * pad:
            break
        trend = np.polyfit(np.abs(f_hz[inner]), amplitude[inner], 1)
        local = max(float(np.polyval(trend, abs(edge_hz))), 0.0) ** 2
        local = min(peak, local) if local > TIP_BRIGHT ** 2 * plateau else min(plateau, local)
        if local < noise_level * 10 ** (EDGE_TIP_DB / 10):
            break  # the tips' level is lost in the noise
        level = local * 10 ** (-HALF_AMPLITUDE_DB / 10)
        while index != centre and np.nan_to_num(column[index]) < level:  # the level rose above the last bin
            index -= step
        while 0 <= index + step < len(column) and np.nan_to_num(column[index + step]) >= level:
            index += step
        if not 0 <= index + step < len(column):
            return None  # above the level to the span's end
        edge_hz = _crossing(column, f_hz, index, step, level)
    return edge_hz


def plateau_ripple(column, f_hz, edge_hz):
    """How much a flash frame's amplitude spectrum (``column``, power) ripples between 0 Hz and its edge ``edge_hz``
    on that side: the RMS of its residual about a straight line (a uniform or tapered blade's plateau) over the inner
    60 % of the way, against the line's mean. One flash in the frame: a smooth plateau; two, ``dt`` apart: fringes
    ``1 / dt`` apart in Doppler, as deep as the weaker flash is strong; fringes wider than the inner part bend it as a
    taper would, unseen. 0 where that part holds under 8 of ``f_hz``'s bins."""
    inner = (np.abs(f_hz) > 0.2 * abs(edge_hz)) & (np.abs(f_hz) < 0.8 * abs(edge_hz)) & (f_hz * edge_hz > 0)
    if inner.sum() < 8:
        return 0.0
    amplitude = np.sqrt(np.maximum(np.nan_to_num(column[inner]), 0.0))
    line = least_squares_line(f_hz[inner], amplitude)
    level = float(np.mean(line))
    return float(np.sqrt(np.mean((amplitude - line) ** 2)) / level) if level > 0 else 0.0


def broadside(edges):
    """The tip edges of broadside flashes, from one side's ``(distance from 0 Hz, smooth)`` of each flash frame:
    the distances of the smooth frames (one flash alone lit them) within ``BROADSIDE_SPREAD`` of the widest.

    A blade's Doppler at any aspect is at most its broadside tips': a point of it at radius ``rho`` moves
    ``rho Omega sin(theta)`` along the line of sight. Blades of point scatterers spaced over ``lambda / 2`` also
    flash off broadside, in grating lobes at ``cos(theta_k) = k lambda / (2 d)``, and those flashes reach only
    ``sin(theta_k)`` of the tip Doppler: 16 points on a 30 cm blade at X band flash twice as often off broadside
    (to 0.53 of it) as on it, and the median of all edges read -47 %. Where rotors fly at rates apart, their
    broadside flashes often beat with the others' grating flashes while the grating flashes stand alone. The
    widest edges are therefore found among all frames, smooth or not: the edge ``BROADSIDE_SHARE`` of them from the
    top (the 3rd at least, against a stray wide one).
    """
    if not edges:
        return np.array([])
    reach_hz, smooth = np.array(edges, dtype=float).T
    rank = min(len(reach_hz), max(3, int(np.ceil(BROADSIDE_SHARE * len(reach_hz)))))
    widest = np.sort(reach_hz)[-rank]
    return reach_hz[(smooth > 0) & (reach_hz >= (1 - BROADSIDE_SPREAD) * widest)]


def _median_error(values):
    """Standard error of the median of ``values``: 1.2533 sigma / sqrt(n), sigma from the median absolute
    deviation (Gaussian scatter); NaN for fewer than 3 values."""
    if len(values) < 3:
        return np.nan
    return 1.2533 * robust_sigma(values) / np.sqrt(len(values))


def _crossing(column, f_hz, index, step, level):
    a, b = column[index], column[index + step]
    t = (np.log(a) - np.log(level)) / (np.log(a) - np.log(b)) if a > b > 0 else 0.0
    return f_hz[index] + step * t * (f_hz[1] - f_hz[0])


@dataclass(frozen=True)
class FlashEdges:
    """Median Doppler edges of the blade flashes (None when no frame has both), frames used, frames filled, the frames'
    length; the standard error of the edges' distance and the number of edges counted on the side with fewer."""

    low_hz: float
    high_hz: float
    n_frames: int
    n_filled: int
    window_s: float            # the frames' length, whole chirps
    spread_hz: float = np.nan  # standard error of high_hz - low_hz, from the frames' scatter about their medians
    n_edges: int = 0           # edges read on the side with fewer

    @property
    def fills_span(self):
        """Most (and at least three) flashes spread over the whole span: the tips alias."""
        return self.n_filled >= 3 and self.n_filled > self.n_frames / 2


def flash_edges(signal, *, prf_hz, window_s, noise_power, differenced=False, hop_fraction=0.125):
    """Doppler edges of the blade flashes, from a spectrogram of window ``window_s`` and hop ``hop_fraction`` of it.

    For the edges the window should be a quarter chopping period (it holds one flash whole); to see
    whether flashes fill the span, any window a few chirps long does.

    A broadside blade's echo is a sinc in time whose spectrum is a rectangle reaching the tip
    Doppler on both sides. In each flash frame (a local maximum of the frames' total power, in its top
    half: ``EDGE_PERCENTILE``) the edges are where the spectrum falls to half amplitude (-6.02 dB) of the
    frame's plateau (median over its occupied part): for any symmetric window kernel the rectangle's edge
    lies there; each side's median is over the broadside flashes' edges (:func:`broadside`). A frame whose
    plateau reaches both ends of the span has no edges: its tips alias (counted among the frames in the
    power's top fifth, ``FLASH_PERCENTILE``, as ``n_filled`` of ``n_frames``).
    A blade alone flashes on one side: an odd-N rotor's blade has no opposite one, so each of its flashes
    reaches the tip Doppler on one side only (from the root's on that side), and its other side's edge is
    no tip's (0.4-0.7 of it, seen on 3-blade rotors). A side's edge counts only when it reaches
    ``ONE_SIDED_SHARE`` of the frame's other side; each side's median is over the edges that count.
    The noise level (``noise_power`` per chirp of the undifferenced echo) is taken out of each frame;
    frames whose plateau is not ``EDGE_PLATEAU_DB`` above it are not flashes to read edges on and are
    left out (``OCCUPIED_DB`` for a differenced echo, whose frames only tell whether they fill the span).
    ``differenced``: ``signal`` is a first difference; its response ``|2 sin(pi f / PRF)|^2`` is
    divided out, and the two bins around 0 Hz (where it vanishes) are left out.
    """
    pad = 1 if differenced else EDGE_PAD  # a differenced echo's frames only tell whether they fill the span
    spec = spectrogram(signal, prf_hz=prf_hz, window_s=window_s, hop_s=window_s * hop_fraction, pad=pad)
    power, f = spec.power, spec.f_hz
    noise_level = noise_level_per_bin(noise_power, int(round(spec.window_s * prf_hz)))
    if differenced:
        response = (2 * np.sin(np.pi * f / prf_hz)) ** 2
        near_zero = np.abs(f) <= 2 * (f[1] - f[0])
        power = np.where(near_zero[:, None], np.nan, power / np.where(near_zero, 1.0, response)[:, None])
    total = np.nansum(power, axis=0) if differenced else power.sum(axis=0)  # (NaN only near 0 Hz, differenced)
    flash_level = np.percentile(total, FLASH_PERCENTILE)
    edge_level = flash_level if differenced else np.percentile(total, EDGE_PERCENTILE)
    frames = np.flatnonzero((total > np.roll(total, 1)) & (total >= np.roll(total, -1)) & (total > edge_level))
    strong = total[frames] > flash_level
    lows, highs, filled, used = [], [], 0, 0
    for frame, counted in zip(frames, strong):
        # the noise adds its level to every bin: left in, it lifts the flank outside the edges and a weak
        # flash reads wider (+5 % at a plateau 12 dB over the noise); its expectation is taken out
        column = power[:, frame] if differenced else np.maximum(power[:, frame] - noise_level, 0.0)
        valid = column[np.isfinite(column)]
        lit = valid[valid > np.percentile(valid, 99) * 1e-2]
        if not len(lit):  # the frame stands nowhere over the noise's expectation
            continue
        plateau = np.median(lit)
        if plateau < noise_level * 10 ** ((OCCUPIED_DB if differenced else EDGE_PLATEAU_DB) / 10):
            continue
        used += counted
        level = plateau * 10 ** (-HALF_AMPLITUDE_DB / 10)
        above = np.flatnonzero(np.nan_to_num(column, nan=level) >= level)
        if above[0] == 0 and above[-1] == len(f) - 1:
            filled += counted
            continue
        if above[0] == 0 or above[-1] == len(f) - 1:
            continue
        low = _tip_edge(column, f, above[0], -1, plateau=plateau, noise_level=noise_level, pad=pad)
        high = _tip_edge(column, f, above[-1], 1, plateau=plateau, noise_level=noise_level, pad=pad)
        if low is None or high is None:
            continue
        reach = max(-low, high)
        # a side's edge is a tip's where it reaches near the other's; one flash alone lit it where its plateau is
        # smooth (two beat: ``plateau_ripple``)
        if -low >= ONE_SIDED_SHARE * reach:
            lows.append((-low, plateau_ripple(column, f, low) <= MAX_RIPPLE))
        if high >= ONE_SIDED_SHARE * reach:
            highs.append((high, plateau_ripple(column, f, high) <= MAX_RIPPLE))
    lows, highs = -broadside(lows), broadside(highs)
    if not len(lows) or not len(highs):
        return FlashEdges(None, None, used, filled, spec.window_s)
    return FlashEdges(float(np.median(lows)), float(np.median(highs)), used, filled, spec.window_s,
                      float(np.hypot(_median_error(lows), _median_error(highs))), min(len(lows), len(highs)))
