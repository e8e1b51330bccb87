"""Draw a seeded, labelled sweep of scenes from a sweep YAML (see ``configs/sweeps/default.yaml``).

A sweep names scene *families* with weights. Each family gives distributions for the radar
(band, bandwidth, PRF, dwell, samples per chirp, RX channels), the placement of its target
(range, azimuth, height, speed, heading), the noise block, static clutter, the probability that the
blade count and the elevation are given to ``mdpipe process``, and a ``target`` template that is
plain scene YAML (see ``mdpipe/simulate/scene.py``) in which any value may be a distribution:

``{uniform: [a, b]}``, ``{loguniform: [a, b]}``, ``{normal: [mean, sd]}`` or
``{normal: [mean, sd, low, high]}`` (clipped), ``{randint: [a, b]}`` (inclusive), ``{choice: [...]}``
(items may be distributions; a target key that draws null is left out), ``{per_rotor: <distribution>}`` (one draw per rotor, inside ``rotors``)
and ``{rotor_rates: {mean_hz: ..., spread_fraction: ..., alternate_spin: true}}`` (rotor ``i`` turns at
``mean (1 + spread u_i)``, ``u_i`` uniform in [-1, 1], signs alternating). A key appears in a drawn
scene only when the template names it, so a sweep that uses no new simulator key runs on any version.

Scene ``i`` is drawn from its own generator ``default_rng([seed, i])``: the same scene whatever
``n_scenes`` or ``--limit``.
"""

from dataclasses import dataclass

import numpy as np

from mdpipe.errors import ParameterError
from mdpipe.params import RadarParams
from mdpipe.simulate.scene import load_scene_mapping

DISTRIBUTIONS = ("uniform", "loguniform", "normal", "randint", "choice", "per_rotor", "rotor_rates")
SWEEP_KEYS = ("seed", "n_scenes", "max_chirps", "bands", "blocks", "families")
FAMILY_KEYS = ("weight", "radar", "place", "noise", "clutter", "given", "target")
RADAR_KEYS = ("band", "bandwidth_hz", "prf_hz", "dwell_s", "n_samples", "n_channels")
PLACE_KEYS = ("range_m", "azimuth_deg", "height_m", "speed_mps", "heading_deg")
RAMP_FRACTION = 0.8        # sampled up-ramp / chirp period
MIN_CHIRPS = 2048          # the range statistics probe at least this many chirps
MIN_RANGE_M = 2.0          # the target stays beyond this range over the dwell ...
MAX_RANGE_FRACTION = 0.85  # ... and within this fraction of the largest range of the range FFT
PLACE_TRIES = 50
MAX_NUMBER = 2.0 ** 62     # a distribution's bounds (randint draws int64)
MAX_CLUTTER = 100          # static scatterers a family may draw


@dataclass(frozen=True)
class Draw:
    """One drawn scene: its mapping (scene YAML) and how it is processed.

    Attributes
    ----------
    name : str
        ``<index>_<family>``, also the scene's ``name`` and the stem of its files.
    family : str
    band : str
        The radar band's name in the sweep's ``bands``.
    scene : dict
        The scene mapping, ready for :func:`mdpipe.simulate.scene.scene_from_mapping`.
    process : dict
        :class:`mdpipe.params.ProcessParams` keywords: ``n_blades`` (int, or None when not given) and
        ``elevation_deg`` (only when given).
    """

    name: str
    family: str
    band: str
    scene: dict
    process: dict


def _clean(value):
    """Python scalars with 6 significant digits (readable scene YAML)."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(f"{float(value):.6g}")
    return value


def _number(value):
    """Whether ``value`` is a finite number within int64's reach (not a bool)."""
    return isinstance(value, (int, float)) and not isinstance(value, bool) and bool(np.isfinite(value)) \
        and abs(value) < MAX_NUMBER


def _pair(spec, name, path):
    if not isinstance(spec, (list, tuple)) or len(spec) not in (2, 4) or not all(_number(v) for v in spec):
        raise ParameterError(f"{path}: {name} takes a list [a, b] of finite numbers, got {spec!r}")
    if name == "normal" and spec[1] < 0:
        raise ParameterError(f"{path}: normal takes [mean, sd] with sd >= 0, got {spec!r}")
    if name in ("uniform", "loguniform", "randint") and (len(spec) != 2 or spec[1] < spec[0]):
        raise ParameterError(f"{path}: {name} takes [low, high] with low <= high, got {spec!r}")
    if name == "loguniform" and spec[0] <= 0:
        raise ParameterError(f"{path}: loguniform needs a low bound > 0, got {spec!r}")
    return spec


def draw_value(spec, rng, path, *, count=None):
    """Draw ``spec`` (a distribution, a mapping or list holding some, or a plain value).

    ``count`` is the number of rotors, for ``per_rotor`` and ``rotor_rates``.
    """
    if isinstance(spec, dict) and len(spec) == 1 and next(iter(spec)) in DISTRIBUTIONS:
        name, args = next(iter(spec.items()))
        if name == "choice":
            if not isinstance(args, list) or not args:
                raise ParameterError(f"{path}: choice takes a non-empty list, got {args!r}")
            return draw_value(args[int(rng.integers(len(args)))], rng, path, count=count)
        if name in ("per_rotor", "rotor_rates"):
            if count is None:
                raise ParameterError(f"{path}: {name} is for keys inside a multirotor's rotors block")
            if name == "per_rotor":
                return [draw_value(args, rng, f"{path}[{i}]") for i in range(count)]
            return _rotor_rates(args, rng, path, count)
        a = _pair(args, name, path)
        if name == "uniform":
            return _clean(rng.uniform(a[0], a[1]))
        if name == "loguniform":
            return _clean(np.exp(rng.uniform(np.log(a[0]), np.log(a[1]))))
        if name == "randint":
            return int(rng.integers(int(a[0]), int(a[1]) + 1))
        value = rng.normal(a[0], a[1])
        return _clean(np.clip(value, a[2], a[3]) if len(a) == 4 else value)
    if isinstance(spec, dict):
        return {k: draw_value(v, rng, f"{path}.{k}", count=count) for k, v in spec.items()}
    if isinstance(spec, list):
        return [draw_value(v, rng, f"{path}[{i}]", count=count) for i, v in enumerate(spec)]
    return _clean(spec)


def _rotor_rates(args, rng, path, count):
    if not isinstance(args, dict) or "mean_hz" not in args:
        raise ParameterError(f"{path}: rotor_rates needs mean_hz (and optionally spread_fraction, alternate_spin)")
    unknown = set(args) - {"mean_hz", "spread_fraction", "alternate_spin"}
    if unknown:
        raise ParameterError(f"{path}.{sorted(unknown)[0]}: unknown key (mean_hz, spread_fraction, alternate_spin)")
    mean = draw_value(args["mean_hz"], rng, f"{path}.mean_hz")
    spread = draw_value(args.get("spread_fraction", 0.0), rng, f"{path}.spread_fraction")
    rates = mean * (1.0 + spread * rng.uniform(-1.0, 1.0, count))
    if args.get("alternate_spin", True):
        rates = rates * (-1.0) ** np.arange(count)
    return [_clean(r) for r in rates]


def _drop_none(value):
    """Mappings without their null entries (a choice that drew null leaves its key out)."""
    if isinstance(value, dict):
        return {k: _drop_none(v) for k, v in value.items() if v is not None}
    if isinstance(value, list):
        return [_drop_none(v) for v in value]
    return value


def _draw_target(template, rng, path):
    """The target template drawn (null entries left out); a multirotor's ``rotors.count`` first, for its
    per-rotor entries. A ``rotors.merge`` entry draws a mapping of keys that go together (a blade profile
    and its parameters) and is merged into ``rotors``."""
    template = dict(template)
    rotors = template.pop("rotors", None)
    target = draw_value(template, rng, path)
    if rotors is not None:
        rotors = dict(rotors)
        count = draw_value(rotors.pop("count", 1), rng, f"{path}.rotors.count")
        drawn = draw_value(rotors, rng, f"{path}.rotors", count=count)
        target["rotors"] = {"count": count, **(drawn.pop("merge", None) or {}), **drawn}
    return _drop_none(target)


def radar_block(spec, bands, rng, path, *, max_chirps):
    """Radar mapping from drawn band, bandwidth, PRF, dwell, samples per chirp and channels."""
    drawn = draw_value(spec, rng, path)
    unknown = sorted(set(drawn) - set(RADAR_KEYS))
    if unknown:
        raise ParameterError(f"{path}.{unknown[0]}: unknown key (known keys: {', '.join(RADAR_KEYS)})")
    values = {k: drawn.get(k) for k in RADAR_KEYS}
    missing = [k for k in RADAR_KEYS if values[k] is None and k != "n_channels"]
    if missing:
        raise ParameterError(f"{path}.{missing[0]}: missing (a family's radar needs {', '.join(RADAR_KEYS[:-1])})")
    if not isinstance(values["band"], str) or values["band"] not in bands:
        raise ParameterError(f"{path}.band: {values['band']!r} is not in the sweep's bands ({', '.join(bands)})")
    for key in RADAR_KEYS[1:]:
        value = values[key]
        if value is not None and not (_number(value) and value > 0):
            raise ParameterError(f"{path}.{key}: must draw a finite number > 0, drew {value!r}")
    chirp_period_s = 1.0 / values["prf_hz"]
    ramp_s = RAMP_FRACTION * chirp_period_s
    n_chirps = int(min(max_chirps, max(MIN_CHIRPS, round(values["dwell_s"] * values["prf_hz"]))))
    f_start = float(bands[values["band"]])
    return {"f_start_hz": f_start, "f_stop_hz": _clean(f_start + values["bandwidth_hz"]),
            "ramp_up_s": _clean(ramp_s), "chirp_period_s": _clean(chirp_period_s),
            "sample_rate_hz": float(values["n_samples"] / _clean(ramp_s) * (1 + 1e-9)),
            "n_samples": int(values["n_samples"]), "n_chirps": n_chirps,
            "n_channels": int(values["n_channels"] or 1)}, values["band"]


def _max_range_m(radar):
    keys = ("f_start_hz", "f_stop_hz", "ramp_up_s", "chirp_period_s", "sample_rate_hz", "n_samples")
    return RadarParams(**{k: radar[k] for k in keys}).max_range_m


def place(spec, rng, path, *, radar):
    """Start position and velocity (m, m/s) so that the track's middle is at the drawn range, and the
    whole track stays within [``MIN_RANGE_M``, ``MAX_RANGE_FRACTION`` x the largest range] (redrawn else)."""
    dwell_s = radar["n_chirps"] * radar["chirp_period_s"]
    limit_m = MAX_RANGE_FRACTION * _max_range_m(radar)
    for _ in range(PLACE_TRIES):
        v = {k: draw_value(spec.get(k, 0.0), rng, f"{path}.{k}") for k in PLACE_KEYS}
        r, h = v["range_m"], min(v["height_m"], 0.95 * v["range_m"])
        az, heading = np.deg2rad(v["azimuth_deg"]), np.deg2rad(v["heading_deg"])
        ground = np.sqrt(r ** 2 - h ** 2)
        middle = np.array([ground * np.cos(az), ground * np.sin(az), h])
        velocity = v["speed_mps"] * np.array([np.cos(heading), np.sin(heading), 0.0])
        start = middle - 0.5 * dwell_s * velocity
        ranges = np.linalg.norm(start + np.linspace(0, dwell_s, 64)[:, None] * velocity, axis=1)
        if ranges.min() >= MIN_RANGE_M and ranges.max() <= limit_m:
            return [_clean(x) for x in start], [_clean(x) for x in velocity]
    raise ParameterError(f"{path}: no placement in {PLACE_TRIES} draws keeps the target within "
                         f"{MIN_RANGE_M:g}-{limit_m:.3g} m over the dwell; narrow range_m or speed_mps")


def clutter_targets(spec, rng, path, *, radar):
    """``count`` static scatterers at drawn ranges, azimuths and RCS."""
    if not spec:
        return []
    if not isinstance(spec, dict) or "range_m" not in spec or "rcs_m2" not in spec:
        raise ParameterError(f"{path}: expected a mapping with count, range_m and rcs_m2 (azimuth_deg optional)")
    count = draw_value(spec.get("count", 0), rng, f"{path}.count")
    if not (_number(count) and count == int(count) and 0 <= count <= MAX_CLUTTER):
        raise ParameterError(f"{path}.count: must draw a whole number from 0 to {MAX_CLUTTER}, drew {count!r}")
    count = int(count)
    limit_m = MAX_RANGE_FRACTION * _max_range_m(radar)
    targets = []
    for i in range(count):
        r = draw_value(spec["range_m"], rng, f"{path}.range_m")
        targets.append({"type": "static", "name": f"clutter{i}", "range_m": _clean(min(r, limit_m)),
                        "azimuth_deg": draw_value(spec.get("azimuth_deg", 0.0), rng, f"{path}.azimuth_deg"),
                        "rcs_m2": draw_value(spec["rcs_m2"], rng, f"{path}.rcs_m2")})
    return targets


def draw_scene(sweep, index):
    """Draw scene ``index`` of ``sweep`` (a validated mapping from :func:`load_sweep`); a :class:`Draw`.

    A draw the simulator refuses as implausible (micro-Doppler over 10x the span, a target beyond the
    maximum range...) is drawn again within its family, up to ``MAX_DRAWS`` times: a sweep holds scenes a
    radar could see.
    """
    from mdpipe.simulate.scene import scene_from_mapping

    for attempt in range(MAX_DRAWS):
        draw = _draw_scene(sweep, index, attempt)
        try:
            scene_from_mapping(draw.scene)
        except ParameterError as exc:
            refusal = exc
            continue
        return draw
    raise ParameterError(f"scene {draw.name}: {MAX_DRAWS} draws refused by the simulator, the last: {refusal}")


def _draw_scene(sweep, index, attempt):
    """Scene ``index``'s family, and its draw number ``attempt`` within that family."""
    rng = np.random.default_rng([int(sweep["seed"]), index])
    names = list(sweep["families"])
    weights = np.array([float(sweep["families"][n].get("weight", 1.0)) for n in names])
    family_name = names[int(rng.choice(len(names), p=weights / weights.sum()))]
    if attempt:
        rng = np.random.default_rng([int(sweep["seed"]), index, attempt])
    family = sweep["families"][family_name]
    path = f"families.{family_name}"
    name = f"{index:04d}_{family_name}"
    radar, band = radar_block(family["radar"], sweep["bands"], rng, f"{path}.radar",
                              max_chirps=int(sweep.get("max_chirps", 40000)))
    targets, process = [], {"n_blades": None}
    template = family.get("target")
    if template:
        target = {"name": family_name, **_draw_target(template, rng, f"{path}.target")}
        start, velocity = place(family.get("place", {}), rng, f"{path}.place", radar=radar)
        if target.get("type") == "branch":
            target["position_m"] = start
        else:
            target["motion"] = {"position_m": start, "velocity_mps": velocity, **target.get("motion", {})}
        given = family.get("given", {})
        if target.get("type") == "multirotor":
            if rng.uniform() < float(given.get("blades", 0.0)):
                process["n_blades"] = int(target["rotors"].get("blades", 2))
            if rng.uniform() < float(given.get("elevation", 0.0)):
                process["elevation_deg"] = float(target.get("elevation_deg", 0.0))
        targets.append(target)
    targets += clutter_targets(family.get("clutter"), rng, f"{path}.clutter", radar=radar)
    scene = {"name": name, "seed": int(rng.integers(2 ** 31)), "radar": radar,
             "noise": draw_value(family.get("noise", {}), rng, f"{path}.noise"), "targets": targets}
    return Draw(name=name, family=family_name, band=band, scene=scene, process=process)


MAX_DRAWS = 20


def validate_sweep(sweep, source):
    """Check the sweep's top-level structure; one-line :class:`ParameterError` naming the key otherwise."""
    if not isinstance(sweep, dict):
        raise ParameterError(f"{source}: expected a mapping with seed, n_scenes, bands and families")
    for key in ("seed", "n_scenes", "bands", "families"):
        if key not in sweep:
            raise ParameterError(f"{source}: {key}: missing (see configs/sweeps/default.yaml)")
    unknown = sorted(set(sweep) - set(SWEEP_KEYS))
    if unknown:
        raise ParameterError(f"{source}: {unknown[0]}: unknown key (known keys: {', '.join(SWEEP_KEYS)}; "
                             "shared YAML anchors go under blocks)")
    for key, least in (("n_scenes", 1), ("seed", 0), ("max_chirps", 1)):
        value = sweep.get(key, least)
        if isinstance(value, bool) or not isinstance(value, int) or not least <= value < MAX_NUMBER:
            raise ParameterError(f"{source}: {key}: must be an integer >= {least}, got {value!r}")
    bands = sweep["bands"]
    if not isinstance(bands, dict) or not bands or not all(
            isinstance(k, str) and _number(v) and v > 0 for k, v in bands.items()):
        raise ParameterError(f"{source}: bands: expected a mapping of band names to start frequencies in Hz, got "
                             f"{bands!r}")
    if not isinstance(sweep["families"], dict) or not sweep["families"]:
        raise ParameterError(f"{source}: families: expected a mapping of family names to families")
    for name, family in sweep["families"].items():
        if not isinstance(family, dict) or "radar" not in family:
            raise ParameterError(f"{source}: families.{name}.radar: missing")
        unknown = sorted(set(family) - set(FAMILY_KEYS))
        if unknown:
            raise ParameterError(f"{source}: families.{name}.{unknown[0]}: unknown key "
                                 f"(known keys: {', '.join(FAMILY_KEYS)})")
        if not isinstance(family["radar"], dict):
            raise ParameterError(f"{source}: families.{name}.radar: expected a mapping of {', '.join(RADAR_KEYS)}")
        weight = family.get("weight", 1.0)
        if not (_number(weight) and weight > 0):
            raise ParameterError(f"{source}: families.{name}.weight: must be a finite number > 0, got {weight!r}")
    return sweep


def load_sweep(path):
    """Read and check a sweep YAML (YAML anchors and ``<<`` merges share blocks between families)."""
    return validate_sweep(load_scene_mapping(path), path)


def draw_scenes(sweep, *, limit=None, seed=None):
    """The first ``min(n_scenes, limit)`` scenes of ``sweep``, as :class:`Draw` objects; drawn with ``seed`` instead
    of the sweep's where given (a fresh draw of the same distributions: scenes no estimator was tuned on)."""
    if seed is not None:
        sweep = {**sweep, "seed": int(seed)}
    n = sweep["n_scenes"] if limit is None else min(sweep["n_scenes"], limit)
    return [draw_scene(sweep, i) for i in range(n)]
