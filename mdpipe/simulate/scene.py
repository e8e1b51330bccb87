"""Scene description: radar, targets, noise, ADC and model fidelity, read from YAML.

Lengths in metres, angles in degrees (``_deg``), rates in Hz; positions and velocities are
``[x, y, z]`` in the radar frame (x boresight, y along the RX array, z up).
"""

import dataclasses
import re
from dataclasses import dataclass, field
from typing import Optional

import numpy as np
import yaml

from mdpipe.errors import ParameterError
from mdpipe.params import RadarParams
from mdpipe.simulate.schema import NON_NEGATIVE, POSITIVE, Vec3, build, check

RADARLOG_RX_SPACING_M = 1.948e-3


@dataclass(frozen=True)
class RadarConfig:
    """The radar block: chirp parameters, capture length and RX layout."""

    f_start_hz: float = field(metadata=POSITIVE)
    f_stop_hz: float = field(metadata=POSITIVE)
    ramp_up_s: float = field(metadata=POSITIVE)
    chirp_period_s: float = field(metadata=POSITIVE)
    sample_rate_hz: float = field(metadata=POSITIVE)
    n_samples: int = field(metadata=check(lambda v: v >= 2, ">= 2"))
    n_chirps: int = field(metadata=check(lambda v: v >= 1, ">= 1"))
    n_channels: int = field(default=1, metadata=check(lambda v: 1 <= v <= 16, "between 1 and 16"))
    ramp_down_s: float = field(default=0.0, metadata=NON_NEGATIVE)
    rx_spacing_m: float = field(default=RADARLOG_RX_SPACING_M, metadata=POSITIVE)
    rx_positions_m: Optional[tuple[float, ...]] = None

    def __post_init__(self):
        if self.rx_positions_m is not None and len(self.rx_positions_m) < self.n_channels:
            raise ParameterError(
                f"rx_positions_m lists {len(self.rx_positions_m)} positions for n_channels={self.n_channels}")
        self.params  # validates the chirp parameters

    @property
    def params(self):
        """The :class:`RadarParams` this block describes."""
        if self.rx_positions_m is None:
            positions = tuple(self.rx_spacing_m * np.arange(self.n_channels))
        else:
            positions = self.rx_positions_m[: self.n_channels]
        return RadarParams(
            f_start_hz=self.f_start_hz, f_stop_hz=self.f_stop_hz, ramp_up_s=self.ramp_up_s,
            chirp_period_s=self.chirp_period_s, sample_rate_hz=self.sample_rate_hz,
            n_samples=self.n_samples, n_channels=self.n_channels, ramp_down_s=self.ramp_down_s,
            rx_positions_m=positions,
        )


@dataclass(frozen=True)
class Motion:
    """Straight-line motion plus an optional sway ``a (cos(2 pi t / T + phase) - cos(phase))``."""

    position_m: Vec3
    velocity_mps: Vec3 = (0.0, 0.0, 0.0)
    sway_amplitude_m: Vec3 = (0.0, 0.0, 0.0)
    sway_period_s: float = field(default=float("inf"), metadata=POSITIVE)
    sway_phase_deg: float = 0.0

    def __post_init__(self):
        if np.linalg.norm(self.position_m) == 0:
            raise ParameterError("position_m must not be the radar's own position [0, 0, 0]")

    @property
    def kwargs(self):
        """Keyword arguments of :func:`mdpipe.physics.kinematics.body_position_m`."""
        return dict(start_m=np.array(self.position_m), velocity_mps=np.array(self.velocity_mps),
                    sway_amplitude_m=np.array(self.sway_amplitude_m), sway_period_s=self.sway_period_s,
                    sway_phase_rad=np.deg2rad(self.sway_phase_deg))


@dataclass(frozen=True)
class Rotors:
    """The rotors of a multirotor; per-rotor entries take one value for all or one per rotor."""

    count: int = field(metadata=check(lambda v: v >= 1, ">= 1"))
    blade_length_m: float = field(metadata=POSITIVE)
    rev_per_s: tuple[float, ...] = field(metadata=check(lambda v: v != 0, "non-zero (sign = spin direction)"))
    blades: int = field(default=2, metadata=check(lambda v: v >= 1, ">= 1"))
    root_m: float = field(default=0.0, metadata=NON_NEGATIVE)
    arm_m: float = field(default=0.0, metadata=NON_NEGATIVE)
    layout_deg: Optional[tuple[float, ...]] = None
    phase_deg: tuple[float, ...] = (0.0,)
    blade_rcs_m2: float = field(default=1e-3, metadata=POSITIVE)
    points_per_blade: Optional[int] = field(default=None, metadata=check(lambda v: v >= 1, ">= 1"))

    def __post_init__(self):
        if self.root_m >= self.blade_length_m:
            raise ParameterError(f"root_m={self.root_m} must be shorter than blade_length_m={self.blade_length_m}")
        for name in ("rev_per_s", "phase_deg", "layout_deg"):
            values = getattr(self, name)
            if values is not None and len(values) not in (1, self.count):
                raise ParameterError(f"{name} has {len(values)} entries; give 1 or count={self.count}")

    def per_rotor(self, name):
        """Values of per-rotor entry ``name`` as an array of length ``count``."""
        values = getattr(self, name)
        if values is None:  # layout: evenly spaced, first arm at 45 deg (an X quad)
            return 45.0 + 360.0 * np.arange(self.count) / self.count
        return np.broadcast_to(np.asarray(values, dtype=np.float64), (self.count,))


@dataclass(frozen=True)
class Multirotor:
    """A multirotor drone: a body scatterer and rotors in one plane seen at elevation beta."""

    motion: Motion
    rotors: Rotors
    name: str = "drone"
    elevation_deg: float = field(default=0.0, metadata=check(lambda v: -90 <= v <= 90, "within [-90, 90]"))
    body_rcs_m2: float = field(default=1e-2, metadata=NON_NEGATIVE)
    kind = "multirotor"


@dataclass(frozen=True)
class Bird:
    """A flapping bird on a level straight flight (paper Eqs. 7-15; angles in degrees)."""

    motion: Motion
    wingbeat_hz: float = field(metadata=POSITIVE)
    upper_arm_m: float = field(metadata=POSITIVE)
    forearm_m: float = field(metadata=POSITIVE)
    name: str = "bird"
    a1_deg: float = 40.0
    a2_deg: Optional[float] = None
    psi10_deg: float = 15.0
    psi20_deg: float = 20.0
    c2_deg: float = 20.0
    phi20_deg: float = 0.0
    heading_deg: Optional[float] = None
    body_rcs_m2: float = field(default=1e-2, metadata=NON_NEGATIVE)
    wing_rcs_m2: float = field(default=5e-3, metadata=POSITIVE)
    points_per_segment: int = field(default=3, metadata=check(lambda v: v >= 1, ">= 1"))
    kind = "bird"

    @property
    def flap_kwargs(self):
        """Keyword arguments of :func:`mdpipe.physics.bird.flap_angles_rad` (A2 defaults to A1)."""
        return dict(wingbeat_hz=self.wingbeat_hz, a1_deg=self.a1_deg,
                    a2_deg=self.a1_deg if self.a2_deg is None else self.a2_deg,
                    psi10_deg=self.psi10_deg, psi20_deg=self.psi20_deg, c2_deg=self.c2_deg,
                    phi20_deg=self.phi20_deg)

    @property
    def heading_rad(self):
        """Flight direction in the horizontal plane: given, else along the horizontal velocity, else +x."""
        if self.heading_deg is not None:
            return np.deg2rad(self.heading_deg)
        vx, vy, _ = self.motion.velocity_mps
        return float(np.arctan2(vy, vx)) if (vx, vy) != (0.0, 0.0) else 0.0


@dataclass(frozen=True)
class Static:
    """A fixed point scatterer (a tree, a mast)."""

    range_m: float = field(metadata=POSITIVE)
    name: str = "static"
    azimuth_deg: float = 0.0
    elevation_deg: float = 0.0
    rcs_m2: float = field(default=1.0, metadata=POSITIVE)
    kind = "static"

    @property
    def position_m(self):
        az, el = np.deg2rad(self.azimuth_deg), np.deg2rad(self.elevation_deg)
        return self.range_m * np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])


@dataclass(frozen=True)
class Point:
    """A moving point scatterer (a body without micro-motion)."""

    motion: Motion
    name: str = "point"
    rcs_m2: float = field(default=1.0, metadata=POSITIVE)
    kind = "point"


TARGET_KINDS = {cls.kind: cls for cls in (Multirotor, Bird, Point, Static)}


@dataclass(frozen=True)
class Noise:
    """Receiver noise: white Gaussian, independent per sample, chirp and channel.

    ``snr_db`` is the mean IF power of the moving targets (drones, birds, points; not static clutter)
    over the noise power, per sample and channel, before any processing gain; ``sigma_v`` sets
    the noise standard deviation directly. Neither: no noise.
    """

    snr_db: Optional[float] = None
    sigma_v: Optional[float] = field(default=None, metadata=NON_NEGATIVE)

    def __post_init__(self):
        if self.snr_db is not None and self.sigma_v is not None:
            raise ParameterError("give snr_db or sigma_v, not both")


@dataclass(frozen=True)
class Adc:
    """int16 quantisation. Without ``full_scale_v`` the scale is chosen so nothing clips."""

    full_scale_v: Optional[float] = field(default=None, metadata=POSITIVE)


@dataclass(frozen=True)
class Fidelity:
    """Model choices: ``auto`` decides from the scene's physics (see :mod:`mdpipe.simulate.fidelity`)."""

    in_chirp_motion: str = field(default="auto", metadata=check(lambda v: v in ("auto", "on", "off", "exact"),
                                                                  "one of auto, on, off, exact"))
    range_migration: str = field(default="auto", metadata=check(lambda v: v in ("auto", "on", "off"),
                                                                  "one of auto, on, off"))
    tolerance: float = field(default=1e-4, metadata=check(lambda v: 0 < v < 1, "in (0, 1)"))


@dataclass(frozen=True)
class Scene:
    """A whole simulated capture."""

    radar: RadarConfig
    targets: tuple = ()
    noise: Noise = Noise()
    adc: Adc = Adc()
    fidelity: Fidelity = Fidelity()
    seed: int = 0
    name: str = "scene"


def _targets(data, path):
    if data is None:
        return ()
    if not isinstance(data, list):
        raise ParameterError(f"{path}: expected a list of targets, got {data!r}")
    targets = []
    for i, item in enumerate(data):
        item_path = f"{path}[{i}]"
        if not isinstance(item, dict) or "type" not in item:
            raise ParameterError(f"{item_path}.type: missing (one of {', '.join(TARGET_KINDS)})")
        kind = item["type"]
        if kind not in TARGET_KINDS:
            raise ParameterError(f"{item_path}.type: unknown target type {kind!r} (one of {', '.join(TARGET_KINDS)})")
        targets.append(build(TARGET_KINDS[kind], {k: v for k, v in item.items() if k != "type"}, item_path))
    return tuple(targets)


def scene_from_mapping(data):
    """Validate a parsed YAML mapping and build the :class:`Scene`."""
    if not isinstance(data, dict):
        raise ParameterError(f"scene: expected a mapping at the top of the file, got {type(data).__name__}")
    if "radar" not in data:
        raise ParameterError("radar: missing (every scene needs a radar block; see configs/radarlog.yaml)")
    rest = {k: v for k, v in data.items() if k != "targets"}
    scene = build(Scene, rest, "")
    return dataclasses.replace(scene, targets=_targets(data.get("targets"), "targets"))


class SceneLoader(yaml.SafeLoader):
    """Safe YAML loader that reads floats by the YAML 1.2 rule, so ``76e9`` and ``1.948e-3`` are numbers."""


SceneLoader.yaml_implicit_resolvers = {k: [r for r in v if r[0] != "tag:yaml.org,2002:float"]
                                       for k, v in yaml.SafeLoader.yaml_implicit_resolvers.items()}
SceneLoader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?$|^[-+]?\.(inf|Inf|INF)$|^\.(nan|NaN|NAN)$"),
    list("-+0123456789."))


def load_scene_mapping(path):
    """Read a scene YAML file into a plain mapping (a separate step so CLI overrides apply before validation)."""
    try:
        with open(path, encoding="utf-8") as fh:
            return yaml.load(fh, Loader=SceneLoader)
    except yaml.YAMLError as exc:
        raise ParameterError(f"{path}: not valid YAML ({str(exc).splitlines()[0]})") from None
    except OSError as exc:
        raise ParameterError(f"{path}: cannot read ({exc.strerror})") from None


def scene_to_yaml(scene_mapping):
    """Serialise a scene mapping as stored in ``/Truth``."""
    return yaml.safe_dump(scene_mapping, sort_keys=False)
