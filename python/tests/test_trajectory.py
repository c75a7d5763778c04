"""Trajectory files from `ccdsim run --frames DT --trajectory F` and from the package, read
back by the tools scientists use: ASE for extended XYZ, the gsd package for GSD."""

import json
import subprocess

import ase.io
import gsd.hoomd
import numpy as np
import pytest

import ccdsim


def gas(dim, n=300, packing=0.3, seed=3):
    return ccdsim.generate.gas(n=n, packing=packing, dim=dim, periodic=True, lattice=True,
                               temperature=1.0, seed=seed)


def run_cli(binary, scene, tmp_path, name, *args):
    scene_file = tmp_path / "scene.json"
    scene_file.write_text(json.dumps(scene))
    out = tmp_path / name
    subprocess.run([str(binary), "run", str(scene_file), "--quiet", "--trajectory", str(out),
                    *args], check=True, capture_output=True, text=True)
    return out


@pytest.mark.parametrize("dim", [2, 3])
def test_cli_frames_read_back_with_ase_and_gsd(ccdsim_binary, tmp_path, dim):
    scene = gas(dim)
    xyz = run_cli(ccdsim_binary, scene, tmp_path, "t.xyz", "--until", "2", "--frames", "0.1")
    gsd_path = run_cli(ccdsim_binary, scene, tmp_path, "t.gsd", "--until", "2", "--frames",
                       "0.1")
    # The same frames through the package, in full precision.
    sim = ccdsim.Simulation(scene)
    frames = list(sim.frames(every=0.1, until=2.0))
    assert len(frames) == 21
    box = np.asarray(scene["periodic"])

    atoms = ase.io.read(xyz, index=":")
    assert len(atoms) == 21
    for a, f in zip(atoms, frames):
        assert a.info["Time"] == pytest.approx(f.time, abs=0)
        assert len(a) == len(scene["bodies"])
        np.testing.assert_array_equal(a.positions[:, :dim], f.positions)
        np.testing.assert_array_equal(a.arrays["velo"][:, :dim], f.velocities)
        np.testing.assert_array_equal(a.arrays["image"][:, :dim], f.images)
        np.testing.assert_array_equal(np.diag(a.cell.array)[:dim], box)
        assert list(a.pbc) == [True] * dim + [False] * (3 - dim)
        np.testing.assert_array_equal(a.arrays["radius"], 0.5)
    # Bodies cross the box in two seconds at kT = 1: images are exercised.
    assert np.abs(frames[-1].images).max() >= 1

    with gsd.hoomd.open(gsd_path, "r") as traj:
        assert len(traj) == 21
        for k, (g, f) in enumerate(zip(traj, frames)):
            assert g.configuration.step == k
            assert g.configuration.dimensions == dim
            np.testing.assert_allclose(g.configuration.box[:dim], box, rtol=1e-7)
            assert g.log["time"][0] == f.time
            assert g.particles.N == len(scene["bodies"])
            # The HOOMD box is centred on the origin; arrays are float32.
            np.testing.assert_allclose(g.particles.position[:, :dim] + box / 2, f.positions,
                                       atol=1e-5 * box.max())
            np.testing.assert_allclose(g.particles.velocity[:, :dim], f.velocities, rtol=1e-6,
                                       atol=1e-6)
            np.testing.assert_array_equal(g.particles.image[:, :dim], f.images)
            np.testing.assert_allclose(g.particles.diameter, 1.0)
        np.testing.assert_array_equal(traj[0].log["particles/id"], np.arange(len(frames[0].positions)))


def test_package_and_cli_write_identical_files(ccdsim_binary, tmp_path):
    scene = gas(2, n=100)
    for name in ("a.xyz", "a.gsd"):
        cli = run_cli(ccdsim_binary, scene, tmp_path, name, "--until", "1", "--frames", "0.25")
        mine = tmp_path / ("py-" + name)
        assert ccdsim.Simulation(scene).write_trajectory(str(mine), every=0.25, until=1.0) == 5
        assert mine.read_bytes() == cli.read_bytes()


def test_a_walled_box_writes_its_bounds(ccdsim_binary, tmp_path):
    scene = ccdsim.generate.gas(n=50, packing=0.2, seed=1)  # walls, no periodic box
    xyz = run_cli(ccdsim_binary, scene, tmp_path, "w.xyz", "--until", "1", "--frames", "0.5")
    atoms = ase.io.read(xyz, index=":")
    assert len(atoms) == 3
    assert not any(atoms[0].pbc)
    xs = [p for w in scene["walls"] for p in (w.get("a"), w.get("b")) if p]
    assert atoms[0].cell.array[0, 0] == pytest.approx(max(p[0] for p in xs) - min(p[0] for p in xs))


@pytest.mark.parametrize(
    "args, message",
    [
        (["--frames", "0", "--trajectory", "t.xyz"], "positive"),
        (["--frames", "0.1", "--trajectory", "t.dcd"], "trajectory format"),
        (["--frames", "0.1", "--trajectory", "t.xyz", "--events", "10"], "cannot be used"),
        (["--frames", "0.1"], "--trajectory"),
    ],
)
def test_bad_frame_requests_are_refused(ccdsim_binary, tmp_path, args, message):
    scene_file = tmp_path / "scene.json"
    scene_file.write_text(json.dumps(gas(2, n=50)))
    args = [str(tmp_path / a) if a.startswith("t.") else a for a in args]
    out = subprocess.run([str(ccdsim_binary), "run", str(scene_file), "--quiet", *args],
                         capture_output=True, text=True)
    assert out.returncode != 0
    assert message in out.stderr
    assert not (tmp_path / "t.xyz").exists()
