"""Scene target kinds, one module each (schema, echo, bounds, truth; see :mod:`.common`), in one table."""

import numpy as np

from mdpipe.simulate.targets import bird, branch, multirotor, point, static

KINDS = {module.Target.kind: module for module in (multirotor, bird, point, static, branch)}


def module_of(target):
    """The module that simulates ``target``."""
    return KINDS[target.kind]


def target_echo(target, realization, t_s, *, f0_hz):
    """Echo of any scene target at times ``t_s``."""
    return module_of(target).echo(target, realization, np.asarray(t_s, dtype=np.float64), f0_hz=f0_hz)


def realize_all(scene):
    """Each target's seeded draws for this capture (from the scene seed and the target's index)."""
    duration_s = scene.radar.n_chirps * scene.radar.chirp_period_s
    return [module_of(target).realize(target, seed=scene.seed, index=index, duration_s=duration_s)
            for index, target in enumerate(scene.targets)]
