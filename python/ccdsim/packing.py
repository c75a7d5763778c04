"""Jammed packings by compression (Lubachevsky–Stillinger), as ``ccdsim pack``.

Example::

    import ccdsim
    p = ccdsim.packing.pack(dim=2, n=1000, bidisperse=1.4, rate=0.01)
    print(p["packing_fraction"], p["mean_contacts"], len(p["rattlers"]))
    sim = ccdsim.Simulation(p["scene"])          # go on from the jammed state
    q = ccdsim.packing.pack(dim=3, n=500, rate=0.05, isostatic=True)
    assert q["rigid"]                            # contacts hold it: isostatic
"""

from __future__ import annotations

import json
from typing import Any, Optional

import numpy as np

from . import _ccdsim

__all__ = ["pack"]


def pack(
    dim: int = 3,
    n: int = 1000,
    bidisperse: Optional[float] = None,
    polydisperse: Optional[float] = None,
    rate: float = 0.01,
    periodic: bool = True,
    until_pressure: Optional[float] = None,
    start_packing: Optional[float] = None,
    seed: int = 1,
    finder: str = "cells",
    max_events: Optional[int] = None,
    isostatic: bool = False,
    overlap: float = 1e-6,
) -> dict[str, Any]:
    """Compresses a dilute random gas of ``n`` bodies (radius 0.5; ``bidisperse=R``: half of them
    ``R`` times larger; ``polydisperse=W``: radii uniform in 0.5·[1 − W, 1 + W]) in a periodic box
    (or, with ``periodic=False``, a walled one) by growing every radius at ``rate`` times its
    start value per second, velocities brought back to kT = 1 after every block of 20·n events,
    until the reduced pressure P V / (N kT) passes ``until_pressure`` (default 1e12). With
    ``isostatic=True`` the compression stops at 1e4 (unless ``until_pressure`` says otherwise)
    and the packing is then taken to its jamming point by soft-sphere energy minimisation, until
    the mean overlap is at most ``overlap`` of a contact distance: its contacts then hold it
    rigid (``ccdsim pack --isostatic``). Runs in Rust without the GIL.

    Returns a dict: ``packing_fraction``, ``reduced_pressure``, ``stop`` (``"pressure"`` when
    jammed), ``events``, ``time``, ``mean_contacts`` (of the bodies that are not rattlers),
    ``contact_tolerance``, ``held_contacts`` (contacts among the bodies that are not rattlers),
    ``isostatic_contacts`` (the fewest that hold them: their degrees of freedom), ``rigid``,
    ``finish`` (with ``isostatic``: ``minimizations``, ``steps``, ``mean_overlap``,
    ``max_overlap``, ``radius_scale``; else None), ``contacts`` (k × 2 array of touching body
    pairs), ``wall_contacts``
    (k × 2: body, wall), ``rattlers`` (array of body indices) and ``scene`` (the packing as a
    scene dict). Bad settings raise ``ValueError``.
    """
    out = json.loads(
        _ccdsim.pack_json(
            dim, n, bidisperse, polydisperse, rate, periodic, until_pressure, start_packing, seed,
            finder, max_events, isostatic, overlap,
        )
    )
    out["contacts"] = np.array(out["contacts"], dtype=np.int64).reshape(-1, 2)
    out["wall_contacts"] = np.array(out["wall_contacts"], dtype=np.int64).reshape(-1, 2)
    out["rattlers"] = np.array(out["rattlers"], dtype=np.int64)
    return out
