"""Bring a drawn scene to what the installed simulator accepts (``mdpipe evaluate --compat``).

A sweep may ask for simulator keys a given version does not know yet. With ``--compat`` each drawn
scene is reduced to the installed schema, and what was changed is listed with the scene:

* keys the schema does not know are dropped (``targets[0].rotors.blade_profile``, ...);
* ``noise.moving_snr_db`` (the SNR of what MTI keeps) becomes ``noise.snr_db`` (the SNR of the whole
  moving target) when the schema has no ``moving_snr_db``;
* a target ``type: branch`` the schema does not know becomes a swaying ``point`` of the same RCS,
  position, sway amplitude (along the line of sight) and period ``1 / sway_hz``: the branch
  without its leaves.

When the schema knows every key, the scene is returned unchanged.
"""

import copy
import dataclasses
import typing

import numpy as np

from mdpipe.simulate import scene as scene_module


def _dataclass_of(kind):
    for option in (typing.get_args(kind) or (kind,)):
        if dataclasses.is_dataclass(option):
            return option
    return None


def _reduce(cls, data, path, dropped):
    """``data`` with only the keys of dataclass ``cls`` (recursing into nested dataclasses)."""
    if not isinstance(data, dict):
        return data
    hints = typing.get_type_hints(cls)
    fields = {f.name for f in dataclasses.fields(cls) if f.init}
    out = {}
    for key, value in data.items():
        key_path = f"{path}.{key}" if path else key
        if key not in fields:
            dropped.append(key_path)
            continue
        nested = _dataclass_of(hints[key])
        out[key] = _reduce(nested, value, key_path, dropped) if nested is not None else value
    return out


def _branch_as_point(target):
    position = np.asarray(target["position_m"], dtype=float)
    los = position / np.linalg.norm(position)
    amplitude = float(target.get("sway_amplitude_m", 0.0))
    motion = {"position_m": target["position_m"]}
    if amplitude > 0 and float(target.get("sway_hz", 0.0)) > 0:
        motion.update(sway_amplitude_m=[float(x) for x in amplitude * los], sway_period_s=1.0 / target["sway_hz"])
    return {"type": "point", "name": target.get("name", "branch"), "rcs_m2": target.get("rcs_m2", 1.0),
            "motion": motion}


def to_current_schema(mapping):
    """The scene ``mapping`` reduced to the installed schema, and the list of changes (key paths)."""
    mapping = copy.deepcopy(mapping)
    changes = []
    noise = mapping.get("noise") or {}
    noise_fields = {f.name for f in dataclasses.fields(scene_module.Noise)}
    if "moving_snr_db" in noise and "moving_snr_db" not in noise_fields:
        noise["snr_db"] = noise.pop("moving_snr_db")
        changes.append("noise.moving_snr_db->snr_db")
    targets = []
    for i, target in enumerate(mapping.get("targets") or []):
        kind = target.get("type")
        if kind == "branch" and kind not in scene_module.TARGET_KINDS:
            target = _branch_as_point(target)
            changes.append(f"targets[{i}].type:branch->point")
        cls = scene_module.TARGET_KINDS.get(target.get("type"))
        if cls is not None:
            target = {"type": target["type"], **_reduce(cls, {k: v for k, v in target.items() if k != "type"},
                                                         f"targets[{i}]", changes)}
        targets.append(target)
    rest = _reduce(scene_module.Scene, {k: v for k, v in mapping.items() if k != "targets"}, "", changes)
    return {**rest, "targets": targets}, changes
