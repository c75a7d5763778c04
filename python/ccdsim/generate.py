"""Scene generators: each returns a scene dict in the scene-file format (see
docs/scene-format.md)."""

from __future__ import annotations

import json
from typing import Any, Optional

from . import _ccdsim


def gas(
    n: int = 1000,
    packing: float = 0.2,
    dim: int = 2,
    radius_min: float = 0.5,
    radius_max: float = 0.5,
    speed_min: float = 0.0,
    speed_max: float = 1.0,
    seed: int = 1,
    periodic: bool = False,
    lattice: bool = False,
    temperature: Optional[float] = None,
) -> dict[str, Any]:
    """``n`` non-overlapping discs (spheres) at packing fraction ``packing`` in a walled square
    (cube), or with ``periodic`` in a periodic box; ``lattice`` starts them on the densest
    lattice (needed for dense packings); ``temperature`` gives Maxwell velocities at that kT
    with zero total momentum instead of uniform speeds. As ``ccdsim gen gas``."""
    return json.loads(
        _ccdsim.gas_json(
            n, packing, dim, radius_min, radius_max, speed_min, speed_max, seed, periodic,
            lattice, temperature,
        )
    )


def thesis(n: int = 256, seed: int = 1, dim: int = 2) -> dict[str, Any]:
    """The thesis's §5.2 benchmark scene with ``n`` bodies. As ``ccdsim gen thesis``."""
    return json.loads(_ccdsim.thesis_json(n, seed, dim))


def rack(speed: Optional[float] = None, offset: Optional[float] = None) -> dict[str, Any]:
    """A 15-ball billiard rack with the cue ball shot into it. As ``ccdsim gen rack``."""
    return json.loads(_ccdsim.rack_json(speed, offset))
