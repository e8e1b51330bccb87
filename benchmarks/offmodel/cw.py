"""The scenes of this folder as a continuous-wave (CW) radar records them: complex baseband I/Q, one RX, written
as mdpipe's HDF5 I/Q layout (``/IQ`` complex64, attributes ``fc`` and ``fs``). Numpy, scipy and h5py only;
nothing from mdpipe.

Each scatterer of a scene's targets (``echo.Drone``, ``echo.Bird``, ``echo.Static``) at range R(t) adds
``A exp(-j 4 pi fc R(t) / c)`` (approaching: positive Doppler), fc the scene's carrier (the FMCW sweep's
centre), recorded at the scene's PRF in one of two ways:

* ``filtered`` (a sound card's or an SDR's receiver): the echo computed at a multiple of the rate that holds its
  whole Doppler extent, then low-passed (a Kaiser-windowed FIR, polyphase) and decimated: micro-Doppler beyond half
  the rate is cut off, none folds, and a flash shorter than a sample is spread over one rather than missed;
* ``sampled`` (a sample-and-hold without a filter): the echo at the samples' instants only: the Doppler folds as
  the FMCW capture's does, and a flash shorter than a sample is caught only where a sample falls in it.

Noise: complex white Gaussian, added at the recorded rate, its power set so that the SNR per I/Q sample of the
moving echo (what a static removal keeps) is the FMCW capture's per slow-time sample: the scene's SNR per IF
sample plus the range FFT's gain over N samples, less the Hann window's 1.76 dB.
"""
import math

import h5py
import numpy as np

import echo

C = 299792458.0
HANN_LOSS_DB = 1.76
BLOCK = 4096


def echo_at(objects, t, fc):
    """The echo (n,) complex at instants ``t`` and the part of it that moves (all but ``echo.Static``)."""
    total = np.zeros(len(t), complex)
    moving = np.zeros(len(t), complex)
    for target in objects:
        for first in range(0, len(t), BLOCK):
            ranges = np.linalg.norm(target.pos(t[first:first + BLOCK]), axis=-1)  # (T, S)
            part = (np.exp(-4j * np.pi * fc / C * ranges) * target.amp[None, :]).sum(axis=1)
            total[first:first + BLOCK] += part
            if not isinstance(target, echo.Static):
                moving[first:first + BLOCK] += part
    return total, moving


def oversampling(scene, truth, fs):
    """The whole multiple of ``fs`` that holds the echo's Doppler extent (the tips' and the body's, or a bird's
    wings) with a quarter to spare."""
    extent_hz = truth.get("tip_hz", 0.0) + 2 * abs(truth.get("body_v", 0.0)) / truth["lam"]
    if truth["kind"] == "bird":
        extent_hz = 2 * (abs(truth.get("body_v", 0.0)) + 2 * np.pi * truth["wb"] * truth["span"]) / truth["lam"]
    return max(1, int(math.ceil(2.5 * extent_hz / fs)))


def iq(scene, objects, truth, seed, *, filtered=True):
    """The scene's I/Q samples (n,) complex128, sample rate (Hz), carrier (Hz) and noise power per sample (V^2)."""
    from scipy.signal import resample_poly

    radar = scene["radar"]
    fc = radar["f0"] + radar["B"] / 2
    fs = 1.0 / radar["Tp"]
    n = radar["M"]
    m = oversampling(scene, truth, fs) if filtered else 1
    total, moving = echo_at(objects, np.arange(n * m) / (fs * m), fc)
    if m > 1:
        total = resample_poly(total, 1, m, window=("kaiser", 8.0))[:n]
        moving = resample_poly(moving, 1, m, window=("kaiser", 8.0))[:n]
    rng = np.random.default_rng(seed)
    power = np.mean(np.abs(moving - moving.mean()) ** 2)
    snr_db = scene["snr"] + 10 * math.log10(radar["N"]) - HANN_LOSS_DB
    sigma = math.sqrt(power / 10 ** (snr_db / 10) / 2) if power > 0 else 1e-3
    return total + sigma * (rng.standard_normal(n) + 1j * rng.standard_normal(n)), fs, fc, 2 * sigma ** 2


def write(path, samples, fs, fc, noise_power):
    """The HDF5 I/Q layout; the noise power the echo was given is kept as an attribute mdpipe does not read."""
    with h5py.File(path, "w") as h5:
        h5.attrs["fc"] = float(fc)
        h5.attrs["fs"] = float(fs)
        h5.attrs["Creator"] = "mdpipe benchmarks/offmodel cw"
        h5.attrs["noise_power_v2"] = float(noise_power)
        h5.create_dataset("IQ", data=samples.astype(np.complex64))
