"""Quickstart for physicists: a hard-disc fluid from set-up to g(r), diffusion and pressure.

Run it as a script (``python python/examples/quickstart.py --out results/``) or paste the cells
(marked ``# %%``) into Jupyter. Every number is computed here, in a few seconds; nothing is
read from elsewhere. Needs the package with its analysis extras: ``pip install "./python[analysis]"``.
"""

# %% Set-up: 2000 discs of diameter 1 at packing 0.4, kT = 1, on a lattice that melts.
import argparse
from pathlib import Path

import numpy as np

import ccdsim
from ccdsim.ensemble import reference_z

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", type=Path, default=Path("."), help="directory for the outputs")
parser.add_argument("--n", type=int, default=2000, help="number of discs")
args = parser.parse_args()
args.out.mkdir(parents=True, exist_ok=True)

packing = 0.4
scene = ccdsim.generate.gas(n=args.n, packing=packing, dim=2, periodic=True, lattice=True,
                            temperature=1.0, seed=1)
sim = ccdsim.Simulation(scene)
sim.run_events(50 * args.n)  # equilibrate: about 100 collisions per disc
kind, origin, box = sim.cell()
print(f"{len(sim)} discs in a periodic box {box[0]:.2f} x {box[1]:.2f}, t = {sim.time:.2f}")

# %% Sample frames every 0.05 time units for 10 time units; keep a GSD file for OVITO/HOOMD.
dt, span = 0.05, 10.0
frames = list(sim.frames(every=dt, until=sim.time + span))
positions = np.array([f.positions for f in frames])             # F x N x 2, in the box
unwrapped = np.array([f.unwrapped_positions for f in frames])   # F x N x 2, paths
velocities = np.array([f.velocities for f in frames])
gsd_file = args.out / "quickstart.gsd"
ccdsim.Simulation(scene).write_trajectory(str(gsd_file), every=1.0, until=5.0)
print(f"{len(frames)} frames sampled; a GSD trajectory is in {gsd_file}")

# %% Structure: the radial distribution function.
r, g = ccdsim.observables.rdf(positions, box, r_max=5.0, bins=200)
peak = r[np.argmax(g)]
print(f"g(r): contact peak {g.max():.3f} at r = {peak:.3f}")

# %% Dynamics: mean-square displacement (Einstein) and velocity autocorrelation (Green-Kubo).
msd = ccdsim.observables.msd(unwrapped)
vacf = ccdsim.observables.vacf(velocities)
lags = np.arange(len(msd)) * dt
late = lags > 2.0  # past the ballistic regime
slope = np.polyfit(lags[late], msd[late], 1)[0]
d_einstein = slope / (2 * 2)                      # MSD = 2 D d t in d = 2 dimensions
half = len(vacf) // 2                            # the well-averaged half of the lags
d_green_kubo = np.trapezoid(vacf[:half], dx=dt) / 2
print(f"diffusion coefficient: {d_einstein:.4f} (MSD), {d_green_kubo:.4f} (VACF)")

# %% Pressure: the full tensor from the collisions, and Z against Henderson's equation.
before = sim.time
p = sim.run_until_pressure_tensor(before + 20.0)
kt = sim.observables()["temperature"]
density = len(sim) / (box[0] * box[1])
z = np.trace(p) / 2 / (density * kt)
print(f"pressure tensor\n{p}\nZ = {z:.4f} (Henderson {reference_z(2, packing):.4f})")

# %% A figure of it all.
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, ax = plt.subplots(1, 3, figsize=(12, 3.5))
ax[0].plot(r, g)
ax[0].set(xlabel="r", ylabel="g(r)", title=f"hard discs, packing {packing}")
ax[1].loglog(lags[1:], msd[1:])
ax[1].set(xlabel="t", ylabel="MSD", title=f"D = {d_einstein:.3f}")
ax[2].plot(lags[:half], vacf[:half] / vacf[0])
ax[2].set(xlabel="t", ylabel="VACF / VACF(0)")
fig.tight_layout()
figure = args.out / "quickstart.png"
fig.savefig(figure, dpi=100)
print(f"figure written to {figure}")
