"""Shared helpers: small radars and scenes, and a reference range FFT for known-answer tests."""

import copy
import signal

import numpy as np
import pytest

from mdpipe.io import open_capture
from mdpipe.simulate.run import simulate_to_file
from mdpipe.simulate.scene import scene_from_mapping, scene_to_yaml

# 76 GHz Radarlog chirp with 256 samples (same 3.75 m bins as 2048 samples at 40 MHz over 51.2 us).
RADARLOG_SMALL = dict(f_start_hz=76.0e9, f_stop_hz=76.04e9, ramp_up_s=51.2e-6, chirp_period_s=64e-6,
                      sample_rate_hz=5.0e6, n_samples=256, n_chirps=1024, n_channels=1)
# 9.8 GHz, 20 MHz stand-in for the paper's radar: 7.5 m bins, PRF 40 kHz (1/80 s = 500 chirps).
XBAND = dict(f_start_hz=9.79e9, f_stop_hz=9.81e9, ramp_up_s=12.8e-6, chirp_period_s=25e-6,
             sample_rate_hz=5.0e6, n_samples=64, n_chirps=4000, n_channels=1)


def scene_mapping(radar, targets, **extra):
    return {"radar": copy.deepcopy(radar), "targets": copy.deepcopy(targets), **extra}


def simulate(tmp_path, mapping, name="capture.h5"):
    """Simulate ``mapping`` into ``tmp_path/name``; return (path, truth)."""
    path = tmp_path / name
    truth = simulate_to_file(scene_from_mapping(mapping), path, scene_yaml=scene_to_yaml(mapping))
    return path, truth


def range_profiles(path, *, channel=0):
    """Hann-windowed range FFT of every chirp of one channel, shape (chirps, N//2 + 1), and params."""
    with open_capture(path) as cap:
        samples = cap.read_chirps(0, cap.n_chirps, channels=[channel])[:, 0, :].astype(np.float64)
        params = cap.params
    return np.fft.rfft(samples * np.hanning(params.n_samples), axis=-1), params


def slow_time(path, range_bin, *, channel=0):
    """Complex slow-time signal of one range bin in the paper's Doppler convention (conjugated bin)."""
    profiles, params = range_profiles(path, channel=channel)
    return np.conj(profiles[:, range_bin]), params


@pytest.fixture
def tmp_capture(tmp_path):
    return lambda mapping, name="capture.h5": simulate(tmp_path, mapping, name)


def as_from_a_terminal():
    """``preexec_fn`` for a child that must see Ctrl-C as a user's shell delivers it: a runner started in the
    background (``cmd &``) passes SIGINT on ignored, and Python then never raises KeyboardInterrupt."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)

