"""Exact event-driven simulation of hard discs (2D) and hard spheres (3D).

Python bindings of the Rust library ccdsim. Bodies move in straight lines between events; the
next contact is found exactly (every finder returns, bit for bit, the event the all-pairs
search would), resolved by an impulse, and the loop goes on. Units are the scene's (metres,
seconds, kilograms; Boltzmann's constant is 1).

Example::

    import ccdsim
    scene = ccdsim.generate.gas(n=400, packing=0.3, periodic=True, lattice=True,
                                temperature=1.0, seed=1)
    sim = ccdsim.Simulation(scene)
    sim.run_events(10_000)              # in Rust, without the GIL
    print(sim.time, sim.observables()["compressibility"])
    x = sim.positions                   # N x D NumPy array
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any, Iterator, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _ccdsim
from . import billiards
from . import generate
from . import observables
from . import packing

__all__ = [
    "Simulation",
    "Frame",
    "read_run",
    "events_array",
    "EVENT_DTYPE",
    "SENSOR_EVENT_DTYPE",
    "FINDER_NAMES",
    "billiards",
    "generate",
    "observables",
    "packing",
]

#: Names of the finders (broad phases); all give the same events bit for bit.
FINDER_NAMES: list[str] = list(_ccdsim.FINDER_NAMES)

#: Kinds in the ``kind`` field of an event: body-body, body-wall, and a thermostat's velocity
#: reset of body ``a`` (scenes with ``settings.thermostat``).
BODY, WALL, RESET = 0, 1, 2


def EVENT_DTYPE(dim: int) -> np.dtype:
    """The NumPy structured dtype of events in ``dim`` dimensions.

    Fields: ``t`` (time, s), ``kind`` (0 body-body, 1 body-wall, 2 thermostat reset, 3 edit), ``a``, ``b``
    (body indices, or body and wall index; for a reset the body and 0), ``pos`` (2 x dim: the bodies' positions at ``t``; the second zero for a
    wall event) and ``vel`` (2 x dim: their velocities after the event), ``rests`` (2 bools:
    the body rests on a wall after the event, see ``settings.rest_speed``) and ``pivots``
    (2 bools: the body turns about a segment's end point after the event, rolling over an
    edge, from ``pos`` and ``vel``).
    """
    return np.dtype(
        [
            ("t", "f8"),
            ("kind", "u1"),
            ("a", "u4"),
            ("b", "u4"),
            ("pos", "f8", (2, dim)),
            ("vel", "f8", (2, dim)),
            ("rests", "?", (2,)),
            ("pivots", "?", (2,)),
        ]
    )


def events_array(arrays: Mapping[str, np.ndarray], dim: int) -> np.ndarray:
    """Events as a structured array (see :func:`EVENT_DTYPE`) from the extension's arrays."""
    out = np.zeros(len(arrays["t"]), dtype=EVENT_DTYPE(dim))
    for name in ("t", "kind", "a", "b", "pos", "vel", "rests", "pivots"):
        out[name] = arrays[name]
    return out


SENSOR_EVENT_DTYPE = np.dtype(
    [("t", "f8"), ("body", "u4"), ("sensor", "u4"), ("enter", "?")]
)
"""Fields of a sensor event: its time ``t`` (s), the ``body`` and ``sensor`` indices, and
``enter`` (True when the body started to overlap the sensor, False when it stopped)."""


SceneLike = Union[str, Mapping[str, Any]]


@dataclass(frozen=True)
class Frame:
    """The bodies at one instant (see :meth:`Simulation.frame`).

    ``positions`` (N x D, m; inside ``[0, L)`` in a periodic box), ``images`` (N x D integers:
    ``positions + images * box`` are the unwrapped positions), ``velocities`` (N x D, m/s) and
    the ``time`` (s). ``box`` is the periodic box's sides (None otherwise).
    """

    time: float
    positions: np.ndarray
    images: np.ndarray
    velocities: np.ndarray
    box: Optional[np.ndarray]

    @property
    def unwrapped_positions(self) -> np.ndarray:
        """Positions plus the periods crossed: the paths travelled, N x D, m."""
        if self.box is None:
            return self.positions
        return self.positions + self.images * self.box


def _scene_json(scene: SceneLike) -> str:
    if isinstance(scene, str):
        return scene
    return json.dumps(scene)


class Simulation:
    """An exact event-driven simulation of a scene.

    ``scene`` is a scene in the scene-file format (see docs/scene-format.md): a dict, or its
    JSON text.
    ``finder`` names the broad phase (default ``"cells"``, the fast one). Bad input raises
    ``ValueError`` with a one-line message naming the field or body.
    """

    def __init__(self, scene: SceneLike, finder: str = "cells") -> None:
        self._sim = _ccdsim.Simulation(_scene_json(scene), finder)

    @classmethod
    def from_arrays(
        cls,
        positions: Sequence[Sequence[float]],
        velocities: Sequence[Sequence[float]],
        radii: Sequence[float],
        masses: Optional[Sequence[float]] = None,
        walls: Optional[Sequence[Mapping[str, Any]]] = None,
        periodic: Optional[Sequence[float]] = None,
        restitution: float = 1.0,
        start_time: float = 0.0,
        finder: str = "cells",
    ) -> "Simulation":
        """A simulation of bodies given as arrays: positions and velocities N x D, radii (and
        masses, default unit density) of length N; walls as in the scene format; a periodic
        box as its D side lengths."""
        pos = np.asarray(positions, dtype=float)
        vel = np.asarray(velocities, dtype=float)
        rad = np.asarray(radii, dtype=float)
        if pos.ndim != 2 or pos.shape[1] not in (2, 3):
            raise ValueError(f"positions must be N x 2 or N x 3, not {pos.shape}")
        if vel.shape != pos.shape or rad.shape != (pos.shape[0],):
            raise ValueError(
                f"velocities {vel.shape} and radii {rad.shape} must match positions {pos.shape}"
            )
        bodies = []
        for i in range(pos.shape[0]):
            body: dict[str, Any] = {
                "pos": pos[i].tolist(),
                "vel": vel[i].tolist(),
                "radius": float(rad[i]),
            }
            if masses is not None:
                body["mass"] = float(masses[i])
            bodies.append(body)
        scene: dict[str, Any] = {
            "dim": int(pos.shape[1]),
            "settings": {"restitution": float(restitution)},
            "start_time": float(start_time),
            "bodies": bodies,
            "walls": list(walls or []),
        }
        if periodic is not None:
            scene["periodic"] = [float(x) for x in periodic]
        return cls(scene, finder)

    @property
    def dim(self) -> int:
        """2 or 3."""
        return self._sim.dim

    def __len__(self) -> int:
        """Number of body slots: bodies, and vacant slots after :meth:`remove_body`."""
        return len(self._sim)

    @property
    def finder(self) -> str:
        """The finder's name."""
        return self._sim.finder

    @property
    def time(self) -> float:
        """Current simulated time, s."""
        return self._sim.time

    @property
    def positions(self) -> np.ndarray:
        """Positions at the current time, N x D (inside the box in periodic worlds), m."""
        return self._sim.positions

    @property
    def velocities(self) -> np.ndarray:
        """Velocities, N x D, m/s."""
        return self._sim.velocities

    @property
    def spins(self) -> np.ndarray:
        """Angular velocities, N x 3, rad/s (a disc spins about the third axis; zeros unless
        the scene has rough bodies or spins: ``settings.tangential_restitution``,
        ``bodies[].spin``)."""
        return self._sim.spins

    @property
    def images(self) -> np.ndarray:
        """Periodic images, N x D integers: ``positions + images * box`` are the unwrapped
        positions (zeros without a periodic box)."""
        return self._sim.images

    @property
    def unwrapped_positions(self) -> np.ndarray:
        """Unwrapped positions (the paths travelled, never folded into the box), N x D, m."""
        return self._sim.unwrapped_positions

    def cell(self) -> Tuple[str, Optional[np.ndarray], Optional[np.ndarray]]:
        """The simulation cell as ``(kind, origin, size)``: kind ``"periodic"`` (the box
        ``[0, L)``), ``"walls"`` (the walls' bounding box) or ``"open"`` (origin, size None)."""
        kind, origin, size = self._sim.cell()
        as_array = lambda v: None if v is None else np.asarray(v)  # noqa: E731
        return kind, as_array(origin), as_array(size)

    def frame(self) -> Frame:
        """The bodies now, as a :class:`Frame`."""
        kind, _, size = self.cell()
        return Frame(
            time=self.time,
            positions=self.positions,
            images=self.images,
            velocities=self.velocities,
            box=size if kind == "periodic" else None,
        )

    def frames(self, every: float, until: float) -> Iterator[Frame]:
        """Runs to ``until``, yielding a :class:`Frame` every ``every`` seconds from now (now
        included). Sample times are ``t0 + k * every``, computed from ``k``. Stops early if the
        run halts (see :attr:`halt`)."""
        every, until = float(every), float(until)
        if not (every > 0.0 and np.isfinite(every)):
            raise ValueError(f"every must be a positive number of seconds, not {every}")
        t0 = self.time
        k = 0
        while True:
            t = t0 + k * every
            if t > until:
                break
            self.run_until(t)
            if self.time < t:
                break
            yield self.frame()
            k += 1

    def write_trajectory(self, path: str, every: float, until: float) -> int:
        """Runs to ``until``, writing a frame every ``every`` seconds from now (now included) to
        ``path``: extended XYZ for ``.xyz``/``.extxyz`` (ASE, OVITO; full precision), GSD for
        ``.gsd`` (the ``gsd`` package, HOOMD, freud; float32, box centred on the origin).
        Returns the number of frames. Runs in Rust without the GIL.

        This advances the simulation: afterwards :attr:`time` is the last frame's time (or
        where the run halted), as after :meth:`run_until`. To keep a simulation where it is,
        write the trajectory from a second ``Simulation`` of the same scene."""
        return self._sim.write_trajectory(str(path), float(every), float(until))

    def run_until_pressure_tensor(self, t: float) -> np.ndarray:
        """Runs to time ``t`` and returns the pressure tensor (D x D) over that stretch: the
        time-integrated kinetic tensor (centre-of-mass frame when periodic) plus the collision
        virial, over the volume. Its trace / D is the scalar pressure of :meth:`observables`."""
        return self._sim.run_until_pressure_tensor(float(t))

    @property
    def radii(self) -> np.ndarray:
        """Radii now, m (they grow in a scene with ``settings.growth``)."""
        return self._sim.radii

    @property
    def masses(self) -> np.ndarray:
        """Masses, kg."""
        return self._sim.masses

    @property
    def halt(self) -> Optional[str]:
        """Why the run stopped while events remained (a contact beyond the largest time, or
        time no longer resolving a body), or None."""
        return self._sim.halt

    def step(self) -> Optional[np.void]:
        """Resolves the next event and returns it (a record of :func:`EVENT_DTYPE`), or None
        when no event will ever happen."""
        ev = events_array(self._sim.step(), self.dim)
        return ev[0] if len(ev) else None

    def run_until(self, t: float) -> int:
        """Resolves every event up to time ``t`` and moves the clock to ``t``; returns the number
        of events. The loop runs in Rust without the GIL."""
        return self._sim.run_until(float(t))

    def run_events(self, n: int) -> int:
        """Resolves up to ``n`` events; returns the number resolved (fewer when none is left)."""
        return self._sim.run_events(int(n))

    def advance(self, dt: float) -> np.ndarray:
        """Advances the clock by ``dt`` seconds (one game frame) and returns the frame's events
        as a structured array, in order."""
        return events_array(self._sim.advance(float(dt)), self.dim)

    def set_velocity(self, i: int, v: Sequence[float]) -> None:
        """Gives body ``i`` velocity ``v`` from the current time on."""
        self._sim.set_velocity(int(i), [float(x) for x in v])

    def set_position(self, i: int, p: Sequence[float]) -> None:
        """Moves body ``i`` to ``p`` at the current time, keeping its velocity (a teleport);
        raises ValueError where it would overlap another body or a wall."""
        self._sim.set_position(int(i), [float(x) for x in p])

    def set_collision_filter(self, i: int, group: int, mask: int = 0xFFFFFFFF) -> None:
        """Gives body ``i`` the collision ``group`` and ``mask`` bit sets from now on: two
        bodies collide only when each one's group shares a bit with the other's mask (group 0:
        a ghost that collides with no body). Raises ValueError when it would make overlapping
        bodies collide."""
        self._sim.set_collision_filter(int(i), int(group), int(mask))

    def set_wall_velocity(self, k: int, v: Sequence[float]) -> None:
        """Gives moving wall ``k`` (the scene's ``moving_walls[k]``, wall ``len(walls) + k`` in
        events) velocity ``v`` from the current time on: a paddle steered each frame, a piston
        started or stopped. The wall stays where it is now; bodies bounce off it exactly.

        >>> sim = Simulation({"dim": 2, "bodies": [{"pos": [0, 5], "vel": [0, 0], "radius": 0.5}],
        ...                   "moving_walls": [{"point": [0, 0], "normal": [0, 1]}]})
        >>> sim.set_wall_velocity(0, [0, 1])
        >>> e = sim.step()
        >>> float(e["t"]), int(e["b"]), sim.wall_offset(0)
        (4.5, 0, [0.0, 4.5])
        """
        self._sim.set_wall_velocity(int(k), [float(x) for x in v])

    def wall_offset(self, k: int) -> list:
        """How far moving wall ``k`` has moved from where the scene put it, now (metres)."""
        return self._sim.wall_offset(int(k))

    def add_body(
        self,
        pos: Sequence[float],
        vel: Sequence[float],
        radius: float,
        *,
        mass: Optional[float] = None,
        restitution: Optional[float] = None,
        kinematic: bool = False,
        group: Optional[int] = None,
        mask: Optional[int] = None,
        id: Optional[int] = None,
    ) -> int:
        """Adds a body at the current time and returns its index, which names it until it is
        removed (a removed body's slot may be filled again). Fields as in a scene's
        ``bodies``; ``id`` defaults to one above every id so far. Raises ValueError when a
        field is invalid, the id is taken, or the body would overlap a body or a wall. With
        ``settings.growth``, ``radius`` is its radius now (it grows from then on); with
        ``settings.thermostat``, it takes resets from now on unless it is kinematic.

        >>> sim = Simulation({"dim": 2, "bodies": []}, finder="cells")
        >>> a = sim.add_body([0, 0], [1, 0], 0.5)
        >>> b = sim.add_body([3, 0], [-1, 0], 0.5)
        >>> float(sim.step()["t"])
        1.0
        """
        return self._sim.add_body(
            [float(x) for x in pos],
            [float(x) for x in vel],
            float(radius),
            None if mass is None else float(mass),
            None if restitution is None else float(restitution),
            bool(kinematic),
            None if group is None else int(group),
            None if mask is None else int(mask),
            None if id is None else int(id),
        )

    def remove_body(self, i: int) -> None:
        """Removes body ``i`` now: its slot becomes vacant (see :attr:`present`) and every other
        body keeps its index. A body inside a sensor leaves it."""
        self._sim.remove_body(int(i))

    @property
    def present(self) -> np.ndarray:
        """Which slots hold a body, N booleans: arrays such as :attr:`positions` have a row
        per slot, and a vacant slot's row is a body at rest that takes part in nothing."""
        return self._sim.present

    @property
    def ids(self) -> np.ndarray:
        """Each slot's user id, N unsigned integers (2**64 - 1 for a vacant slot)."""
        return self._sim.ids

    def take_sensor_events(self) -> np.ndarray:
        """The scene's sensor events since the last call, in time order, as a structured
        array (see :data:`SENSOR_EVENT_DTYPE`): bodies entering and leaving the ``sensors``
        regions as the clock passed them. Empty for a scene without sensors."""
        arrays = self._sim.take_sensor_events()
        out = np.zeros(len(arrays["t"]), dtype=SENSOR_EVENT_DTYPE)
        for name in ("t", "body", "sensor", "enter"):
            out[name] = arrays[name]
        return out

    def rescale_velocities(self, factor: float) -> None:
        """Multiplies every velocity by ``factor`` from now on (growing packings heat up; this
        cools them). O(n): every body's next events are computed anew."""
        self._sim.rescale_velocities(float(factor))

    def stop_growth(self) -> None:
        """Stops the growth of the radii (``settings.growth``) now: they keep their current
        values from here on."""
        self._sim.stop_growth()

    def stats(self) -> dict:
        """Counters: ``events``, ``body_collisions``, ``wall_collisions``, ``max_overlap``,
        ``kinetic_energy_start`` (J), the collision ``virial``, thermostat ``resets`` (counted in
        ``events``), and the bodies the scene's ``arrivals`` brought in so far (``arrivals``) with
        the energy they brought (``arrival_energy``, J, kinetic plus potential)."""
        return self._sim.stats()

    def kinetic_energy(self) -> float:
        """Total kinetic energy now, J."""
        return self._sim.kinetic_energy()

    def rotational_energy(self) -> float:
        """Rotational kinetic energy now, J (0 unless the bodies spin)."""
        return self._sim.rotational_energy()

    def potential_energy(self) -> float:
        """Potential energy in the scene's gravity field now (``settings.gravity``), J:
        ``-sum(m g . x)``, zero without gravity. Elastic collisions keep kinetic plus
        potential energy."""
        return self._sim.potential_energy()

    def observables(self) -> dict:
        """Over the run so far: ``temperature`` (kT), ``rotational_temperature`` (kT_rot =
        2 K_rot / (f N), f = 1 for discs and 3 for spheres; None unless the bodies spin),
        ``collision_rate`` (per body per unit time), ``volume``, ``pressure`` and
        ``compressibility`` (Z = PV/NkT; None without a volume)."""
        return self._sim.observables()


def read_run(path: str) -> dict:
    """Reads a run file written by ``ccdsim run --record``: a dict with ``scene`` (the initial
    scene, a dict), ``events`` (a structured array, see :func:`EVENT_DTYPE`), ``end`` (the time
    the run stopped at, or None) and ``complete`` (False for a run cut short)."""
    raw = _ccdsim.read_run(str(path))
    scene = json.loads(raw["scene"])
    return {
        "scene": scene,
        "events": events_array(raw, int(scene["dim"])),
        "end": raw["end"],
        "complete": raw["complete"],
    }
