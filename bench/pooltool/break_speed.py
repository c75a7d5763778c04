"""Times pooltool 0.3.3 on a 9-ball break and writes the break as a layout for ccdsim.

Racks the nine balls with pooltool's own `get_rack` (seeded), strikes the cue ball straight at
the 1 ball (centre, level cue, `--speed` m/s), plays it once to let numba compile, then times
`--runs` further plays of the same break (`simulate` on a fresh copy; wall time) and writes
JSON: the balls, the strike, pooltool's events and its median, fastest and slowest seconds
per break. `ccdsim bench pool-break --layout FILE` plays the identical break and prints the
ratio. Run by scripts/pool-break-compare, which installs pooltool into a virtualenv of its own.
"""

import argparse
import json
import statistics
import sys
import random
import time

import numpy as np
import pooltool as pt
from pooltool.game.datatypes import GameType
from pooltool.layouts import get_rack


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--speed", type=float, default=8.0)
    ap.add_argument("--runs", type=int, default=20)
    args = ap.parse_args()

    table = pt.Table.default()
    # get_rack takes no seed: its random offsets and ball choices come from Python's and
    # numpy's global generators.
    random.seed(args.seed)
    np.random.seed(args.seed)
    balls = get_rack(GameType.NINEBALL, table)
    system = pt.System(cue=pt.Cue(cue_ball_id="cue"), table=table, balls=balls)
    phi = float(pt.aim.at_ball(system, "1"))
    strike = {"V0": args.speed, "phi": phi, "theta": 0.0, "a": 0.0, "b": 0.0}
    system.cue.set_state(**strike)

    played = pt.simulate(system)  # numba compiles here
    times = []
    for _ in range(args.runs):
        fresh = system.copy()
        start = time.perf_counter()
        pt.simulate(fresh, inplace=True)
        times.append(time.perf_counter() - start)

    events = [
        {"type": str(e.event_type), "agents": [a.id for a in e.agents], "time": float(e.time)}
        for e in played.events
        if str(e.event_type) not in ("none", "stick_ball")
    ]
    out = {
        "balls": {
            bid: [float(b.state.rvw[0, 0]), float(b.state.rvw[0, 1])]
            for bid, b in system.balls.items()
        },
        "strike": strike,
        "pooltool": {
            "version": "0.3.3",
            "runs": args.runs,
            "median_seconds": statistics.median(times),
            "min_seconds": min(times),
            "max_seconds": max(times),
            "events": events,
            "pocketed": [
                bid for bid, b in played.balls.items() if int(b.state.s) == 4
            ],
        },
    }
    json.dump(out, sys.stdout, indent=1)
    sys.stdout.write("\n")
    print(
        f"pooltool {len(events)} events, median {statistics.median(times) * 1e3:.1f} ms "
        f"per break over {args.runs} runs",
        file=sys.stderr,
    )


if __name__ == "__main__":
    main()
