"""The examples run as documented and print what they promise."""

import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def test_quickstart_runs_and_finds_the_physics(tmp_path):
    out = subprocess.run([sys.executable, str(EXAMPLES / "quickstart.py"), "--out", str(tmp_path)],
                         capture_output=True, text=True, check=True).stdout
    assert "contact peak" in out and "Z = " in out
    assert (tmp_path / "quickstart.png").stat().st_size > 10_000
    assert (tmp_path / "quickstart.gsd").stat().st_size > 10_000
    z, henderson = [float(x) for x in
                    out.split("Z = ")[1].split(")")[0].replace("(Henderson", "").split()]
    assert abs(z - henderson) < 0.02 * henderson
    d = out.split("diffusion coefficient: ")[1].split()
    assert abs(float(d[0]) - float(d[2])) < 0.15 * float(d[0])  # Einstein vs Green-Kubo


def test_eos_sweep_example_runs_on_a_local_cluster(tmp_path):
    out = subprocess.run(
        [sys.executable, str(EXAMPLES / "eos_sweep.py"), "--packings", "0.3", "0.5",
         "--seeds", "3", "--n", "500", "--collisions", "100000", "--out",
         str(tmp_path / "eos.png")],
        capture_output=True, text=True, check=True).stdout
    assert "packing 0.3: CLI Z = 2.06316" in out
    assert (tmp_path / "eos.png").exists()
