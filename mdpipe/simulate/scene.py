"""Scene description: radar, targets, noise, ADC and model fidelity, read from YAML.

Lengths in metres, angles in degrees (``_deg``), rates in Hz; positions and velocities are
``[x, y, z]`` in the radar frame (x boresight, y along the RX array, z up).
"""

import dataclasses
import os
import re
import stat
from dataclasses import dataclass, field
from typing import Optional

import numpy as np
import yaml

from mdpipe.errors import ParameterError
from mdpipe.io.files import file_kind
from mdpipe.params import MAX_TRANSMITTERS, MAX_TX_SEQUENCE, RadarParams, transmit_cycle
from mdpipe.physics.radar import SPEED_OF_LIGHT_MPS
from mdpipe.simulate.plausibility import check_scene
from mdpipe.simulate.schema import NON_NEGATIVE, POSITIVE, build, check, short_repr
from mdpipe.simulate.targets import KINDS

RADARLOG_RX_SPACING_M = 1.948e-3
MAX_FRACTIONAL_BANDWIDTH = 0.2
MAX_SNR_DB = 100.0
MAX_SCENE_BYTES = 10_000_000
SNR_RANGE = check(lambda v: -MAX_SNR_DB <= v <= MAX_SNR_DB, f"within [-{MAX_SNR_DB:g}, {MAX_SNR_DB:g}] dB")


@dataclass(frozen=True)
class RadarConfig:
    """The radar block: chirp parameters, capture length, RX layout and the transmitters the chirps take in turn.

    ``tx_sequence`` (1-based transmitter numbers, e.g. ``[1, 2]``: a MIMO radar's time-division cycle, written to the
    file as ``TxSeq``; None or one entry: one transmitter) repeats over the chirps; transmitter k sits at
    ``tx_positions_m[k - 1]`` along the array axis (default: a uniform virtual array, k - 1 RX apertures of
    ``n_channels`` spacings each) and adds its feed's ``tx_phase_deg[k - 1]`` (default 0). A target off boresight,
    or feeds apart in phase, then change every echo's phase from one transmitter's chirps to the next.
    """

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
    tx_sequence: Optional[tuple[int, ...]] = field(default=None, metadata=check(
        lambda k: 1 <= k <= MAX_TRANSMITTERS, f"transmitter numbers 1 to {MAX_TRANSMITTERS}"))
    tx_positions_m: Optional[tuple[float, ...]] = None
    tx_phase_deg: Optional[tuple[float, ...]] = None

    def __post_init__(self):
        if self.tx_sequence is not None and not 1 <= len(self.tx_sequence) <= MAX_TX_SEQUENCE:
            raise ParameterError(f"tx_sequence lists {len(self.tx_sequence)} chirps; give 1 to {MAX_TX_SEQUENCE} "
                                 "transmitter numbers (one transmit cycle)")
        for name in ("tx_positions_m", "tx_phase_deg"):
            given = getattr(self, name)
            if given is not None and len(given) < self.n_transmitters:
                raise ParameterError(f"{name} lists {len(given)} entries for transmitters 1 to {self.n_transmitters} "
                                     "(tx_sequence)")
        if self.rx_positions_m is not None and len(self.rx_positions_m) < self.n_channels:
            raise ParameterError(
                f"rx_positions_m lists {len(self.rx_positions_m)} positions for n_channels={self.n_channels}")
        params = self.params  # validates the chirp parameters (a carrier in GHz written as 24: a hint)
        share = params.bandwidth_hz / params.centre_hz
        if share > MAX_FRACTIONAL_BANDWIDTH:
            raise ParameterError(f"the sweep is {params.bandwidth_hz / 1e9:.4g} GHz wide, {100 * share:.0f} % of its "
                                 f"{params.centre_hz / 1e9:.4g} GHz centre (at most "
                                 f"{100 * MAX_FRACTIONAL_BANDWIDTH:.0f} %); check f_start_hz and f_stop_hz")

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

    @property
    def transmit_cycle(self):
        """Chirps per transmit cycle (:func:`mdpipe.params.transmit_cycle`); 1 for one transmitter."""
        return transmit_cycle(self.tx_sequence or (1,))

    @property
    def analysed(self):
        """(RadarParams, chirps) of the first transmitter's chirps, what the processing reads of a cycling capture."""
        cycle = self.transmit_cycle
        return self.params.every(cycle), len(range(0, self.n_chirps, cycle))

    @property
    def n_transmitters(self):
        """The highest transmitter number of ``tx_sequence`` (1 without one)."""
        return max(self.tx_sequence or (1,))

    def chirp_transmitters(self, chirps):
        """The 0-based transmitter index of each chirp index in ``chirps``."""
        sequence = np.asarray(self.tx_sequence or (1,), dtype=np.int64) - 1
        return sequence[np.asarray(chirps) % len(sequence)]

    def tx_phase_rad(self, chirps, los_y):
        """The phase (rad) each chirp's transmitter adds to an echo arriving along ``los_y`` (the line of sight's
        component along the array axis), shape ``np.broadcast(chirps[:, None], los_y)``: its position's path
        ``2 pi y sin(theta) / lambda`` at the sweep start and its feed's phase."""
        tx = self.chirp_transmitters(chirps)
        if self.tx_positions_m is None:
            positions = self.n_channels * self.rx_spacing_m * np.arange(self.n_transmitters)
        else:
            positions = np.asarray(self.tx_positions_m[: self.n_transmitters], dtype=np.float64)
        feeds = np.deg2rad(np.asarray(self.tx_phase_deg[: self.n_transmitters] if self.tx_phase_deg is not None
                                      else np.zeros(self.n_transmitters), dtype=np.float64))
        path = 2 * np.pi * self.f_start_hz / SPEED_OF_LIGHT_MPS * positions[tx][:, None] * los_y
        return path + feeds[tx][:, None]


TARGET_KINDS = {kind: module.Target for kind, module in KINDS.items()}


@dataclass(frozen=True)
class Noise:
    """Receiver noise: white Gaussian, independent per sample, chirp and channel. Give at most one of:

    ``snr_db``
        The mean IF power of all moving targets (multirotors, birds, points, branches; not static
        clutter) over the noise power, per IF sample and channel, before any processing gain. The
        whole echo counts, the body's included: a hovering drone's body line, which MTI removes,
        counts as much as its blades.
    ``moving_snr_db``
        The same ratio for the part of the echoes that MTI keeps: each target's echo minus its
        slow-time mean over the capture, summed over the moving targets.
    ``sigma_v``
        The noise standard deviation per sample directly (V).

    None of them: no noise. ``/Truth`` records both resulting SNRs of every target.
    """

    snr_db: Optional[float] = field(default=None, metadata=SNR_RANGE)
    sigma_v: Optional[float] = field(default=None, metadata=NON_NEGATIVE)
    moving_snr_db: Optional[float] = field(default=None, metadata=SNR_RANGE)

    def __post_init__(self):
        given = [name for name in ("snr_db", "sigma_v", "moving_snr_db") if getattr(self, name) is not None]
        if len(given) > 1:
            if set(given) == {"snr_db", "sigma_v"}:
                raise ParameterError("give snr_db or sigma_v, not both")
            raise ParameterError(f"give one of snr_db, moving_snr_db, sigma_v, not {' and '.join(given)}")


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
    tolerance: float = field(default=1e-4, metadata=check(lambda v: 1e-9 <= v < 1, "in [1e-9, 1)"))


@dataclass(frozen=True)
class Scene:
    """A whole simulated capture."""

    radar: RadarConfig
    targets: tuple = ()
    noise: Noise = Noise()
    adc: Adc = Adc()
    fidelity: Fidelity = Fidelity()
    seed: int = field(default=0, metadata=NON_NEGATIVE)
    name: str = "scene"


def _targets(data, path):
    if data is None:
        return ()
    if not isinstance(data, list):
        raise ParameterError(f"{path}: expected a list of targets, got {short_repr(data)}")
    targets = []
    for i, item in enumerate(data):
        item_path = f"{path}[{i}]"
        if not isinstance(item, dict) or "type" not in item:
            raise ParameterError(f"{item_path}.type: missing (one of {', '.join(TARGET_KINDS)})")
        kind = item["type"]
        if not isinstance(kind, str) or kind not in TARGET_KINDS:
            raise ParameterError(f"{item_path}.type: unknown target type {short_repr(kind)} "
                                 f"(one of {', '.join(TARGET_KINDS)})")
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
    scene = dataclasses.replace(scene, targets=_targets(data.get("targets"), "targets"))
    check_scene(scene)
    return scene


class SceneLoader(yaml.SafeLoader):
    """Safe YAML loader that reads floats by the YAML 1.2 rule, so ``76e9`` and ``1.948e-3`` are numbers, and refuses
    a key given twice in one mapping (the last would win unseen; a key a ``<<`` merge brings may be given again)."""

    def construct_mapping(self, node, deep=False):
        if isinstance(node, yaml.MappingNode):
            seen = set()
            for key_node, _ in node.value:
                if key_node.tag == "tag:yaml.org,2002:merge" or not isinstance(key_node, yaml.ScalarNode):
                    continue
                if key_node.value in seen:
                    raise yaml.constructor.ConstructorError(None, None, f"duplicate key {key_node.value!r}",
                                                            key_node.start_mark)
                seen.add(key_node.value)
        return super().construct_mapping(node, deep)


SceneLoader.yaml_implicit_resolvers = {k: [r for r in v if r[0] != "tag:yaml.org,2002:float"]
                                       for k, v in yaml.SafeLoader.yaml_implicit_resolvers.items()}
SceneLoader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?$|^[-+]?\.(inf|Inf|INF)$|^\.(nan|NaN|NAN)$"),
    list("-+0123456789."))


def load_scene_mapping(path):
    """Read a scene YAML file into a plain mapping (a separate step so CLI overrides apply before validation)."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        mode = None  # the open below says why
    if mode is not None and not stat.S_ISREG(mode):  # a FIFO would hang the read, a device never end it
        raise ParameterError(f"{path}: is {file_kind(mode)}; scenes and sweeps are read from regular files only")
    try:
        with open(path, "rb") as fh:
            raw = fh.read(MAX_SCENE_BYTES + 1)
    except OSError as exc:
        raise ParameterError(f"{path}: cannot read ({exc.strerror})") from None
    if len(raw) > MAX_SCENE_BYTES:
        raise ParameterError(f"{path}: over {MAX_SCENE_BYTES // 1_000_000} MB, too large to be a scene YAML")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ParameterError(f"{path}: not UTF-8 text (byte 0x{raw[exc.start]:02x} at offset {exc.start}); "
                             "save the scene as UTF-8") from None
    try:
        return yaml.load(text, Loader=SceneLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark is not None else ""
        problem = " ".join((exc.problem or exc.context or "syntax error").split())
        raise ParameterError(f"{path}: not valid YAML{where} ({problem})") from None
    except yaml.YAMLError as exc:
        raise ParameterError(f"{path}: not valid YAML ({str(exc).splitlines()[0]})") from None
    except RecursionError:
        raise ParameterError(f"{path}: nested too deeply to be a scene (a scene needs a few levels)") from None


def scene_to_yaml(scene_mapping):
    """Serialise a scene mapping as stored in ``/Truth``."""
    return yaml.safe_dump(scene_mapping, sort_keys=False)
