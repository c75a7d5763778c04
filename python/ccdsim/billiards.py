"""Pool: a shot played out event by event on pooltool's default table, exactly.

Balls slide, roll and spin on the cloth, bounce off cushions and jaws and drop into pockets,
with pooltool 0.3.3's models and parameters (Leckie & Greenspan's event-based simulator;
see docs/model.md, "Pool"). A shot runs in Rust without the GIL, in well under a millisecond
for a break: fast enough for reinforcement-learning loops.

Example::

    import ccdsim
    balls = ccdsim.billiards.rack("nine-ball", seed=1)     # [(name, x, y), ...], cue first
    result = ccdsim.billiards.shot(balls, speed=8.0, phi=ccdsim.billiards.aim(balls, "1"))
    print(result.pocketed)                  # {"8": "rb", ...}: ball -> pocket
    for time, kind, agents in result.events:
        ...                                 # e.g. (0.0508, "ball_ball", ["cue", "1"])
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Optional, Sequence, Tuple

from . import _ccdsim

__all__ = ["Shot", "rack", "shot", "aim"]

Ball = Tuple[str, float, float]


@dataclass(frozen=True)
class Shot:
    """A shot played to the end.

    ``events``: every event as ``(time, type, agents)`` with pooltool's type names
    (``"ball_ball"``, ``"ball_linear_cushion"``, ``"ball_circular_cushion"``,
    ``"ball_pocket"``, and transitions such as ``"sliding_rolling"``) and agents (ball names,
    cushion, jaw and pocket ids); ``positions``: each ball's final position (a pocketed ball
    at its pocket's centre); ``pocketed``: ball name to pocket id, in the order they
    dropped; ``time``: when the last ball stopped, in seconds; ``pressings``: collisions of
    balls their decelerations pressed together, parted at the speed a contact's duration asks
    for (docs/model.md, "Balls pressed together"), and ``pressing_energy`` the joules that
    added.
    """

    events: list[tuple[float, str, list[str]]]
    positions: dict[str, tuple[float, float]]
    pocketed: dict[str, str]
    time: float
    pressings: int = 0
    pressing_energy: float = 0.0


def rack(game: str = "nine-ball", seed: int = 1) -> list[Ball]:
    """The balls of a rack (``"nine-ball"`` or ``"eight-ball"``) as ``(name, x, y)`` in
    metres, the cue ball first, with pooltool's spots and small seeded random offsets."""
    return [tuple(b) for b in _ccdsim.pool_rack(game, seed)]


def aim(balls: Sequence[Ball], target: str, cue: str = "cue") -> float:
    """The angle ``phi`` (degrees counter-clockwise from +x) from the cue ball straight at
    ``target``'s centre."""
    where = {name: (x, y) for name, x, y in balls}
    (cx, cy), (tx, ty) = where[cue], where[target]
    return math.degrees(math.atan2(ty - cy, tx - cx)) % 360.0


def shot(
    balls: Sequence[Ball],
    speed: float,
    phi: float,
    theta: float = 0.0,
    a: float = 0.0,
    b: float = 0.0,
    cue: str = "cue",
    max_events: int = 1_000_000,
    ball_ball: Optional[Mapping[str, float]] = None,
    record: Optional[str] = None,
    finder: str = "cells",
) -> Shot:
    """Strikes ball ``cue`` (``speed`` m/s towards ``phi`` degrees; cue elevation ``theta``
    degrees; tip offsets ``a`` (side) and ``b`` (height) in ball radii) and plays the shot
    until every ball rests or is pocketed. ``balls``: ``(name, x, y)`` in metres on
    pooltool's default 7-foot table (0.9906 x 1.9812 m). Balls meet without friction,
    elastically, unless ``ball_ball`` is given, as in a pool scene: ``{"restitution": e_b,
    "friction": mu}`` (0.95 and Alciatore's friction curve when left out) selects the
    frictional model. Raises ``ValueError`` for balls off the table or overlapping, for a tip
    that misses and for bad ``ball_ball`` numbers or keys, ``RuntimeError`` when the shot
    does not end within ``max_events`` events. With ``record``, the shot's run file is written
    to that path as it plays (``ccdsim verify``, ``ccdsim view`` and ``ccdsim export`` read
    it; docs/run-files.md, "Pool shots"). ``finder`` names how each event is found:
    ``"all-pairs"`` (the oracle), ``"sedgewick"``, ``"cells"`` or ``"bvh"``; every finder gives
    the same events, bit for bit (``ValueError`` for another name)."""
    model = None
    if ball_ball is not None:
        unknown = set(ball_ball) - {"restitution", "friction"}
        if unknown:
            raise ValueError(f"ball_ball: unknown keys {sorted(unknown)}")
        friction = ball_ball.get("friction")
        model = (
            float(ball_ball.get("restitution", 0.95)),
            None if friction is None else float(friction),
        )
    d = _ccdsim.pool_shot(
        [(str(n), float(x), float(y)) for n, x, y in balls],
        float(speed),
        float(phi),
        float(theta),
        float(a),
        float(b),
        cue,
        int(max_events),
        model,
        None if record is None else str(record),
        str(finder),
    )
    return Shot(
        events=[(t, k, list(agents)) for t, k, agents in d["events"]],
        positions={k: tuple(v) for k, v in d["positions"].items()},
        pocketed=dict(d["pocketed"]),
        time=d["time"],
        pressings=d["pressings"],
        pressing_energy=d["pressing_energy"],
    )
