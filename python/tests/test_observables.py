"""Observables against freud on the same frames (g(r), MSD), against their definitions
(VACF) and against the scalar pressure (pressure tensor)."""

import freud
import numpy as np
import pytest

import ccdsim


def run_frames(dim, n, packing, every, until, seed=2):
    scene = ccdsim.generate.gas(n=n, packing=packing, dim=dim, periodic=True, lattice=True,
                                temperature=1.0, seed=seed)
    sim = ccdsim.Simulation(scene)
    sim.run_events(20 * n)  # melt the lattice
    frames = list(sim.frames(every=every, until=sim.time + until))
    return sim, frames, np.asarray(scene["periodic"])


def freud_box(box):
    if len(box) == 2:
        return freud.box.Box(Lx=box[0], Ly=box[1], is2D=True)
    return freud.box.Box(Lx=box[0], Ly=box[1], Lz=box[2])


def as3(points):
    if points.shape[-1] == 3:
        return points
    return np.concatenate([points, np.zeros(points.shape[:-1] + (1,))], axis=-1)


@pytest.mark.parametrize("dim, packing", [(2, 0.5), (3, 0.35)])
def test_rdf_matches_freud(dim, packing):
    sim, frames, box = run_frames(dim, 1000 if dim == 2 else 1500, packing, 0.2, 4.0)
    positions = np.array([f.positions for f in frames])
    r_max = 0.45 * box.min()
    bins = int(r_max / 0.05)
    r, g = ccdsim.observables.rdf(positions, box, r_max=r_max, bins=bins)

    rdf = freud.density.RDF(bins=bins, r_max=r_max)
    fbox = freud_box(box)
    for p in positions:
        rdf.compute(system=(fbox, as3(p - box / 2)), reset=False)
    np.testing.assert_allclose(r, rdf.bin_centers, rtol=1e-6)
    # freud works in float32: a pair within ~1e-7 of a shell edge may land in the next shell.
    np.testing.assert_allclose(g, rdf.rdf, rtol=2e-3, atol=1e-3)
    # Hard bodies of diameter 1: no pair in a shell wholly inside it, a contact peak at it.
    width = r[1] - r[0]
    assert np.all(g[r + width / 2 <= 1.0] == 0)
    assert g[np.argmax(r - width / 2 >= 1.0)] > 1.5


@pytest.mark.parametrize("dim", [2, 3])
def test_msd_matches_freud_on_unwrapped_positions(dim):
    sim, frames, box = run_frames(dim, 500, 0.3, 0.05, 5.0)
    unwrapped = np.array([f.unwrapped_positions for f in frames])
    # Bodies cross faces during the window: images at work.
    assert np.any(frames[-1].images != frames[0].images)
    mine = ccdsim.observables.msd(unwrapped)
    # freud sums in float32: given positions relative to the first frame its rounding is small.
    theirs = freud.msd.MSD(mode="window").compute(as3(unwrapped - unwrapped[0])).msd
    np.testing.assert_allclose(mine, theirs, rtol=1e-4, atol=1e-6)
    # And freud unwrapping from images agrees with the package's unwrapped positions.
    wrapped = np.array([f.positions - box / 2 for f in frames])
    images = np.array([f.images for f in frames])
    via_images = freud.msd.MSD(box=freud_box(box), mode="window").compute(
        as3(wrapped), images=as3(images).astype(np.int32)).msd
    # Here freud squares coordinates of the box's size in float32: agreement to its rounding.
    np.testing.assert_allclose(mine[10:], via_images[10:], rtol=1e-2)


def test_vacf_matches_its_definition():
    sim, frames, box = run_frames(3, 300, 0.3, 0.05, 3.0)
    v = np.array([f.velocities for f in frames])
    mine = ccdsim.observables.vacf(v)
    fcount = len(v)
    direct = [np.mean(np.sum(v[: fcount - m] * v[m:], axis=2)) for m in range(fcount)]
    np.testing.assert_allclose(mine, direct, rtol=1e-9, atol=1e-12)
    # <v^2> = D kT / m with m = pi/6 for unit spheres of unit density.
    assert mine[0] == pytest.approx(3 * sim.observables()["temperature"] / (np.pi / 6), rel=1e-9)
    assert mine[-1] < 0.2 * mine[0]  # decorrelates


def test_pressure_tensor_traces_to_the_scalar_pressure():
    scene = ccdsim.generate.gas(n=800, packing=0.4, dim=2, periodic=True, lattice=True,
                                temperature=1.0, seed=5)
    sim = ccdsim.Simulation(scene)
    p = sim.run_until_pressure_tensor(30.0)
    scalar = sim.observables()["pressure"]
    assert np.trace(p) / 2 == pytest.approx(scalar, rel=1e-9)
    np.testing.assert_allclose(p, p.T, rtol=0, atol=1e-9 * scalar)
    assert abs(p[0, 1]) < 0.05 * scalar
    assert p[0, 0] == pytest.approx(p[1, 1], rel=0.05)


def test_a_sheared_box_has_a_shear_stress_near_enskogs_viscosity():
    # Lees–Edwards shear at a small rate: the pressure tensor's kinetic part is taken in
    # peculiar velocities, and -P_xy / rate is the viscosity (Enskog: 0.2232 in units of
    # sqrt(m kT) / sigma^2 at packing 0.1, m = pi/6 here).
    rate = 0.15
    scene = ccdsim.generate.gas(n=1500, packing=0.1, dim=3, periodic=True, temperature=1.0,
                                radius_min=0.5, radius_max=0.5, seed=3)
    ly = scene["periodic"][1]
    scene["settings"]["shear_rate"] = rate
    for b in scene["bodies"]:
        b["vel"][0] += rate * (b["pos"][1] - ly / 2)
    sim = ccdsim.Simulation(scene)
    sim.run_events(20 * 1500)
    kt0 = sim.observables()["temperature"]
    p = sim.run_until_pressure_tensor(sim.time + 40)
    kt = 0.5 * (kt0 + sim.observables()["temperature"])
    np.testing.assert_allclose(p, p.T, rtol=0, atol=1e-9 * np.trace(p))
    eta = -p[0, 1] / rate / np.sqrt(np.pi / 6 * kt)
    assert eta == pytest.approx(0.2232, rel=0.2)
    # The temperature is the peculiar one: the flow's kinetic energy is left out.
    assert 0.9 < kt < 1.6


def test_bad_frames_are_refused():
    with pytest.raises(ValueError, match="F x N x 2"):
        ccdsim.observables.msd(np.zeros((3, 4, 5)))
    with pytest.raises(ValueError, match="half"):
        ccdsim.observables.rdf(np.zeros((1, 4, 2)), [4.0, 4.0], r_max=3.0)
    sim = ccdsim.Simulation(ccdsim.generate.gas(n=10, packing=0.1, periodic=True, seed=1))
    with pytest.raises(ValueError, match="positive"):
        list(sim.frames(every=0.0, until=1.0))
