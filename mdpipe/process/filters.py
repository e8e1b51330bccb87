"""Running filters, local maxima and their sub-sample refinement, and a robust scatter, on 1-D signals (numpy;
scipy.ndimage costs 0.25 s to import, a tenth of a capture's run).

Edges are handled as scipy.ndimage's ``mode="nearest"`` (the edge value repeated), ``mode="wrap"`` or
``mode="constant"`` (zeros); tests check the results against scipy.ndimage. ``moving_average`` also takes
``mode="inside"``: the mean of the neighbours that lie inside the signal (no value repeated: one edge sample
of a strong tone, repeated, is no average of anything).
"""

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

MEDIAN_CHUNK = 4096  # samples a running median takes at once (its windows' copy bounded)


def _padded(x, size, mode, axis):
    before = size // 2
    after = size - 1 - before
    widths = [(0, 0)] * x.ndim
    widths[axis] = (before, after)
    return np.pad(x, widths, mode={"nearest": "edge", "wrap": "wrap", "constant": "constant"}[mode])


def moving_average(x, size, *, mode="nearest", axis=-1):
    """Mean over ``size`` neighbours centred on each sample (scipy.ndimage.uniform_filter1d), or with
    ``mode="inside"`` over those of them inside ``x``."""
    x = np.asarray(x, dtype=np.float64)
    if size <= 1:
        return x.copy()
    if mode == "inside":  # zeros beyond the edges, over the share of the window inside
        shape = [1] * x.ndim
        shape[axis] = -1
        counts = moving_average(np.ones(x.shape[axis]), size, mode="constant")
        return moving_average(x, size, mode="constant", axis=axis) / counts.reshape(shape)
    padded = np.moveaxis(_padded(x, size, mode, axis), axis, -1)
    total = np.cumsum(padded, axis=-1)
    total = np.concatenate([np.zeros(total.shape[:-1] + (1,)), total], axis=-1)
    return np.moveaxis((total[..., size:] - total[..., :-size]) / size, -1, axis)


def triangular_average(signal, size, *, axis=-1):
    """Triangular moving average over ``2 size - 1`` samples (two boxcars of ``size``) along ``axis``, real and
    imaginary parts, of the samples inside the signal (``mode="inside"``: at its ends, an edge value repeated would
    pass for a line). A constant passes unchanged; its frequency response's first null lies at ``1 / size`` cycles a
    sample."""
    signal = np.asarray(signal)

    def smooth(x):
        return moving_average(moving_average(x, size, mode="inside", axis=axis), size, mode="inside", axis=axis)
    if not np.iscomplexobj(signal):
        return smooth(signal)
    return smooth(signal.real) + 1j * smooth(signal.imag)


def running_min(x, size):
    """Minimum over ``size`` neighbours centred on each sample (scipy.ndimage.minimum_filter1d, nearest)."""
    return sliding_window_view(_padded(np.asarray(x), size, "nearest", 0), size).min(axis=-1)


def running_max(x, size):
    """Maximum over ``size`` neighbours centred on each sample (scipy.ndimage.maximum_filter1d, nearest)."""
    return sliding_window_view(_padded(np.asarray(x), size, "nearest", 0), size).max(axis=-1)


def running_median(x, size, *, mode="nearest"):
    """Median over ``size`` (odd) neighbours centred on each sample (scipy.ndimage.median_filter; ``mode``
    ``"nearest"``, or ``"wrap"`` for a circular axis such as a Doppler span). Taken ``MEDIAN_CHUNK`` samples at a
    time: the median copies its windows, ``size`` values a sample (a window of 257 over a long capture's 100 000
    spectrum bins: 206 MB at once, 8 MB a chunk)."""
    windows = sliding_window_view(_padded(np.asarray(x), size, mode, 0), size)
    if len(windows) <= MEDIAN_CHUNK:
        return np.median(windows, axis=-1)
    return np.concatenate([np.median(windows[start:start + MEDIAN_CHUNK], axis=-1)
                           for start in range(0, len(windows), MEDIAN_CHUNK)])


def local_maxima(values):
    """Indices of the interior samples above their left neighbour and not below their right one (a plateau
    counts once, at its left end); NaN never is one."""
    v = np.where(np.isfinite(values), values, -np.inf)
    return np.flatnonzero((v[1:-1] > v[:-2]) & (v[1:-1] >= v[2:])) + 1


def robust_sigma(values):
    """Standard deviation of Gaussian scatter in ``values`` from their median absolute deviation (1.4826 MAD):
    outliers (flashes in a power, stray edges) do not raise it."""
    values = np.asarray(values)
    return 1.4826 * np.median(np.abs(values - np.median(values)))


def least_squares_line(x, y):
    """The least-squares straight line through the points ``(x, y)``, at ``x``."""
    return np.polyval(np.polyfit(x, y, 1), x)


def parabolic_offset(left, mid, right):
    """Where, within +-0.5 sample of ``mid``, the parabola through three equally spaced values peaks; 0 where
    they do not curve down (a slope or a plateau). Elementwise.

    Clipped: off a true maximum (a sample at the edge of a search window, on a slope) the vertex lies
    outside the three samples, arbitrarily far when they are nearly in line (a lag of -8291 samples
    was refined from a window's edge).
    """
    left, mid, right = (np.asarray(v, dtype=np.float64) for v in (left, mid, right))
    curvature = left - 2 * mid + right
    down = curvature < 0
    return np.where(down, np.clip(0.5 * (left - right) / np.where(down, curvature, -1.0), -0.5, 0.5), 0.0)
