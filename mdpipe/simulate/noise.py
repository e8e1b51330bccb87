"""Receiver noise: independent Gaussian samples per sample, chirp and channel, fast.

numpy's ziggurat costs ~8 ns per float32 normal here, against ~0.4 ns for the random bits
themselves. The Box-Muller transform ``(r cos t, r sin t)`` with ``r = sqrt(-2 ln u1)``,
``t = 2 pi u2`` turns two independent uniforms into two independent standard normals exactly; on
whole arrays it runs on numpy's SIMD log/sqrt/sin/cos in ~5 ns per sample. ``u1`` is drawn as a
float64 uniform (53 bits: the tail reaches 8.6 sigma; a float32 draw would stop at 5.8 sigma,
which 1.3 GB of samples would notice) and its log taken in float32 (small values keep their
magnitude there; 10 % faster than float64); ``t`` is a float32 uniform angle (2 pi / 2^24 steps).
"""

import numpy as np


def noise_streams(seed, n_channels):
    """One independent generator per RX channel (SFC64, the fastest of numpy's bit generators here).

    Channel k's stream depends only on the seed and k, so a capture with fewer channels holds the
    same noise on the channels it keeps.
    """
    return [np.random.Generator(np.random.SFC64(s)) for s in np.random.SeedSequence(seed).spawn(n_channels)]


def standard_normal_f32(rng, out, *, scale=1.0):
    """Fill the float32 array ``out`` with independent normals of standard deviation ``scale`` (Box-Muller).

    ``out`` must be C-contiguous; an odd size draws one extra normal that is discarded.
    """
    flat = out.reshape(-1)
    half = (flat.size + 1) // 2
    uniform = rng.random(half)
    np.subtract(1.0, uniform, out=uniform)  # (0, 1]: no log(0)
    radius32 = uniform.astype(np.float32)
    np.log(radius32, out=radius32)
    np.multiply(radius32, np.float32(-2.0 * scale * scale), out=radius32)
    np.sqrt(radius32, out=radius32)
    angle = rng.random(half, dtype=np.float32)
    np.multiply(angle, np.float32(2.0 * np.pi), out=angle)
    second = flat.size - half
    np.cos(angle, out=flat[:half])
    flat[:half] *= radius32
    np.sin(angle[:second], out=flat[half:])
    flat[half:] *= radius32[:second]
    return out
