"""Reference shots from pooltool 0.3.3 for ccdsim's billiards engine.

Writes JSON to stdout: pooltool's default pocket table (its linear cushion segments, circular
jaws and pockets) and 100 simple shots on it, seeded: 50 with the cue ball alone (it runs off
the cushions, sometimes into a pocket) and 50 with the cue ball sent onto one object ball
(straight or cut). For each shot: where the balls start, the cue strike (V0, phi, theta, a, b)
and every event pooltool's `simulate` gives (type, agents, time), with the balls' final
positions and states; and the same shot played again with pooltool's separation after a
collision (`constants.EPS_SPACE`: it moves touching balls, or a ball and a cushion, 10^-9 m
apart before resolving) a hundred times smaller, 10^-11 m. Where a time depends on that
nudge (a slow ball meeting a cushion at a grazing angle), the second run shows which way
the exact answer lies. ccdsim's test `billiards_vs_pooltool` (crates/ccdsim/tests/suite/)
plays the same shots and compares. Run by scripts/pooltool-reference, which installs pooltool
into a virtualenv of its own.
"""

import json
import sys

import numpy as np
import pooltool as pt
import pooltool.constants as const

# pooltool's own separation after a collision, and the finer one of the second run.
EPS_SPACE = const.EPS_SPACE
FINE_EPS_SPACE = 1e-11


STATES = {0: "stationary", 1: "spinning", 2: "sliding", 3: "rolling", 4: "pocketed"}


def table_geometry(table):
    segs = table.cushion_segments
    return {
        "width": table.w,
        "length": table.l,
        "linear": [
            {
                "id": s.id,
                "p1": [float(s.p1[0]), float(s.p1[1])],
                "p2": [float(s.p2[0]), float(s.p2[1])],
                "height": float(s.height),
            }
            for s in segs.linear.values()
        ],
        "circular": [
            {
                "id": s.id,
                "center": [float(s.center[0]), float(s.center[1])],
                "radius": float(s.radius),
                "height": float(s.height),
            }
            for s in segs.circular.values()
        ],
        "pockets": [
            {
                "id": p.id,
                "center": [float(p.center[0]), float(p.center[1])],
                "radius": float(p.radius),
            }
            for p in table.pockets.values()
        ],
    }


def shot(table, balls, strike, eps_space=EPS_SPACE):
    # make_kiss reads the module attribute at every call.
    const.EPS_SPACE = eps_space
    system = pt.System(
        cue=pt.Cue(cue_ball_id="cue"),
        table=table,
        balls={bid: pt.Ball.create(bid, xy=xy) for bid, xy in balls.items()},
    )
    system.cue.set_state(**strike)
    pt.simulate(system, inplace=True)
    events = []
    for e in system.events:
        kind = str(e.event_type)
        if kind in ("none", "stick_ball"):
            continue
        events.append(
            {"type": kind, "agents": [a.id for a in e.agents], "time": float(e.time)}
        )
    final = {
        bid: {
            "pos": [float(b.state.rvw[0, 0]), float(b.state.rvw[0, 1])],
            "state": STATES[int(b.state.s)],
        }
        for bid, b in system.balls.items()
    }
    return events, final


def main():
    table = pt.Table.default()
    w, l = table.w, table.l
    rng = np.random.default_rng(2026)
    margin = 0.1
    out = {
        "pooltool": "0.3.3",
        "eps_space": EPS_SPACE,
        "fine_eps_space": FINE_EPS_SPACE,
        "table": table_geometry(table),
        "shots": [],
    }

    def spot():
        return (
            float(rng.uniform(margin, w - margin)),
            float(rng.uniform(margin, l - margin)),
        )

    for k in range(100):
        cue = spot()
        balls = {"cue": cue}
        theta = float(rng.choice([0.0, 0.0, 5.0, 15.0]))
        a = float(rng.uniform(-0.3, 0.3))
        b = float(rng.uniform(-0.3, 0.3))
        if k < 50:
            phi = float(rng.uniform(0.0, 360.0))
            V0 = float(rng.uniform(0.3, 4.0))
        else:
            while True:
                obj = spot()
                if np.hypot(obj[0] - cue[0], obj[1] - cue[1]) > 0.2:
                    break
            balls["1"] = obj
            system = pt.System(
                cue=pt.Cue(cue_ball_id="cue"),
                table=table,
                balls={bid: pt.Ball.create(bid, xy=xy) for bid, xy in balls.items()},
            )
            cut = float(rng.uniform(-40.0, 40.0))
            phi = float(pt.aim.at_ball(system, "1", cut=cut))
            V0 = float(rng.uniform(0.5, 4.0))
        strike = {"V0": V0, "phi": phi, "theta": theta, "a": a, "b": b}
        events, final = shot(table, balls, strike)
        fine, _ = shot(table, balls, strike, FINE_EPS_SPACE)
        out["shots"].append(
            {
                "balls": {bid: list(xy) for bid, xy in balls.items()},
                "strike": strike,
                "events": events,
                "final": final,
                "fine_gap_events": fine,
            }
        )
    json.dump(out, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
