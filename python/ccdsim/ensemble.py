"""Equation-of-state sweeps as tasks on a Dask cluster.

One task is one independent run (a packing and a seed): a periodic gas on a lattice at kT = 1,
equilibrated, then measured. :func:`eos_sweep` submits every (packing, seed) pair to a
``dask.distributed`` client and gathers the compressibility factor Z with its standard error
over seeds into a table. The tasks are plain functions of plain arguments, so any Dask
cluster (a LocalCluster, SLURM through dask-jobqueue, ...) runs them.

Example::

    from dask.distributed import Client, LocalCluster
    from ccdsim.ensemble import eos_sweep, format_table

    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        table = eos_sweep(client, packings=[0.2, 0.3, 0.4], seeds=range(4), dim=2, n=1000)
    print(format_table(table))
"""

from __future__ import annotations

import math
import statistics
from typing import Any, Iterable, Optional, Sequence

from . import generate
from . import Simulation

__all__ = ["eos_point", "eos_sweep", "reference_z", "format_table", "plot_table"]


def reference_z(dim: int, packing: float) -> float:
    """Z from Henderson's equation (2D discs) or Carnahan-Starling's (3D spheres) at this
    packing fraction."""
    eta = float(packing)
    if dim == 2:
        return (1.0 + eta * eta / 8.0) / (1.0 - eta) ** 2
    if dim == 3:
        return (1.0 + eta + eta * eta - eta**3) / (1.0 - eta) ** 3
    raise ValueError(f"dim must be 2 or 3, not {dim}")


def eos_point(
    dim: int,
    n: int,
    packing: float,
    seed: int,
    equilibrate: int,
    collisions: int,
    finder: str = "cells",
) -> dict[str, Any]:
    """One run: a periodic lattice gas of ``n`` bodies (diameter 1, kT = 1, zero momentum),
    ``equilibrate`` events, then ``collisions`` events measured. Returns ``dim``, ``n``,
    ``packing``, ``seed``, ``Z`` (over the measured window), ``temperature``, ``collision_rate``,
    ``sim_time`` (of the window) and ``events``."""
    scene = generate.gas(
        n=n,
        packing=packing,
        dim=dim,
        periodic=True,
        lattice=True,
        temperature=1.0,
        seed=seed,
    )
    sim = Simulation(scene, finder)
    sim.run_events(equilibrate)
    before, t0 = sim.stats(), sim.time
    done = sim.run_events(collisions)
    after, t1 = sim.stats(), sim.time
    kt = sim.observables()["temperature"]
    span = t1 - t0
    if span <= 0.0 or kt <= 0.0:
        raise RuntimeError(f"no measurement window (packing {packing}, seed {seed})")
    virial = after["virial"] - before["virial"]
    body = after["body_collisions"] - before["body_collisions"]
    return {
        "dim": dim,
        "n": n,
        "packing": packing,
        "seed": seed,
        "Z": 1.0 + virial / (dim * span * n * kt),
        "temperature": kt,
        "collision_rate": 2.0 * body / (n * span),
        "sim_time": span,
        "events": done,
    }


def eos_sweep(
    client: Any,
    packings: Sequence[float],
    seeds: Iterable[int],
    dim: int = 2,
    n: int = 1000,
    equilibrate: int = 50_000,
    collisions: int = 200_000,
    finder: str = "cells",
    progress: bool = False,
) -> list[dict[str, Any]]:
    """Runs every (packing, seed) as a task on the Dask ``client`` and returns one row per
    packing, in order: ``packing``, ``Z`` (mean over seeds), ``Z_error`` (standard error of that
    mean; needs two seeds or more), ``Z_reference`` (Henderson / Carnahan-Starling),
    ``collision_rate`` and its error, ``runs`` and ``events``."""
    seeds = list(seeds)
    if len(seeds) < 2:
        raise ValueError("error bars need at least two seeds")
    futures = {
        (p, s): client.submit(
            eos_point, dim, n, p, s, equilibrate, collisions, finder, pure=False
        )
        for p in packings
        for s in seeds
    }
    if progress:
        from dask.distributed import progress as show_progress

        show_progress(list(futures.values()))
    results = dict(zip(futures.keys(), client.gather(list(futures.values()))))
    table = []
    for p in packings:
        runs = [results[(p, s)] for s in seeds]
        z = [r["Z"] for r in runs]
        rate = [r["collision_rate"] for r in runs]
        table.append(
            {
                "packing": p,
                "Z": statistics.fmean(z),
                "Z_error": statistics.stdev(z) / math.sqrt(len(z)),
                "Z_reference": reference_z(dim, p),
                "collision_rate": statistics.fmean(rate),
                "collision_rate_error": statistics.stdev(rate) / math.sqrt(len(rate)),
                "runs": len(runs),
                "events": sum(r["events"] for r in runs),
            }
        )
    return table


def format_table(table: Sequence[dict[str, Any]]) -> str:
    """The sweep's table as aligned text."""
    lines = [f"{'packing':>8} {'Z':>9} {'error':>8} {'reference':>9} {'runs':>5}"]
    for row in table:
        lines.append(
            f"{row['packing']:>8.3f} {row['Z']:>9.4f} {row['Z_error']:>8.4f} "
            f"{row['Z_reference']:>9.4f} {row['runs']:>5d}"
        )
    return "\n".join(lines)


def plot_table(
    table: Sequence[dict[str, Any]], path: str, dim: int = 2, title: Optional[str] = None
) -> None:
    """Plots Z with error bars against packing, and the reference equation of state, to
    ``path`` (PNG, SVG, ... by extension). Needs matplotlib."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    packings = [r["packing"] for r in table]
    fig, ax = plt.subplots(figsize=(5, 3.5))
    lo, hi = min(packings), max(packings)
    grid = [lo + (hi - lo) * k / 100 for k in range(101)]
    name = "Henderson" if dim == 2 else "Carnahan-Starling"
    ax.plot(grid, [reference_z(dim, p) for p in grid], "-", color="0.6", label=name)
    ax.errorbar(
        packings,
        [r["Z"] for r in table],
        yerr=[r["Z_error"] for r in table],
        fmt="o",
        capsize=3,
        label="ccdsim (Dask sweep)",
    )
    ax.set_xlabel("packing fraction")
    ax.set_ylabel("Z = PV / NkT")
    ax.set_title(title or f"{dim}D hard {'discs' if dim == 2 else 'spheres'}")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
