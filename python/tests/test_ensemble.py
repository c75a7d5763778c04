"""An equation-of-state sweep as tasks on dask.distributed (a LocalCluster of two worker
processes): the tasks are deterministic, agree with the ccdsim binary, and reproduce the
CLI's benchmark figures for Z within their error bars."""

import json
import math
import subprocess
from pathlib import Path

import pytest
from dask.distributed import Client, LocalCluster

import ccdsim
from ccdsim.ensemble import eos_point, eos_sweep, format_table, plot_table, reference_z

ROOT = Path(__file__).resolve().parents[2]
CLI_FIGURES = ROOT / "bench/results/amd-epyc-2vcpu/gas"


@pytest.fixture(scope="module")
def client():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as c:
        yield c


def test_sweep_reproduces_the_cli_figures(client, tmp_path):
    table = eos_sweep(client, packings=[0.3, 0.5], seeds=range(8), dim=2, n=1000,
                      equilibrate=50_000, collisions=400_000)
    print(format_table(table))
    assert [row["packing"] for row in table] == [0.3, 0.5]
    for row in table:
        cli = json.loads((CLI_FIGURES / f"eos-2d-{row['packing']}.json").read_text())
        sigma = math.hypot(row["Z_error"], cli["compressibility_error"])
        assert row["runs"] == 8
        assert 0 < row["Z_error"] < 0.01
        assert abs(row["Z"] - cli["compressibility"]) < 3 * sigma, (row, cli["compressibility"])
        # And the reference equation of state within a percent.
        assert row["Z"] == pytest.approx(reference_z(2, row["packing"]), rel=1e-2)
    plot_table(table, str(tmp_path / "eos.png"))
    assert (tmp_path / "eos.png").stat().st_size > 1000


def test_a_task_on_a_worker_equals_the_same_run_here(client):
    args = (2, 500, 0.4, 7, 10_000, 50_000)
    assert client.submit(eos_point, *args, pure=False).result() == eos_point(*args)


def test_a_task_agrees_with_the_binary(ccdsim_binary, tmp_path):
    # Measured from the start (no equilibration), the task's Z is the run summary's Z.
    point = eos_point(2, 400, 0.35, 3, 0, 40_000)
    scene = ccdsim.generate.gas(n=400, packing=0.35, dim=2, periodic=True, lattice=True,
                                temperature=1.0, seed=3)
    scene_file = tmp_path / "gas.json"
    scene_file.write_text(json.dumps(scene))
    out = subprocess.run([str(ccdsim_binary), "run", str(scene_file), "--events", "40000",
                          "--json", "--quiet"], capture_output=True, text=True, check=True)
    summary = json.loads(out.stdout)
    assert summary["events"] == point["events"] == 40_000
    assert point["Z"] == pytest.approx(summary["compressibility"], rel=1e-12)


def test_one_seed_has_no_error_bar(client):
    with pytest.raises(ValueError, match="two seeds"):
        eos_sweep(client, packings=[0.3], seeds=[1])
