"""Growing radii and jammed packings through the Python package."""

import numpy as np
import pytest

import ccdsim


def contact_gaps(p, sim):
    """The gaps of a periodic packing's contacts, relative to their contact distances."""
    x, r = sim.positions, sim.radii
    box = np.array(p["scene"]["periodic"])
    i, j = p["contacts"].T
    d = x[j] - x[i]
    d -= box * np.round(d / box)
    return np.linalg.norm(d, axis=1) / (r[i] + r[j]) - 1


def test_a_bidisperse_2d_packing_jams_near_0_84():
    p = ccdsim.packing.pack(dim=2, n=300, bidisperse=1.4, rate=0.02, until_pressure=1e8, seed=2)
    assert p["stop"] == "pressure"
    assert p["reduced_pressure"] >= 1e8
    assert 0.8 < p["packing_fraction"] < 0.87
    assert p["contacts"].shape[1] == 2 and len(p["contacts"]) > 300
    assert 3.5 < p["mean_contacts"] <= 4.0
    assert len(p["rattlers"]) < 60
    # The packing goes on as a simulation, touching pairs within the tolerance of contact.
    sim = ccdsim.Simulation(p["scene"])
    gap = contact_gaps(p, sim)
    assert np.all(gap <= p["contact_tolerance"]) and np.all(gap > -1e-12)
    assert sim.run_events(5000) == 5000
    assert sim.stats()["max_overlap"] < 1e-9


def test_an_isostatic_finish_makes_the_contacts_hold_the_packing():
    plain = ccdsim.packing.pack(dim=2, n=300, bidisperse=1.4, rate=0.05, until_pressure=1e4, seed=3)
    assert plain["finish"] is None
    p = ccdsim.packing.pack(dim=2, n=300, bidisperse=1.4, rate=0.05, seed=3, isostatic=True)
    assert p["rigid"] and p["held_contacts"] >= p["isostatic_contacts"] > 0
    assert p["mean_contacts"] >= 3.97
    assert p["finish"]["mean_overlap"] <= 1e-6 and p["finish"]["minimizations"] >= 2
    # The touching pairs are apart, within the tolerance, and the packing holds its pressure
    # at fixed radii: it is jammed, not held up by growth.
    sim = ccdsim.Simulation(p["scene"])
    gap = contact_gaps(p, sim)
    assert np.all(gap <= p["contact_tolerance"]) and np.all(gap > -1e-12)
    assert sim.run_events(20 * 300) == 20 * 300
    z = sim.observables()["compressibility"]
    assert z > 1e4
    held_by_growth = ccdsim.Simulation(plain["scene"])
    held_by_growth.run_events(20 * 300)
    assert held_by_growth.observables()["compressibility"] < z / 3


def test_radii_grow_and_stop_growing():
    scene = ccdsim.generate.gas(n=100, packing=0.2, periodic=True, temperature=1.0, seed=4)
    scene["settings"]["growth"] = {"rate": 0.1}
    sim = ccdsim.Simulation(scene)
    r0 = sim.radii.copy()
    sim.run_until(2.0)
    np.testing.assert_allclose(sim.radii, r0 * 1.2, rtol=1e-12)
    k = sim.kinetic_energy()
    sim.rescale_velocities(0.5)
    assert sim.kinetic_energy() == pytest.approx(0.25 * k, rel=1e-12)
    sim.stop_growth()
    sim.run_until(4.0)
    np.testing.assert_allclose(sim.radii, r0 * 1.2, rtol=1e-12)


def test_bad_packings_are_refused():
    with pytest.raises(ValueError, match="growth rate"):
        ccdsim.packing.pack(dim=2, n=20, rate=0.0)
    with pytest.raises(ValueError, match="not both"):
        ccdsim.packing.pack(dim=2, n=20, bidisperse=1.4, polydisperse=0.1)
    with pytest.raises(ValueError, match="dim"):
        ccdsim.packing.pack(dim=4, n=20)
    scene = ccdsim.generate.gas(n=10, packing=0.1, periodic=True, seed=1)
    scene["settings"]["growth"] = {"rate": -1}
    with pytest.raises(ValueError, match="settings.growth.rate"):
        ccdsim.Simulation(scene)
