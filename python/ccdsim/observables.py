"""Observables over frames of a run: g(r), mean-square displacement, velocity autocorrelation.

Frames are NumPy arrays ``F x N x D`` (frames x bodies x coordinates), as collected from
:meth:`ccdsim.Simulation.frames`, or read from a trajectory file. The sums run in Rust (g(r) on a
cell grid, the time correlations by FFT over every time origin). The pressure tensor comes from
the collisions themselves: :meth:`ccdsim.Simulation.run_until_pressure_tensor`.

Example::

    import numpy as np, ccdsim
    sim = ccdsim.Simulation(ccdsim.generate.gas(n=500, packing=0.4, periodic=True, seed=1))
    frames = list(sim.frames(every=0.1, until=20.0))
    kind, origin, box = sim.cell()
    r, g = ccdsim.observables.rdf(np.array([f.positions for f in frames]), box, r_max=5.0)
    msd = ccdsim.observables.msd(np.array([f.unwrapped_positions for f in frames]))
"""

from __future__ import annotations

from typing import Optional, Sequence, Tuple

import numpy as np

from . import _ccdsim

__all__ = ["rdf", "msd", "vacf"]


def _frames(a: np.ndarray, what: str) -> np.ndarray:
    a = np.ascontiguousarray(a, dtype=np.float64)
    if a.ndim == 2:
        a = a[np.newaxis]
    if a.ndim != 3 or a.shape[2] not in (2, 3):
        raise ValueError(f"{what} must be F x N x 2 or F x N x 3 (or N x D), not {a.shape}")
    return a


def rdf(
    positions: np.ndarray,
    box: Sequence[float],
    r_max: float,
    bins: int = 100,
    periodic: bool = True,
    origin: Optional[Sequence[float]] = None,
) -> Tuple[np.ndarray, np.ndarray]:
    """The radial distribution function g(r), summed over frames.

    ``positions``: ``F x N x D`` (or one frame ``N x D``), m. ``box``: the D side lengths of the
    cell whose lowest corner is ``origin`` (default zero, as in ccdsim's periodic box).
    ``periodic``: nearest-image distances (``r_max`` at most half the shortest side); otherwise
    direct distances in the box of the walls. Returns the shells' centres (m) and g per shell,
    normalised so that g -> 1 at large r for any N (N(N-1)/V pair density, freud's "exact").
    """
    a = _frames(positions, "positions")
    dim = a.shape[2]
    origin = [0.0] * dim if origin is None else [float(x) for x in origin]
    r, g, _ = _ccdsim.rdf(a, origin, [float(x) for x in box], bool(periodic), float(r_max), int(bins))
    return r, g


def msd(unwrapped_positions: np.ndarray) -> np.ndarray:
    """Mean-square displacement (m^2) for lags 0 .. F-1 frames, averaged over bodies and every
    time origin. ``unwrapped_positions`` is ``F x N x D`` (see ``Frame.unwrapped_positions``);
    frames must be equally spaced in time."""
    return _ccdsim.msd(_frames(unwrapped_positions, "unwrapped_positions"))


def vacf(velocities: np.ndarray) -> np.ndarray:
    """Velocity autocorrelation <v(t0) . v(t0 + lag)> (m^2/s^2) for lags 0 .. F-1 frames,
    averaged over bodies and every time origin. ``velocities`` is ``F x N x D``; frames equally
    spaced in time. Its integral over time divided by D is the diffusion coefficient."""
    return _ccdsim.vacf(_frames(velocities, "velocities"))
