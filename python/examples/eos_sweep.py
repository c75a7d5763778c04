"""An equation-of-state sweep of hard discs on Dask, against the CLI's benchmark figures.

Every (packing, seed) pair is one task on a ``dask.distributed`` cluster (a LocalCluster here;
pass ``--scheduler tcp://host:8786`` for a real one). The table gives Z with its standard error
over seeds, the Henderson equation, and the figure of ``ccdsim bench gas`` where the repository
has one (bench/results/amd-epyc-2vcpu/gas/eos-2d-*.json, N = 10^4, 4 x 10^7 collisions).

    python python/examples/eos_sweep.py --n 10000 --seeds 8 --collisions 2000000 --out eos.png
"""

import argparse
import json
import math
from pathlib import Path

from dask.distributed import Client, LocalCluster

from ccdsim.ensemble import eos_sweep, format_table, plot_table

ROOT = Path(__file__).resolve().parents[2]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--packings", type=float, nargs="+", default=[0.1, 0.2, 0.3, 0.4, 0.5])
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--equilibrate", type=int, default=50_000)
    ap.add_argument("--collisions", type=int, default=200_000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler")
    ap.add_argument("--out", type=Path, default=Path("eos.png"))
    args = ap.parse_args()

    if args.scheduler:
        cluster, client = None, Client(args.scheduler)
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1,
                               dashboard_address=None)
        client = Client(cluster)
    try:
        table = eos_sweep(client, args.packings, range(args.seeds), dim=2, n=args.n,
                          equilibrate=args.equilibrate, collisions=args.collisions,
                          progress=True)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    print()
    print(format_table(table))
    for row in table:
        cli_file = ROOT / f"bench/results/amd-epyc-2vcpu/gas/eos-2d-{row['packing']}.json"
        if cli_file.exists():
            cli = json.loads(cli_file.read_text())
            sigma = math.hypot(row["Z_error"], cli["compressibility_error"])
            print(f"packing {row['packing']}: CLI Z = {cli['compressibility']:.5f} "
                  f"± {cli['compressibility_error']:.5f}; sweep differs by "
                  f"{(row['Z'] - cli['compressibility']) / sigma:+.2f} sigma")
    plot_table(table, str(args.out), dim=2)
    print(f"plot written to {args.out}")


if __name__ == "__main__":
    main()
