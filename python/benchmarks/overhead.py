"""Python overhead against the ccdsim binary: the same scene, the same number of collisions,
run through the package (`Simulation.run_events`, the loop in Rust without the GIL) and through
`ccdsim run --events N --json`, alternated, medians of wall seconds.

Usage: python python/benchmarks/overhead.py [--events 10000000] [--rounds 3] [--bin PATH]
(the binary defaults to the release build in cargo's target directory).
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import ccdsim

ROOT = Path(__file__).resolve().parents[2]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--events", type=int, default=10_000_000)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--bin", type=Path, default=None)
    args = ap.parse_args()
    binary = args.bin
    if binary is None:
        target = subprocess.run(
            [str(ROOT / "scripts/target-dir")], capture_output=True, text=True, check=True
        ).stdout.strip()
        binary = Path(target) / "release" / "ccdsim"
    if not binary.exists():
        raise SystemExit(f"no binary at {binary}: cargo build --release -p ccdsim-cli")

    scene = ccdsim.generate.gas(
        n=10_000, packing=0.5, periodic=True, lattice=True, temperature=1.0, seed=1
    )
    with tempfile.TemporaryDirectory() as tmp:
        scene_file = Path(tmp) / "gas.json"
        scene_file.write_text(json.dumps(scene))
        py_s, cli_s = [], []
        for r in range(args.rounds):
            sim = ccdsim.Simulation(scene)
            t0 = time.perf_counter()
            done = sim.run_events(args.events)
            py_s.append(time.perf_counter() - t0)
            out = subprocess.run(
                [str(binary), "run", str(scene_file), "--finder", "cells",
                 "--events", str(args.events), "--json", "--quiet"],
                capture_output=True, text=True, check=True,
            )
            summary = json.loads(out.stdout)
            cli_s.append(summary["wall_seconds"])
            assert summary["events"] == done, (summary["events"], done)
            print(f"round {r + 1}: python {py_s[-1]:.3f} s, cli {cli_s[-1]:.3f} s "
                  f"({done} events)")
    py, cli = statistics.median(py_s), statistics.median(cli_s)
    print(f"median: python {py:.3f} s, cli {cli:.3f} s, ratio {py / cli:.3f}")


if __name__ == "__main__":
    main()
